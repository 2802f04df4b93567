#include "fields/register_fields.h"

#include <epan/proto.h>

#include <functional>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "fields/field_list.h"
#include "fields/register_field_type.h"
#include "fields/value_tables.h"
#include "protocol/inverter_protocol.h"
#include "settings/register_maps.h"

namespace pvtap::dissector {
namespace {

// The fields of one dialect, indexed like the registers of its effective map.
struct DialectFields {
  const RegisterDef* first = nullptr;
  std::size_t count = 0;
  std::unique_ptr<RegisterField[]> fields;
};

std::array<DialectFields, kDialectCount> g_fields;

// Common field names of invascii that a map key must not shadow.
const std::set<std::string_view> kReservedAsciiKeys = {
    "dialect",          "role",       "station",        "function",      "start",         "count",
    "byte_count",       "device",     "exception_code", "word",          "checksum",      "noise",
    "unknown_function", "request_in", "response_in",    "response_time", "expected_count"};

bool shows_several(DialectSet dialects) {
  unsigned n = 0;
  for (const Dialect d : kAllDialects) n += dialects.contains(d) ? 1u : 0u;
  return n > 1;
}

// A protocol that shows several dialects gives each its segment ("invrtu.gsl."); one that shows
// a single dialect needs none, but a key that would shadow one of its common fields goes under
// "register." ("invascii.register.word").
std::string field_prefix(Dialect d, std::string_view key) {
  const InverterProtocol& p = protocol_of(d);
  const std::string protocol = std::string(p.filter_name) + ".";
  if (shows_several(p.dialects)) return protocol + std::string(to_string(d)) + ".";
  return kReservedAsciiKeys.contains(key) ? protocol + "register." : protocol;
}

// The type the tree description gives the entry's item.
ftenum field_type(const RegisterDef& def) {
  switch (register_field_type(def)) {
    case RegisterFieldType::Uint16:
      return FT_UINT16;
    case RegisterFieldType::Uint32:
      return FT_UINT32;
    case RegisterFieldType::Double:
      return FT_DOUBLE;
    case RegisterFieldType::String:
      return FT_STRING;
  }
  return FT_NONE;
}

int field_display(const RegisterDef& def, ftenum type) {
  if (type == FT_DOUBLE || type == FT_STRING) return BASE_NONE;
  return def.kind == RegisterKind::Enum ? BASE_DEC : BASE_HEX;
}

// Filter-name form of a flag's name: "PV over-voltage" -> "pv_over_voltage".
std::string slug_of(std::string_view name) {
  std::string out;
  for (char c : name) {
    const bool alnum = (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9');
    if (c >= 'A' && c <= 'Z') {
      out += static_cast<char>(c - 'A' + 'a');
    } else if (alnum) {
      out += c;
    } else if (!out.empty() && out.back() != '_') {
      out += '_';
    }
  }
  while (!out.empty() && out.back() == '_') out.pop_back();
  if (!out.empty() && out.front() >= '0' && out.front() <= '9') out.insert(0, "bit_");
  return out;
}

std::string blurb_of(Dialect d, const RegisterDef& def) {
  std::string text = std::string(to_string(d)) + " register " +
                     std::string(format_register_address(d, def.address).view());
  if (def.is_range()) {
    const auto last = static_cast<std::uint16_t>(def.address + (def.repeat - 1) * address_step(d));
    text += " .. " + std::string(format_register_address(d, last).view());
  }
  if (!def.unit.empty()) text += ", " + std::string(def.unit);
  return text;
}

void add_bit_fields(const RegisterDef& def, const std::string& abbrev, RegisterField& field,
                    FieldList& list) {
  std::set<std::string> used;
  for (const BitName& bit : def.bits) {
    if (bit.index >= field.bits.size() || bit.name.empty()) continue;
    std::string slug = slug_of(bit.name);
    if (slug.empty() || used.contains(slug)) slug += "_bit" + std::to_string(bit.index);
    used.insert(slug);
    list.add(&field.bits[bit.index], std::string(bit.name), abbrev + "." + slug, FT_BOOLEAN, 16,
             nullptr, std::uint64_t{1} << bit.index, "flag of " + std::string(def.name));
  }
}

void add_register_field(Dialect d, const RegisterDef& def, RegisterField& field, FieldList& list) {
  field.type = field_type(def);
  const std::string abbrev = field_prefix(d, def.key) + std::string(def.key);
  const bool named_values = def.kind == RegisterKind::Enum;
  list.add(&field.hf, std::string(def.name), abbrev, field.type, field_display(def, field.type),
           named_values ? register_value_names(def) : nullptr, 0, blurb_of(d, def));
  if (def.kind == RegisterKind::Bits) add_bit_fields(def, abbrev, field, list);
}

void register_subtrees(DialectFields& fields) {
  std::vector<gint*> etts;
  for (std::size_t i = 0; i < fields.count; ++i) {
    if (fields.first[i].kind == RegisterKind::Bits) etts.push_back(&fields.fields[i].ett);
  }
  if (etts.empty()) return;
  auto* persistent = g_new(gint*, etts.size());
  std::copy(etts.begin(), etts.end(), persistent);
  proto_register_subtree_array(persistent, static_cast<int>(etts.size()));
}

}  // namespace

void register_register_fields(int proto, Dialect d) {
  const auto registers = effective_map(d).registers();
  DialectFields& fields = g_fields[static_cast<std::size_t>(d)];
  fields.first = registers.data();
  fields.count = registers.size();
  fields.fields = std::make_unique<RegisterField[]>(registers.size());
  FieldList list;
  for (std::size_t i = 0; i < registers.size(); ++i) {
    add_register_field(d, registers[i], fields.fields[i], list);
  }
  list.register_all(proto);
  register_subtrees(fields);
}

const RegisterField* register_field(Dialect d, const RegisterDef* def) {
  const DialectFields& fields = g_fields[static_cast<std::size_t>(d)];
  const std::less<const RegisterDef*> before;
  if (def == nullptr || fields.first == nullptr || before(def, fields.first) ||
      !before(def, fields.first + fields.count)) {
    return nullptr;
  }
  return &fields.fields[static_cast<std::size_t>(def - fields.first)];
}

}  // namespace pvtap::dissector
