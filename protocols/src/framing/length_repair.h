// Reads a damaged RTU frame whose length field lies, once its ends are known (private).
#pragma once

#include <optional>
#include <span>

#include "pvtap/framing/framing_probe.h"

namespace pvtap::detail {

// The reading of `frame` (a span whose start and end are pinned by other evidence) when one
// damaged byte in its function code or byte count hides its length: the byte is set back to
// each value that gives the span's length, and a CRC that then matches shows which one it
// was. The CRC covers the original byte, so a match is evidence of one byte's damage, not a
// guess (a random span matches with odds of 1 in 65536 per value tried). The reading keeps
// the frame's own bytes: its check stays bad. nullopt when no single repair fits.
std::optional<FrameCandidate> repaired_reading(std::span<const std::uint8_t> frame, RoleHint hint,
                                               DialectSet dialects);

// The reading of `frame` (pinned as above) whose CRC holds over the whole span although its
// byte count says another length: a write request of several registers or coils (0x0F 0x10
// 0x17) sent with a byte count that lies (a master's wrong count), malformed but not damaged.
// nullopt for any other function, a frame its direction says is a reply, or a CRC that does
// not hold: an RTU-shaped run from the slave's side is no request.
std::optional<FrameCandidate> lying_count_reading(std::span<const std::uint8_t> frame,
                                                  RoleHint hint, DialectSet dialects);
}  // namespace pvtap::detail
