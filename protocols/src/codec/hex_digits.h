// Hex-ASCII digit conversion for the ASCII dialect (private to the core).
#pragma once

#include <cstdint>
#include <optional>
#include <span>

namespace pvtap::detail {

// Value of one hex digit in either case, or -1.
constexpr int hex_digit_value(std::uint8_t c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

// Reads `digits.size()` (at most 4) hex digits as one number, most significant first.
inline std::optional<std::uint16_t> read_hex(std::span<const std::uint8_t> digits) {
  unsigned v = 0;
  for (auto c : digits) {
    const int d = hex_digit_value(c);
    if (d < 0) return std::nullopt;
    v = (v << 4) | static_cast<unsigned>(d);
  }
  return static_cast<std::uint16_t>(v);
}

// Lowercase, as the seed writes them.
inline std::uint8_t hex_char(unsigned nibble) {
  return static_cast<std::uint8_t>("0123456789abcdef"[nibble & 0xFu]);
}

}  // namespace pvtap::detail
