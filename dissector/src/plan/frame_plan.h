// FramePlan: all that the tree and the Info column show of one frame, worked out beforehand.
#pragma once

#include <cstddef>
#include <cstdint>
#include <type_traits>

#include "plan/modbus_plan.h"
#include "pvtap/codec/frame_codec.h"
#include "pvtap/codec/frame_layout.h"
#include "pvtap/registers/register_decoder.h"

namespace pvtap::dissector {

// PlannedValue: one register value of a frame, ready for the tree.
struct PlannedValue {
  const RegisterDef* def = nullptr;  // its entry of the effective map; null: a word none covers
  FieldSpan span;                    // within the frame
  double number = 0;                 // scaled value (double fields)
  std::uint32_t raw = 0;             // integer value (integer fields, unmapped words)
  const char* text = nullptr;        // the value as a person reads it ("26.6 V")
  const char* label = nullptr;       // "battery voltage (0x1006)"
  std::uint16_t warnings = 0;        // ValueWarning bits worth an expert info
  // An entry of the station's own map (station register maps), which has no field of its own:
  // its key and "name: value", for the generic map fields. Null for any other value.
  const char* map_key = nullptr;
  const char* map_value = nullptr;
};

// Built by analyze_frame with the core before any Wireshark call that may throw (those
// longjmp past C++ destructors), so it is plain data: texts and arrays live in an Arena.
struct FramePlan {
  bool parsed = false;
  const char* parse_error = nullptr;
  Dialect dialect = kDefaultDialect;
  Role role = Role::Request;
  std::uint8_t station = 0;
  std::uint8_t function = 0;
  FrameLayout layout;
  std::uint16_t start = 0;
  const char* start_text = nullptr;  // as the reference writes it ("1050", "0x1000")
  std::uint16_t count = 0;
  std::uint8_t byte_count = 0;
  std::uint8_t exception_code = 0;
  std::uint8_t device_type = 0;
  std::uint32_t device_serial = 0;
  std::uint32_t device_raw = 0;
  const char* device_text = nullptr;
  FrameCheck check;
  bool check_verified = true;
  PlannedValue* values = nullptr;
  std::size_t value_count = 0;
  DecodeStatus decode_status = DecodeStatus::NoRegisterData;
  bool start_assumed = false;
  const char* decode_note = nullptr;
  ModbusPlan modbus;                   // the fields of the plain Modbus functions
  const char* station_name = nullptr;  // what the station said of itself, when known
  const char* summary = nullptr;       // this frame's part of the Info column
};

static_assert(std::is_trivially_destructible_v<FramePlan>);
static_assert(std::is_trivially_destructible_v<PlannedValue>);

}  // namespace pvtap::dissector
