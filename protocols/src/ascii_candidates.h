// Structural readings of ASCII frames at a position (private to the probe).
#pragma once

#include <span>

#include "pvtap/framing_probe.h"

namespace pvtap::detail {

// Adds the ASCII reading at the start of `bytes`, if its structure holds so far.
void add_ascii_candidates(std::span<const std::uint8_t> bytes, RoleHint hint, CandidateList& out);

}  // namespace pvtap::detail
