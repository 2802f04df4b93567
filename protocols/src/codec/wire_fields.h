// Big-endian 16-bit fields and the in-place parse status the frame codecs share (private).
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string_view>
#include <vector>

#include "pvtap/codec/frame.h"

namespace pvtap::detail {

// The fixed-shape frames of Hybrid and GSL: address, function, two words, CRC.
inline constexpr std::size_t kFixedRequestLength = 8;

// ParseStatus: why bytes do not parse, empty when they do. The parsers fill a frame the caller
// keeps, and return only this: a Result<Frame> would copy the frame's inline words once per
// frame on the audit's hot path.
using ParseStatus = std::string_view;
inline constexpr ParseStatus kParsed{};

inline ParseStatus fail(std::string_view why) {
  return why;
}

inline std::uint16_t be16(std::span<const std::uint8_t> b, std::size_t at) {
  return static_cast<std::uint16_t>((b[at] << 8) | b[at + 1]);
}

inline void put16(std::vector<std::uint8_t>& out, std::uint16_t v) {
  out.push_back(static_cast<std::uint8_t>(v >> 8));
  out.push_back(static_cast<std::uint8_t>(v & 0xFFu));
}

// Whole big-endian registers; false when the data is odd or more than the list holds.
inline bool read_words(std::span<const std::uint8_t> data, WordList& words) {
  if (data.size() % 2 != 0) return false;
  for (std::size_t i = 0; i < data.size(); i += 2) {
    if (!words.push_back(be16(data, i))) return false;
  }
  return true;
}

// addr fc n data[n] crc, with n checked against the frame length.
inline std::optional<std::span<const std::uint8_t>> counted_body(std::span<const std::uint8_t> b,
                                                                 Frame& f) {
  if (b.size() < 5) return std::nullopt;
  const std::size_t n = b[2];
  if (b.size() != 5 + n) return std::nullopt;
  f.byte_count = b[2];
  return b.subspan(3, n);
}

}  // namespace pvtap::detail
