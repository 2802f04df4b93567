// Plain Modbus's user-defined function codes, read without a length rule (private).
#pragma once

#include <optional>
#include <span>

#include "pvtap/framing/framing_probe.h"

namespace pvtap::detail {

// The reading of `frame` (a span whose start and end are pinned by other evidence) as a frame
// of a user-defined Modbus code (0x41-0x48, 0x64-0x6E), which has no public length rule: a
// station 1-247 and a CRC that holds over the span (PROTOCOLS.md section 6). A request unless
// its direction says it is a reply; nullopt when plain Modbus is not among `dialects`.
std::optional<FrameCandidate> user_defined_reading(std::span<const std::uint8_t> frame,
                                                   RoleHint hint, DialectSet dialects);

}  // namespace pvtap::detail
