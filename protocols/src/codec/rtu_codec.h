// The RTU frame the RTU dialects share: address, function, body, CRC low first (private). Each
// dialect's record gives the codes its frames may carry and how their bodies are read and
// written (dialects/*/..._dialect.cpp); these templates put the frame around them.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

#include "codec/wire_fields.h"
#include "pvtap/codec/frame_codec.h"

namespace pvtap::detail {

// Why a frame of a code its dialect does not carry does not parse.
std::string_view unknown_function(std::uint8_t function);
// Appends the CRC of out[begin..]; true.
bool append_crc(std::size_t begin, std::vector<std::uint8_t>& out);

// Fills `f` (see wire_fields.h): `carries(bytes, role, function)` says whether the dialect's
// frames may carry the code, `parse_body(bytes, role, f)` reads the rest.
template <auto carries, auto parse_body>
ParseStatus parse_rtu(std::span<const std::uint8_t> b, Dialect dialect, Role role, Frame& f) {
  if (b.size() < 4) return fail("RTU frame shorter than 4 bytes");
  f = make_frame(dialect, role, b[0], b[1]);
  if (!carries(b, role, f.function)) return fail(unknown_function(f.function));
  return parse_body(b, role, f);
}

// Appends the frame, or nothing when `writes(function)` is false or `encode_body` fails.
template <auto writes, auto encode_body>
bool encode_rtu(const Frame& f, std::vector<std::uint8_t>& out) {
  if (!writes(f.function)) return false;
  const std::size_t begin = out.size();
  out.push_back(f.station);
  out.push_back(f.function);
  if (!encode_body(f, out)) {
    out.resize(begin);
    return false;
  }
  return append_crc(begin, out);
}

// The body of a fixed frame (start, count, words) or a counted reply (byte count, words or a
// device number), as Hybrid and GSL write them; a GSL exception's code.
bool encode_rtu_fields(const Frame& f, std::vector<std::uint8_t>& out);

FrameCheck verify_rtu_check(std::span<const std::uint8_t> bytes);
// The station and function in the first two bytes; the CRC as the wire carries it.
void read_rtu_header(std::span<const std::uint8_t> bytes, Frame& out);
void rtu_check_wire_bytes(std::uint16_t expected, std::vector<std::uint8_t>& out);

}  // namespace pvtap::detail
