// ModbusPlan: what the tree shows of the fields only plain Modbus functions carry.
#pragma once

#include <cstddef>
#include <cstdint>
#include <type_traits>

#include "pvtap/codec/frame_layout.h"

namespace pvtap::dissector {

// ModbusField: a field of the plain Modbus functions, or one that names what the bus learned
// of a Modbus station. Its index is the field's slot in the plugin's registration.
enum class ModbusField : std::uint8_t {
  SubFunction,       // 0x08
  DiagnosticsData,   // 0x08 words
  DiagnosticsBytes,  // 0x08 data of odd length
  WriteStart,        // 0x17
  WriteCount,
  AndMask,  // 0x16
  OrMask,
  FifoCount,  // 0x18
  FifoValue,
  ExceptionStatus,  // 0x07
  EventStatus,      // 0x0B
  EventCount,
  EventLog,     // 0x0C
  FileRecords,  // 0x14 0x15
  MeiType,      // 0x2B
  ReadCode,
  Conformity,
  MoreFollows,
  NextObject,
  ObjectCount,
  Object,  // an object's id
  Vendor,  // objects 0x00 0x01 0x02 and any other
  Product,
  Revision,
  ObjectValue,
  ServerId,  // 0x11: the text that names the device
  ServerData,
  Coils,  // the bytes of coils or inputs, over which their bits are shown
  CoilAddress,
  CoilState,
  InputAddress,
  InputState,
  StationName,      // what the station said of itself
  PreviousDialect,  // the dialect a station spoke before this frame
  QuantityMin,      // the range a request's quantity breaks
  QuantityMax,
  MapValue,   // a value of a station's own map: "voltage phase 1: 230.1 V"
  MapKey,     // its entry's key
  MapNumber,  // its number, where it is one
  Count_,
};

inline constexpr std::size_t kModbusFieldCount = static_cast<std::size_t>(ModbusField::Count_);

// PlannedKind: how a planned field's value is held.
enum class PlannedKind : std::uint8_t { Uint, Bytes, String };

// PlannedField: one Modbus field of a frame, at its place.
struct PlannedField {
  ModbusField field = ModbusField::SubFunction;
  PlannedKind kind = PlannedKind::Uint;
  FieldSpan span;
  std::uint32_t value = 0;
  const char* text = nullptr;  // String: the value; Uint: the value as a person reads it (or null)
};

// PlannedBit: one coil or discrete input, in the byte that holds it.
struct PlannedBit {
  std::uint16_t address = 0;
  bool on = false;
  FieldSpan span;
};

// PlannedObject: one device identification object.
struct PlannedObject {
  std::uint8_t id = 0;
  const char* name = nullptr;  // "vendor name"
  const char* value = nullptr;
  FieldSpan span;  // id, length and value
};

struct ModbusPlan {
  PlannedField* fields = nullptr;
  std::size_t field_count = 0;
  PlannedBit* bits = nullptr;
  std::size_t bit_count = 0;
  bool inputs = false;       // the bits are discrete inputs
  bool bits_placed = false;  // their addresses are known (from the frame or its request)
  FieldSpan bits_span;
  PlannedObject* objects = nullptr;
  std::size_t object_count = 0;
  const char* detail = nullptr;  // what the Info column adds ("17 coils")
};

static_assert(std::is_trivially_destructible_v<ModbusPlan>);

}  // namespace pvtap::dissector
