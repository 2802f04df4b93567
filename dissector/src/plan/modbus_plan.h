// ModbusPlan: what the tree shows of the fields only plain Modbus functions carry.
#pragma once

#include <cstddef>
#include <cstdint>
#include <type_traits>

#include "plan/field_table.h"
#include "pvtap/codec/frame_layout.h"

namespace pvtap::dissector {

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
