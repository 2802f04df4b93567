// The fields, expert infos and subtrees of invrtu and invascii, one line each, and their ids.
#pragma once

#include <cstddef>
#include <cstdint>

// Each table is a list of X(...) lines: the tree names a field by its id, and the plugin
// registers it from the same line, so that adding one is one line. The columns after the id
// are Wireshark's (FT_*, BASE_*, PI_*) and only fields/ expands them: the plan and the tree
// description, built without Wireshark, take the ids alone. The lines are registered in
// their order, which is the order `tshark -G fields` lists them in.
//
// Abbrevs are relative to the protocol's filter name. In names and summaries {Check} is the
// protocol's name for its check ("CRC", "Checksum") and {check} its word for it in a sentence
// ("CRC", "checksum"); in abbrevs {check} is its key ("crc", "checksum").

// The fields a frame of any dialect may carry:
// X(id, name, abbrev, type, display, value names, protocols, blurb). Protocols: All, or Rtu
// for the protocol of the binary dialects only. Value names: see fields/common_fields.cpp.
#define PVTAP_FRAME_FIELDS(X)                                                                    \
  X(Station, "Station", "station", FT_UINT8, BASE_DEC, None, All, "Address of the inverter")     \
  X(Start, "Start address", "start", FT_UINT16, BASE_HEX, None, All,                             \
    "Wire address of the first register")                                                        \
  X(Count, "Register count", "count", FT_UINT16, BASE_DEC, None, All, nullptr)                   \
  X(ByteCount, "Byte count", "byte_count", FT_UINT8, BASE_DEC, None, Rtu, nullptr)               \
  X(Device, "Device number", "device", FT_UINT32, BASE_HEX, None, Rtu,                           \
    "Hybrid device number: type code and serial number")                                         \
  X(DeviceSerial, "Device serial number", "device.serial", FT_UINT24, BASE_DEC, None, Rtu,       \
    nullptr)                                                                                     \
  X(ErrorBody, "Error reply body", "error_body", FT_UINT32, BASE_HEX, None, Rtu,                 \
    "The fixed body of a Hybrid error reply (0x1000 0x00FF), not a register range")              \
  X(Word, "Unmapped word", "word", FT_UINT16, BASE_HEX, None, All,                               \
    "A data word that no register map entry covers")                                             \
  X(Undecoded, "Data, not decoded", "undecoded", FT_BYTES, BASE_NONE, None, All,                 \
    "A frame's data or body, not decoded because its check failed or it did not parse")          \
  X(Noise, "Noise", "noise", FT_BYTES, BASE_NONE, None, All, "Bytes that belong to no frame")    \
  X(UnknownFunction, "Unknown function code", "unknown_function", FT_UINT8, BASE_HEX, None, Rtu, \
    "Function code of a frame with a good CRC that no dialect defines")                          \
  X(ResponseTime, "Response time", "response_time", FT_RELATIVE_TIME, BASE_NONE, None, All,      \
    "Time from the request to this response")                                                    \
  X(ExpectedCount, "Expected count", "expected_count", FT_UINT16, BASE_DEC, None, All,           \
    "What the request asked for (bytes; words in the ASCII dialect)")                            \
  X(Check, "{Check}", "{check}", FT_UINT16, BASE_HEX, None, All, nullptr)                        \
  X(CheckStatus, "{Check} status", "{check}.status", FT_UINT8, BASE_NONE, CheckStatus, All,      \
    nullptr)                                                                                     \
  X(CheckExpected, "Expected {check}", "{check}.expected", FT_UINT16, BASE_HEX, None, All,       \
    "The value a correct frame would carry")                                                     \
  X(RequestIn, "Request in frame", "request_in", FT_FRAMENUM, BASE_NONE, RequestFrame, All,      \
    nullptr)                                                                                     \
  X(ResponseIn, "Response in frame", "response_in", FT_FRAMENUM, BASE_NONE, ResponseFrame, All,  \
    nullptr)                                                                                     \
  X(UnansweredRequest, "Unanswered request in frame", "unanswered_request", FT_FRAMENUM,         \
    BASE_NONE, RequestFrame, All, "The request this packet's timeout announcement is about")     \
  X(TimeoutIn, "Timeout announced in frame", "timeout_in", FT_FRAMENUM, BASE_NONE, None, All,    \
    "The packet that showed that this request got no reply")                                     \
  X(Dialect, "Dialect", "dialect", FT_UINT8, BASE_DEC, Dialects, All, nullptr)                   \
  X(Role, "Role", "role", FT_UINT8, BASE_DEC, Roles, All, nullptr)                               \
  X(Function, "Function", "function", FT_UINT8, BASE_HEX, Functions, All, nullptr)               \
  X(ExceptionCode, "Exception code", "exception_code", FT_UINT8, BASE_DEC, Exceptions, Rtu,      \
    nullptr)                                                                                     \
  X(DeviceType, "Device type code", "device.type", FT_UINT8, BASE_HEX, DeviceTypes, Rtu, nullptr)

// The expert infos of every dialect: X(id, abbrev, group, severity, summary).
#define PVTAP_FRAME_EXPERTS(X)                                                                     \
  X(BadCheck, "{check}.bad", PI_CHECKSUM, PI_WARN, "Bad {check}")                                  \
  X(Malformed, "malformed", PI_MALFORMED, PI_ERROR, "Malformed frame")                             \
  X(Noise, "noise_run", PI_PROTOCOL, PI_WARN, "Bytes that belong to no frame")                     \
  X(UnknownFunction, "unknown_function_frame", PI_PROTOCOL, PI_WARN,                               \
    "Frame with an unknown function code")                                                         \
  X(Exception, "exception", PI_RESPONSE_CODE, PI_NOTE, "Exception reply")                          \
  X(Unanswered, "unanswered", PI_SEQUENCE, PI_WARN, "Request never answered")                      \
  X(Unsolicited, "unsolicited", PI_SEQUENCE, PI_WARN, "Reply with no request")                     \
  X(LateReply, "late_reply", PI_SEQUENCE, PI_WARN, "Reply after its request timed out")            \
  X(Duplicate, "duplicate", PI_SEQUENCE, PI_NOTE, "Duplicate reply")                               \
  X(AddressConflict, "address_conflict", PI_SEQUENCE, PI_WARN,                                     \
    "Address conflict: a second reply with other contents")                                        \
  X(Echo, "echo", PI_SEQUENCE, PI_NOTE, "Echo of a request: the tap's adapter repeating it")       \
  X(Collision, "collision", PI_SEQUENCE, PI_WARN,                                                  \
    "Collision: two transmissions at once on a bus of more than one master")                       \
  X(CountMismatch, "count_mismatch", PI_PROTOCOL, PI_WARN,                                         \
    "Byte count disagrees with the request")                                                       \
  X(RoleCorrected, "role_corrected", PI_SEQUENCE, PI_NOTE, "Frame is the echo of a write request") \
  X(StartUnknown, "start_unknown", PI_UNDECODED, PI_NOTE,                                          \
    "Register words without a known start address")                                                \
  X(StartAssumed, "start_assumed", PI_ASSUMPTION, PI_NOTE, "Start address assumed")                \
  X(ValueNote, "value_note", PI_PROTOCOL, PI_NOTE, "Register value note")                          \
  X(ValueSuspicious, "value_suspicious", PI_PROTOCOL, PI_WARN, "Suspicious register value")

// The fields of the plain Modbus functions and of what the bus learned of a Modbus station
// (invrtu only): X(id, name, abbrev, type, display, value names, blurb). Value names: see
// fields/modbus_fields.cpp.
#define PVTAP_MODBUS_FIELDS(X)                                                                     \
  X(SubFunction, "Diagnostics sub-function", "diagnostics.sub_function", FT_UINT16, BASE_HEX,      \
    Diagnostics, nullptr)                                                                          \
  X(DiagnosticsData, "Diagnostics data", "diagnostics.data", FT_UINT16, BASE_HEX, None, nullptr)   \
  X(DiagnosticsBytes, "Diagnostics data bytes", "diagnostics.bytes", FT_BYTES, BASE_NONE, None,    \
    nullptr)                                                                                       \
  X(WriteStart, "Write start address", "write_start", FT_UINT16, BASE_HEX, None,                   \
    "0x17: the first register written")                                                            \
  X(WriteCount, "Write register count", "write_count", FT_UINT16, BASE_DEC, None,                  \
    "0x17: how many registers are written")                                                        \
  X(AndMask, "AND mask", "and_mask", FT_UINT16, BASE_HEX, None, nullptr)                           \
  X(OrMask, "OR mask", "or_mask", FT_UINT16, BASE_HEX, None, nullptr)                              \
  X(FifoCount, "FIFO count", "fifo.count", FT_UINT16, BASE_DEC, None, nullptr)                     \
  X(FifoValue, "FIFO value", "fifo.value", FT_UINT16, BASE_HEX, None, nullptr)                     \
  X(ExceptionStatus, "Exception status", "exception_status", FT_UINT8, BASE_HEX, None,             \
    "0x07: eight device-specific status bits")                                                     \
  X(EventStatus, "Event status", "event.status", FT_UINT16, BASE_HEX, None, nullptr)               \
  X(EventCount, "Event count", "event.count", FT_UINT16, BASE_DEC, None, nullptr)                  \
  X(EventLog, "Event log", "event.log", FT_BYTES, BASE_NONE, None, nullptr)                        \
  X(FileRecords, "File records", "file_records", FT_BYTES, BASE_NONE, None,                        \
    "0x14/0x15: sub-requests or records, as bytes")                                                \
  X(MeiType, "MEI type", "mei_type", FT_UINT8, BASE_HEX, None, nullptr)                            \
  X(ReadCode, "Read device ID code", "device_id.read_code", FT_UINT8, BASE_DEC, ReadCode, nullptr) \
  X(Conformity, "Conformity level", "device_id.conformity", FT_UINT8, BASE_HEX, None, nullptr)     \
  X(MoreFollows, "More follows", "device_id.more_follows", FT_UINT8, BASE_HEX, None, nullptr)      \
  X(NextObject, "Next object", "device_id.next_object", FT_UINT8, BASE_HEX, None, nullptr)         \
  X(ObjectCount, "Number of objects", "device_id.object_count", FT_UINT8, BASE_DEC, None, nullptr) \
  X(Object, "Object id", "device_id.object", FT_UINT8, BASE_HEX, Object, nullptr)                  \
  X(Vendor, "Vendor name", "device_id.vendor", FT_STRING, BASE_NONE, None, nullptr)                \
  X(Product, "Product code", "device_id.product", FT_STRING, BASE_NONE, None, nullptr)             \
  X(Revision, "Revision", "device_id.revision", FT_STRING, BASE_NONE, None, nullptr)               \
  X(ObjectValue, "Object value", "device_id.value", FT_STRING, BASE_NONE, None,                    \
    "Device identification objects other than vendor, product and revision")                       \
  X(ServerId, "Server ID text", "server_id.text", FT_STRING, BASE_NONE, None,                      \
    "0x11: the longest run of printable characters, which names most devices")                     \
  X(ServerData, "Server ID data", "server_id.data", FT_BYTES, BASE_NONE, None, nullptr)            \
  X(Coils, "Bits", "bits", FT_BYTES, BASE_NONE, None, "The bytes of coils or discrete inputs")     \
  X(CoilAddress, "Coil", "coil.address", FT_UINT16, BASE_DEC, None, nullptr)                       \
  X(CoilState, "Coil state", "coil.state", FT_BOOLEAN, BASE_NONE, OnOff, nullptr)                  \
  X(InputAddress, "Discrete input", "input.address", FT_UINT16, BASE_DEC, None, nullptr)           \
  X(InputState, "Discrete input state", "input.state", FT_BOOLEAN, BASE_NONE, OnOff, nullptr)      \
  X(StationName, "Station name", "station_name", FT_STRING, BASE_NONE, None,                       \
    "What the station said of itself (device identification or report server ID)")                 \
  X(PreviousDialect, "Previous dialect", "previous_dialect", FT_UINT8, BASE_DEC, Dialect,          \
    "The dialect the station spoke until this frame")                                              \
  X(QuantityMin, "Smallest quantity allowed", "quantity.min", FT_UINT16, BASE_DEC, None, nullptr)  \
  X(QuantityMax, "Largest quantity allowed", "quantity.max", FT_UINT16, BASE_DEC, None, nullptr)   \
  X(MapValue, "Station map value", "map_value", FT_STRING, BASE_NONE, None,                        \
    "A value of a station's own register map (preference Station register maps): its name "        \
    "and value, \"voltage phase 1: 230.1 V\"")                                                     \
  X(MapKey, "Station map key", "map_key", FT_STRING, BASE_NONE, None,                              \
    "The key of the station map's entry the value belongs to")                                     \
  X(MapNumber, "Station map number", "map_number", FT_DOUBLE, BASE_NONE, None,                     \
    "The value of a numeric station map entry, scaled, as shown")

// The expert infos of the plain Modbus functions (invrtu only), as PVTAP_FRAME_EXPERTS.
#define PVTAP_MODBUS_EXPERTS(X)                                                         \
  X(QuantityProblem, "quantity_out_of_range", PI_PROTOCOL, PI_WARN,                     \
    "Request quantity out of the specification's range")                                \
  X(DialectChanged, "dialect_changed", PI_SEQUENCE, PI_NOTE, "Station changed dialect") \
  X(BroadcastNotAllowed, "broadcast_not_allowed", PI_PROTOCOL, PI_WARN,                 \
    "Broadcast to address 0, which only writes may use")                                \
  X(WriteCountProblem, "write_count_mismatch", PI_PROTOCOL, PI_WARN,                    \
    "Byte count disagrees with the quantity written")

// The subtrees an item may open: X(id, protocols), as PVTAP_FRAME_FIELDS.
#define PVTAP_SUBTREES(X) \
  X(Frame, All)           \
  X(Device, All)          \
  X(Noise, All)           \
  X(Coils, Rtu)           \
  X(Coil, Rtu)            \
  X(DeviceObject, Rtu)    \
  X(MapEntry, Rtu) /* a value of a station's own map: its key and number */

#define PVTAP_TABLE_ID(id, ...) id,
#define PVTAP_TABLE_ONE(...) +1

namespace pvtap::dissector {

// TreeField: the field of an item. The table's come first, so that they index the ids a
// protocol registered.
enum class TreeField : std::uint8_t {
  PVTAP_FRAME_FIELDS(PVTAP_TABLE_ID)
  // Not in the table: their ids come from elsewhere.
  None,           // an expert info's item of its own
  Protocol,       // the protocol's own item
  RegisterValue,  // the field of the map entry `def`
  RegisterFlag,   // the flag `bit` of the map entry `def`
  Modbus,         // the Modbus field `modbus`
};
inline constexpr std::size_t kFrameFieldCount = 0 PVTAP_FRAME_FIELDS(PVTAP_TABLE_ONE);

// TreeExpert: the expert info an item raises.
enum class TreeExpert : std::uint8_t {
  PVTAP_FRAME_EXPERTS(PVTAP_TABLE_ID)
  // invrtu only:
  PVTAP_MODBUS_EXPERTS(PVTAP_TABLE_ID)
  // None: an item that raises nothing.
  None,
};
inline constexpr std::size_t kExpertCount =
    0 PVTAP_FRAME_EXPERTS(PVTAP_TABLE_ONE) PVTAP_MODBUS_EXPERTS(PVTAP_TABLE_ONE);

// ModbusField: a field of the plain Modbus functions; its index is its slot in the plugin's
// registration.
enum class ModbusField : std::uint8_t { PVTAP_MODBUS_FIELDS(PVTAP_TABLE_ID) };
inline constexpr std::size_t kModbusFieldCount = 0 PVTAP_MODBUS_FIELDS(PVTAP_TABLE_ONE);

// Subtree: the subtree an item opens for the items one level deeper that follow it.
enum class Subtree : std::uint8_t {
  PVTAP_SUBTREES(PVTAP_TABLE_ID)
  // Not in the table:
  None,
  Flags,  // the flags of the map entry `def`: their subtree is the register field's
};
inline constexpr std::size_t kSubtreeCount = 0 PVTAP_SUBTREES(PVTAP_TABLE_ONE);

}  // namespace pvtap::dissector

#undef PVTAP_TABLE_ID
#undef PVTAP_TABLE_ONE
