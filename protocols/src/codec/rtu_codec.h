// The RTU framing shared by Hybrid and GSL: address, function, body, CRC low first (private).
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "pvtap/codec/frame_codec.h"

namespace pvtap::detail {

ParseOutcome parse_rtu(std::span<const std::uint8_t> bytes, Dialect dialect, Role role);
FrameCheck verify_rtu_check(std::span<const std::uint8_t> bytes);
bool encode_rtu(const Frame& frame, std::vector<std::uint8_t>& out);

}  // namespace pvtap::detail
