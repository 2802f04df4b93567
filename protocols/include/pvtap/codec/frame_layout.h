// Where each field of a parsed frame lies in its wire bytes (for displays that highlight them).
#pragma once

#include <cstddef>
#include <cstdint>

#include "pvtap/codec/frame.h"

namespace pvtap {

// FieldSpan: a byte range of a frame; length 0 when the frame has no such field.
struct FieldSpan {
  std::uint16_t offset = 0;
  std::uint16_t length = 0;
  bool present() const { return length > 0; }
};

// FrameLayout: the byte ranges of a frame's fields. Data words follow one another from
// `words.offset`, `word_size` bytes each (2 binary bytes in RTU, 4 hex digits in ASCII).
struct FrameLayout {
  FieldSpan start_delimiter;  // ASCII ENQ or ACK
  FieldSpan station;
  FieldSpan function;
  FieldSpan byte_count;
  FieldSpan device_type;    // Hybrid replies: byte 0 of the device number
  FieldSpan device_serial;  // Hybrid replies: bytes 1..3 of the device number
  FieldSpan start;
  FieldSpan count;
  FieldSpan exception_code;
  FieldSpan words;          // all data words
  FieldSpan check;          // CRC (RTU) or checksum digits (ASCII)
  FieldSpan end_delimiter;  // ASCII EOT
  std::uint16_t word_size = 2;

  // The bytes of `n` data words from word `index` on (empty when outside the frame).
  FieldSpan word_span(std::size_t index, std::size_t n = 1) const;
};

// The spans every frame of a dialect has, whatever its function: delimiters, station,
// function and check, those that fit in `length` bytes. A frame that does not parse shows
// these.
FrameLayout header_layout(Dialect dialect, std::size_t length);

// The layout of a frame that parse_frame produced from `length` wire bytes.
FrameLayout frame_layout(const Frame& frame, std::size_t length);

}  // namespace pvtap
