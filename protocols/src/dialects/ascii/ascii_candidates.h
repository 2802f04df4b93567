// Structural readings of ASCII frames at a position (private to the probe).
#pragma once

#include <span>

#include "pvtap/framing/framing_probe.h"

namespace pvtap::detail {

// Only ENQ (request) and ACK (reply) start an ASCII frame.
constexpr bool may_start_ascii(std::uint8_t first) {
  return first == 0x05 || first == 0x06;
}

// Adds the ASCII reading at the start of `bytes`, if its structure holds so far.
void add_ascii_candidates(std::span<const std::uint8_t> bytes, RoleHint hint, CandidateList& out);

}  // namespace pvtap::detail
