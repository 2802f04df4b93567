#include "fields/modbus_fields.h"

#include <epan/tfs.h>

#include <string>

#include "fields/field_list.h"
#include "fields/value_tables.h"
#include "pvtap/codec/device_identification.h"
#include "pvtap/codec/function_codes.h"

namespace pvtap::dissector {
namespace {

// Names: the value names a line of PVTAP_MODBUS_FIELDS shows.
enum class Names : std::uint8_t { None, Diagnostics, ReadCode, Object, Dialect, OnOff };

// ModbusFieldSpec: a line of PVTAP_MODBUS_FIELDS.
struct ModbusFieldSpec {
  ModbusField id;
  const char* name;
  const char* abbrev;
  ftenum type;
  int display;
  Names names;
  const char* blurb;
};

#define PVTAP_MODBUS_ROW(id, name, abbrev, type, display, names, blurb) \
  {ModbusField::id, name, abbrev, type, display, Names::names, blurb},
constexpr ModbusFieldSpec kFields[] = {PVTAP_MODBUS_FIELDS(PVTAP_MODBUS_ROW)};
#undef PVTAP_MODBUS_ROW

constexpr ExpertRow kExperts[] = {PVTAP_MODBUS_EXPERTS(PVTAP_EXPERT_ROW)};

const value_string* diagnostics_names() {
  static const value_string* names = [] {
    std::vector<std::pair<std::uint32_t, std::string>> entries;
    for (unsigned sub = 0; sub <= 0xFF; ++sub) {
      const std::string_view name = fc::diagnostics_name(static_cast<std::uint16_t>(sub));
      if (!name.empty()) entries.emplace_back(sub, std::string(name));
    }
    return persist_value_strings(entries);
  }();
  return names;
}

const value_string* object_names() {
  static const value_string* names = [] {
    std::vector<std::pair<std::uint32_t, std::string>> entries;
    for (unsigned id = 0; id <= 0x06; ++id) {
      entries.emplace_back(id, std::string(device_object_name(static_cast<std::uint8_t>(id))));
    }
    return persist_value_strings(entries);
  }();
  return names;
}

const value_string kReadCodes[] = {
    {1, "basic"}, {2, "regular"}, {3, "extended"}, {4, "one object"}, {0, nullptr}};

const void* strings_of(Names names) {
  switch (names) {
    case Names::Diagnostics:
      return diagnostics_names();
    case Names::ReadCode:
      return kReadCodes;
    case Names::Object:
      return object_names();
    case Names::Dialect:
      return dialect_names();
    case Names::OnOff:
      return &tfs_on_off;
    case Names::None:
      break;
  }
  return nullptr;
}

void register_fields(InverterProtocol& p) {
  FieldList list;
  const std::string prefix = std::string(p.filter_name) + ".";
  for (const ModbusFieldSpec& f : kFields) {
    list.add(&p.hf.modbus[static_cast<std::size_t>(f.id)], f.name, prefix + f.abbrev, f.type,
             f.display, strings_of(f.names), 0, f.blurb != nullptr ? f.blurb : "");
  }
  list.register_all(p.proto);
}

void register_experts(InverterProtocol& p) {
  const std::string prefix = std::string(p.filter_name) + ".";
  ExpertList experts;
  for (const ExpertRow& e : kExperts) {
    experts.add(p.ei.of(e.id), prefix + e.abbrev, e.group, e.severity, e.summary);
  }
  experts.register_all(p.proto);
}

}  // namespace

void register_modbus_items(InverterProtocol& p) {
  register_fields(p);
  register_experts(p);
}

}  // namespace pvtap::dissector
