#include "frame_decision.h"

#include "pvtap/checksums.h"

namespace pvtap::detail {
namespace {

enum class Evidence : std::uint8_t { Yes, No, Wait };

RoleHint hint_at(const DecisionInput& in, std::size_t index) {
  return role_hint(in.timeline->direction_at(in.offset + index));
}

// A complete frame with a good check starting at `index`; `incomplete` when one may still come.
bool good_frame_at(const DecisionInput& in, std::size_t index, bool& incomplete) {
  const ProbeResult p = probe_frame(in.bytes.subspan(index), hint_at(in, index), in.dialects);
  incomplete = p.status == ProbeResult::Status::NeedMore;
  return p.status == ProbeResult::Status::Complete && p.check.ok;
}

// A good frame that starts inside the candidate means the candidate is the misreading.
bool good_frame_inside(const DecisionInput& in, std::size_t length) {
  bool incomplete = false;
  for (std::size_t q = 1; q < length; ++q) {
    if (good_frame_at(in, q, incomplete)) return true;
  }
  return false;
}

Evidence end_evidence(const DecisionInput& in, std::size_t length) {
  if (in.timeline->silence_before(in.offset + length)) return Evidence::Yes;
  if (length == in.bytes.size()) {
    return (in.final || in.silence_after) ? Evidence::Yes : Evidence::Wait;
  }
  bool incomplete = false;
  if (good_frame_at(in, length, incomplete)) return Evidence::Yes;
  return (incomplete && !in.final) ? Evidence::Wait : Evidence::No;
}

Evidence bad_frame_evidence(const DecisionInput& in, const FrameCandidate& c) {
  // ENQ/ACK ... EOT delimit an ASCII frame by themselves.
  if (c.dialect == Dialect::Ascii) return Evidence::Yes;
  if (!in.after_frame && !in.timeline->silence_before(in.offset)) return Evidence::No;
  // RTU frames are sent without pauses: a t3.5 silence inside says this reading is wrong.
  if (in.timeline->silence_inside(in.offset, in.offset + c.length - 1)) return Evidence::No;
  const Evidence end = end_evidence(in, c.length);
  if (end != Evidence::Yes) return end;
  return good_frame_inside(in, c.length) ? Evidence::No : Evidence::Yes;
}

// Checks the candidates one after the other. RTU readings at one position share their first
// bytes, so the CRC of a shorter reading is continued for the longer one instead of restarted.
class CandidateChecker {
 public:
  explicit CandidateChecker(std::span<const std::uint8_t> bytes) : bytes_(bytes) {}

  FrameCheck check(const FrameCandidate& c) {
    if (c.dialect == Dialect::Ascii || c.length < 2) {
      return verify_check(bytes_.first(c.length), c.dialect);
    }
    const std::size_t body = c.length - 2;
    if (body < covered_) {
      crc_ = Crc16Modbus::kInit;
      covered_ = 0;
    }
    crc_ = Crc16Modbus::update(crc_, bytes_.subspan(covered_, body - covered_));
    covered_ = body;
    const auto found = static_cast<std::uint16_t>(bytes_[body] | (bytes_[body + 1] << 8));
    return FrameCheck{found == crc_, found, crc_};
  }

 private:
  std::span<const std::uint8_t> bytes_;
  std::uint16_t crc_ = Crc16Modbus::kInit;
  std::size_t covered_ = 0;
};

}  // namespace

Decision decide_at(const DecisionInput& in) {
  const CandidateList cands = frame_candidates(in.bytes, hint_at(in, 0), in.dialects);
  // A long silence after the last byte rules out frames that would need more bytes.
  const bool more_possible = !in.final && !in.give_up;
  bool waiting = cands.need_header > 0 && more_possible;
  CandidateChecker checker(in.bytes);
  for (std::size_t i = 0; i < cands.size; ++i) {
    const FrameCandidate& c = cands.items[i];
    if (c.length > in.bytes.size()) {
      waiting = waiting || more_possible;
      continue;
    }
    const FrameCheck check = checker.check(c);
    if (check.ok) return Decision{Decision::Kind::Frame, c, check};
  }
  if (waiting) return Decision{Decision::Kind::Wait, {}, {}};
  // Only bad readings are left (the rare path): their checks are computed again.
  for (std::size_t i = 0; i < cands.size; ++i) {
    const FrameCandidate& c = cands.items[i];
    if (c.length > in.bytes.size()) continue;
    const Evidence e = bad_frame_evidence(in, c);
    if (e == Evidence::Yes) {
      return Decision{Decision::Kind::Frame, c, verify_check(in.bytes.first(c.length), c.dialect)};
    }
    if (e == Evidence::Wait) return Decision{Decision::Kind::Wait, {}, {}};
  }
  return Decision{Decision::Kind::Noise, {}, {}};
}

}  // namespace pvtap::detail
