// FramePlan: all that the tree and the Info column show of one frame, worked out beforehand.
#pragma once

#include <glib.h>

#include <type_traits>

#include "fields/register_fields.h"
#include "pvtap/codec/frame_codec.h"
#include "pvtap/codec/frame_layout.h"
#include "pvtap/registers/register_decoder.h"

namespace pvtap::dissector {

// PlannedValue: one register value of a frame, ready for the tree.
struct PlannedValue {
  const RegisterField* field = nullptr;  // null: a word no map entry covers
  FieldSpan span;                        // within the frame
  double number = 0;                     // scaled value (FT_DOUBLE fields)
  guint32 raw = 0;                       // integer value (FT_UINT fields, unmapped words)
  const char* text = nullptr;            // the value as a person reads it ("26.6 V")
  const char* label = nullptr;           // "battery voltage (0x1006)"
  guint16 warnings = 0;                  // ValueWarning bits worth an expert info
};

// Built by analyze_frame with the core before any Wireshark call that may throw (those
// longjmp past C++ destructors), so it is plain data: texts and arrays live in pinfo->pool.
struct FramePlan {
  bool parsed = false;
  const char* parse_error = nullptr;
  Dialect dialect = Dialect::Gsl;
  Role role = Role::Request;
  guint8 station = 0;
  guint8 function = 0;
  FrameLayout layout;
  guint16 start = 0;
  const char* start_text = nullptr;  // as the reference writes it ("1050", "0x1000")
  guint16 count = 0;
  guint8 byte_count = 0;
  guint8 exception_code = 0;
  guint8 device_type = 0;
  guint32 device_serial = 0;
  guint32 device_raw = 0;
  const char* device_text = nullptr;
  FrameCheck check;
  bool check_verified = true;
  PlannedValue* values = nullptr;
  std::size_t value_count = 0;
  DecodeStatus decode_status = DecodeStatus::NoRegisterData;
  bool start_assumed = false;
  const char* decode_note = nullptr;
  const char* summary = nullptr;  // this frame's part of the Info column
};

static_assert(std::is_trivially_destructible_v<FramePlan>);
static_assert(std::is_trivially_destructible_v<PlannedValue>);

}  // namespace pvtap::dissector
