#include "fields/modbus_fields.h"

#include <epan/tfs.h>

#include <string>

#include "fields/field_list.h"
#include "fields/value_tables.h"
#include "pvtap/codec/device_identification.h"
#include "pvtap/codec/function_codes.h"

namespace pvtap::dissector {
namespace {

// Which value names a field shows.
enum class Names : std::uint8_t { None, Diagnostics, ReadCode, Object, Dialect, OnOff };

// ModbusFieldSpec: one field, in ModbusField order; names relative to the protocol's.
struct ModbusFieldSpec {
  ModbusField field;
  const char* name;
  const char* abbrev;
  ftenum type;
  int display;
  Names names;
  const char* blurb;
};

constexpr ModbusFieldSpec kFields[] = {
    {ModbusField::SubFunction, "Diagnostics sub-function", "diagnostics.sub_function", FT_UINT16,
     BASE_HEX, Names::Diagnostics, nullptr},
    {ModbusField::DiagnosticsData, "Diagnostics data", "diagnostics.data", FT_UINT16, BASE_HEX,
     Names::None, nullptr},
    {ModbusField::DiagnosticsBytes, "Diagnostics data bytes", "diagnostics.bytes", FT_BYTES,
     BASE_NONE, Names::None, nullptr},
    {ModbusField::WriteStart, "Write start address", "write_start", FT_UINT16, BASE_HEX,
     Names::None, "0x17: the first register written"},
    {ModbusField::WriteCount, "Write register count", "write_count", FT_UINT16, BASE_DEC,
     Names::None, "0x17: how many registers are written"},
    {ModbusField::AndMask, "AND mask", "and_mask", FT_UINT16, BASE_HEX, Names::None, nullptr},
    {ModbusField::OrMask, "OR mask", "or_mask", FT_UINT16, BASE_HEX, Names::None, nullptr},
    {ModbusField::FifoCount, "FIFO count", "fifo.count", FT_UINT16, BASE_DEC, Names::None, nullptr},
    {ModbusField::FifoValue, "FIFO value", "fifo.value", FT_UINT16, BASE_HEX, Names::None, nullptr},
    {ModbusField::ExceptionStatus, "Exception status", "exception_status", FT_UINT8, BASE_HEX,
     Names::None, "0x07: eight device-specific status bits"},
    {ModbusField::EventStatus, "Event status", "event.status", FT_UINT16, BASE_HEX, Names::None,
     nullptr},
    {ModbusField::EventCount, "Event count", "event.count", FT_UINT16, BASE_DEC, Names::None,
     nullptr},
    {ModbusField::EventLog, "Event log", "event.log", FT_BYTES, BASE_NONE, Names::None, nullptr},
    {ModbusField::FileRecords, "File records", "file_records", FT_BYTES, BASE_NONE, Names::None,
     "0x14/0x15: sub-requests or records, as bytes"},
    {ModbusField::MeiType, "MEI type", "mei_type", FT_UINT8, BASE_HEX, Names::None, nullptr},
    {ModbusField::ReadCode, "Read device ID code", "device_id.read_code", FT_UINT8, BASE_DEC,
     Names::ReadCode, nullptr},
    {ModbusField::Conformity, "Conformity level", "device_id.conformity", FT_UINT8, BASE_HEX,
     Names::None, nullptr},
    {ModbusField::MoreFollows, "More follows", "device_id.more_follows", FT_UINT8, BASE_HEX,
     Names::None, nullptr},
    {ModbusField::NextObject, "Next object", "device_id.next_object", FT_UINT8, BASE_HEX,
     Names::None, nullptr},
    {ModbusField::ObjectCount, "Number of objects", "device_id.object_count", FT_UINT8, BASE_DEC,
     Names::None, nullptr},
    {ModbusField::Object, "Object id", "device_id.object", FT_UINT8, BASE_HEX, Names::Object,
     nullptr},
    {ModbusField::Vendor, "Vendor name", "device_id.vendor", FT_STRING, BASE_NONE, Names::None,
     nullptr},
    {ModbusField::Product, "Product code", "device_id.product", FT_STRING, BASE_NONE, Names::None,
     nullptr},
    {ModbusField::Revision, "Revision", "device_id.revision", FT_STRING, BASE_NONE, Names::None,
     nullptr},
    {ModbusField::ObjectValue, "Object value", "device_id.value", FT_STRING, BASE_NONE, Names::None,
     "Device identification objects other than vendor, product and revision"},
    {ModbusField::ServerId, "Server ID text", "server_id.text", FT_STRING, BASE_NONE, Names::None,
     "0x11: the longest run of printable characters, which names most devices"},
    {ModbusField::ServerData, "Server ID data", "server_id.data", FT_BYTES, BASE_NONE, Names::None,
     nullptr},
    {ModbusField::Coils, "Bits", "bits", FT_BYTES, BASE_NONE, Names::None,
     "The bytes of coils or discrete inputs"},
    {ModbusField::CoilAddress, "Coil", "coil.address", FT_UINT16, BASE_DEC, Names::None, nullptr},
    {ModbusField::CoilState, "Coil state", "coil.state", FT_BOOLEAN, BASE_NONE, Names::OnOff,
     nullptr},
    {ModbusField::InputAddress, "Discrete input", "input.address", FT_UINT16, BASE_DEC, Names::None,
     nullptr},
    {ModbusField::InputState, "Discrete input state", "input.state", FT_BOOLEAN, BASE_NONE,
     Names::OnOff, nullptr},
    {ModbusField::StationName, "Station name", "station_name", FT_STRING, BASE_NONE, Names::None,
     "What the station said of itself (device identification or report server ID)"},
    {ModbusField::PreviousDialect, "Previous dialect", "previous_dialect", FT_UINT8, BASE_DEC,
     Names::Dialect, "The dialect the station spoke until this frame"},
    {ModbusField::QuantityMin, "Smallest quantity allowed", "quantity.min", FT_UINT16, BASE_DEC,
     Names::None, nullptr},
    {ModbusField::QuantityMax, "Largest quantity allowed", "quantity.max", FT_UINT16, BASE_DEC,
     Names::None, nullptr},
    {ModbusField::MapValue, "Station map value", "map_value", FT_STRING, BASE_NONE, Names::None,
     "A value of a station's own register map (preference Station register maps): its name "
     "and value, \"voltage phase 1: 230.1 V\""},
    {ModbusField::MapKey, "Station map key", "map_key", FT_STRING, BASE_NONE, Names::None,
     "The key of the station map's entry the value belongs to"},
    {ModbusField::MapNumber, "Station map number", "map_number", FT_DOUBLE, BASE_NONE, Names::None,
     "The value of a numeric station map entry, scaled, as shown"},
};
static_assert(std::size(kFields) == kModbusFieldCount);

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
    list.add(&p.hf.modbus[static_cast<std::size_t>(f.field)], f.name, prefix + f.abbrev, f.type,
             f.display, strings_of(f.names), 0, f.blurb != nullptr ? f.blurb : "");
  }
  list.register_all(p.proto);
}

void register_experts(InverterProtocol& p) {
  const std::string prefix = std::string(p.filter_name) + ".";
  ExpertList experts;
  experts.add(&p.ei.quantity_problem, prefix + "quantity_out_of_range", PI_PROTOCOL, PI_WARN,
              "Request quantity out of the specification's range");
  experts.add(&p.ei.dialect_changed, prefix + "dialect_changed", PI_SEQUENCE, PI_NOTE,
              "Station changed dialect");
  experts.add(&p.ei.broadcast_not_allowed, prefix + "broadcast_not_allowed", PI_PROTOCOL, PI_WARN,
              "Broadcast to address 0, which only writes may use");
  experts.add(&p.ei.write_count_problem, prefix + "write_count_mismatch", PI_PROTOCOL, PI_WARN,
              "Byte count disagrees with the quantity written");
  experts.register_all(p.proto);
}

}  // namespace

void register_modbus_items(InverterProtocol& p) {
  for (std::size_t i = 0; i < kModbusFieldCount; ++i) {
    if (kFields[i].field != static_cast<ModbusField>(i)) return;  // the table is out of order
  }
  register_fields(p);
  register_experts(p);
  gint* etts[] = {&p.ett.coils, &p.ett.coil, &p.ett.device_object, &p.ett.map_entry};
  proto_register_subtree_array(etts, G_N_ELEMENTS(etts));
}

}  // namespace pvtap::dissector
