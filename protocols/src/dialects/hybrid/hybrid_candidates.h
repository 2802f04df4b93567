// Length rules of the Hybrid function codes (PROTOCOLS.md section 2), inline: they run at
// every position a hunt tries (private).
#pragma once

#include <cstdint>

#include "codec/wire_fields.h"
#include "framing/candidate_reader.h"
#include "pvtap/codec/function_codes.h"

namespace pvtap::detail {

inline void add_hybrid_request(CandidateReader& r, std::uint8_t f) {
  if (f == fc::kHybridError) return;
  if (r.strict && fc::is_hybrid_range_request(f) && r.has(5)) {
    const unsigned count = r.word(4);
    if (count == 0 || count > kMaxReadCount) return;
  }
  r.add(kFixedRequestLength, Role::Request);
}

// Every reply carries the 4-byte device number and then whole registers; write echoes,
// restore confirmations and error replies always carry exactly two words after it.
inline void add_hybrid_response(CandidateReader& r, std::uint8_t f) {
  if (r.strict && r.b[0] == fc::kHybridBroadcast) return;
  if (!r.has(2)) return;
  const std::size_t n = r.b[2];
  const bool fixed =
      f == fc::kHybridWriteParameter || f == fc::kHybridRestoreFactory || f == fc::kHybridError;
  if (r.strict && (n < 4 || n % 2 != 0 || (fixed && n != 8))) return;
  r.add(5 + n, Role::Response);
}

}  // namespace pvtap::detail
