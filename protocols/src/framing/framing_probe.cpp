#include "pvtap/framing/framing_probe.h"

#include "dialects/dialect_module.h"

namespace pvtap {

ProbeResult probe_frame(std::span<const std::uint8_t> bytes, RoleHint hint, DialectSet dialects) {
  const CandidateList cands = frame_candidates(bytes, hint, dialects);
  ProbeResult result;
  const FrameCandidate* first_bad = nullptr;
  FrameCheck first_bad_check;
  std::size_t more = cands.need_header;
  for (std::size_t i = 0; i < cands.size; ++i) {
    const FrameCandidate& c = cands.items[i];
    if (c.length > bytes.size()) {
      const std::size_t need = c.length - bytes.size();
      if (more == 0 || need < more) more = need;
      continue;
    }
    const FrameCheck check = verify_check(bytes.first(c.length), c.dialect);
    if (check.ok) {
      return ProbeResult{ProbeResult::Status::Complete, c.length, 0, c.dialect, c.role, check};
    }
    // All readings bad: one that spans exactly the bytes given is the better guess.
    if (!first_bad || (c.length == bytes.size() && first_bad->length != bytes.size())) {
      first_bad = &c;
      first_bad_check = check;
    }
  }
  if (more > 0) {
    result.status = ProbeResult::Status::NeedMore;
    result.more = more;
    return result;
  }
  if (first_bad) {
    return ProbeResult{ProbeResult::Status::Complete,
                       first_bad->length,
                       0,
                       first_bad->dialect,
                       first_bad->role,
                       first_bad_check};
  }
  return result;
}

}  // namespace pvtap
