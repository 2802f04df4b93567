// The RTU framing shared by Hybrid and GSL: address, function, body, CRC low first (private).
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "codec/wire_fields.h"
#include "pvtap/codec/frame_codec.h"

namespace pvtap::detail {

// Fills `f` (see wire_fields.h).
ParseStatus parse_rtu(std::span<const std::uint8_t> bytes, Dialect dialect, Role role, Frame& f);
FrameCheck verify_rtu_check(std::span<const std::uint8_t> bytes);
bool encode_rtu(const Frame& frame, std::vector<std::uint8_t>& out);
// The station and function in the first two bytes; the CRC as the wire carries it.
void read_rtu_header(std::span<const std::uint8_t> bytes, Frame& out);
void rtu_check_wire_bytes(std::uint16_t expected, std::vector<std::uint8_t>& out);

}  // namespace pvtap::detail
