// Every dialect's structural readings of the bytes at a position (framing_probe.h): the text
// dialect's by its start byte, the RTU dialects' by their length rules.
#include "dialects/ascii/ascii_candidates.h"
#include "dialects/rtu_candidates.h"
#include "pvtap/framing/framing_probe.h"

namespace pvtap {

CandidateList frame_candidates(std::span<const std::uint8_t> bytes, RoleHint hint,
                               DialectSet dialects, Plausibility plausibility) {
  CandidateList out;
  if (bytes.empty()) {
    out.need_header = 1;
    return out;
  }
  if (dialects.contains(Dialect::Ascii) && detail::may_start_ascii(bytes[0])) {
    detail::add_ascii_candidates(bytes, hint, out);
  }
  if (dialects.rtu()) detail::add_rtu_candidates(bytes, hint, dialects, plausibility, out);
  return out;
}

}  // namespace pvtap
