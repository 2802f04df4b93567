// Whether a flow speaks Solarman V5, from the structure of its first bytes (port 8899 is
// only a hint: sticks are reached through NAT and port forwards).
#pragma once

#include <cstdint>
#include <span>

namespace pvtap::solarman_v5 {

enum class Recognition : std::uint8_t { NeedMore, Yes, No };

// The first bytes of one direction of a flow: Yes when they open with a whole V5 frame whose
// end byte, checksum and control code all hold (a random start passes all three about once
// in 10^9); NeedMore while that frame is not complete.
Recognition recognize(std::span<const std::uint8_t> first_bytes);

}  // namespace pvtap::solarman_v5
