// Structural readings of RTU frames at a position: the length rules of each RTU dialect
// (Hybrid, GSL, plain Modbus) that a function code calls on (private).
#pragma once

#include <span>

#include "pvtap/framing/framing_probe.h"

namespace pvtap::detail {

// Adds every RTU reading (Hybrid and GSL, request and response) the header allows.
void add_rtu_candidates(std::span<const std::uint8_t> bytes, RoleHint hint, DialectSet dialects,
                        Plausibility plausibility, CandidateList& out);

}  // namespace pvtap::detail
