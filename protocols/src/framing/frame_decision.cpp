#include "framing/frame_decision.h"

#include <algorithm>
#include <optional>

#include "dialects/dialect_module.h"
#include "dialects/modbus/modbus_user_defined.h"
#include "framing/length_repair.h"
#include "pvtap/codec/checksums.h"

namespace pvtap::detail {
namespace {

enum class Evidence : std::uint8_t { Yes, No, Wait };

// A long silence after the last byte rules out frames that would need more bytes.
bool more_possible(const DecisionInput& in) {
  return !in.final && !in.give_up;
}

RoleHint hint_at(const DecisionInput& in, std::size_t index) {
  return role_hint(in.timeline->direction_at(in.offset + index));
}

// A complete frame with a good check starting at `index`; `incomplete` when one may still come.
bool good_frame_at(const DecisionInput& in, std::size_t index, bool& incomplete) {
  const ProbeResult p = probe_frame(in.bytes.subspan(index), hint_at(in, index), in.dialects);
  incomplete = p.status == ProbeResult::Status::NeedMore;
  return p.status == ProbeResult::Status::Complete && p.check.ok;
}

// What may start at `index`, from one reading of its header: a frame with a good check, one
// that needs more bytes, or a complete ASCII frame (ENQ/ACK ... EOT delimit it whatever its
// check says).
struct StartAt {
  bool good = false;
  bool incomplete = false;
  bool delimited = false;
};

StartAt start_at(const DecisionInput& in, std::size_t index) {
  const auto rest = in.bytes.subspan(index);
  const CandidateList cands = frame_candidates(rest, hint_at(in, index), in.dialects);
  StartAt s;
  s.incomplete = cands.need_header > 0;
  for (std::size_t i = 0; i < cands.size; ++i) {
    const FrameCandidate& c = cands.items[i];
    if (c.length > rest.size()) {
      s.incomplete = true;
      continue;
    }
    if (!detail::dialect_module(c.dialect).rtu_framed) s.delimited = true;
    if (!s.good && verify_check(rest.first(c.length), c.dialect).ok) s.good = true;
  }
  return s;
}

// A good frame that starts inside the candidate means the candidate is the misreading.
bool good_frame_inside(const DecisionInput& in, std::size_t length) {
  bool incomplete = false;
  for (std::size_t q = 1; q < length; ++q) {
    if (good_frame_at(in, q, incomplete)) return true;
  }
  return false;
}

// Whether a good frame starts right after `length` bytes: Wait while one may still arrive.
Evidence good_frame_after(const DecisionInput& in, std::size_t length) {
  bool incomplete = false;
  if (good_frame_at(in, length, incomplete)) return Evidence::Yes;
  return (incomplete && more_possible(in)) ? Evidence::Wait : Evidence::No;
}

Evidence end_evidence(const DecisionInput& in, std::size_t length) {
  if (in.timeline->silence_before(in.offset + length)) return Evidence::Yes;
  if (in.timeline->segment_ends_at(in.offset + length)) return Evidence::Yes;
  if (length == in.bytes.size()) {
    return (in.final || in.silence_after) ? Evidence::Yes : Evidence::Wait;
  }
  return good_frame_after(in, length);
}

// Whether a silence inside the reading rules it out. RTU frames are sent without pauses, so
// a silence the timestamps prove says the reading is wrong. Batched timestamps, though, date
// the reads of a serial adapter or the segments of a gateway, not the bytes: a read that came
// late (the sniffer was not scheduled) seems to follow a silence that was never on the bus.
// There a good frame right after the reading, or the end of the input right at its end,
// outweighs them: structure first.
Evidence silence_rules_out(const DecisionInput& in, const FrameCandidate& c) {
  if (!in.timeline->silence_inside(in.offset, in.offset + c.length - 1)) return Evidence::No;
  if (in.timeline->trusted()) return Evidence::Yes;
  if (in.final && c.length == in.bytes.size()) return Evidence::No;
  switch (good_frame_after(in, c.length)) {
    case Evidence::Yes:
      return Evidence::No;
    case Evidence::Wait:
      return Evidence::Wait;
    case Evidence::No:
      break;
  }
  return Evidence::Yes;
}

Evidence bad_frame_evidence(const DecisionInput& in, const FrameCandidate& c, bool pinned) {
  // ENQ/ACK ... EOT delimit an ASCII frame by themselves.
  if (!detail::dialect_module(c.dialect).rtu_framed) return Evidence::Yes;
  if (!pinned) return Evidence::No;
  if (c.needs_good_check && !verify_check(in.bytes.first(c.length), c.dialect).ok) {
    return Evidence::No;
  }
  const Evidence silence = silence_rules_out(in, c);
  if (silence != Evidence::No) return silence == Evidence::Wait ? Evidence::Wait : Evidence::No;
  const Evidence end = end_evidence(in, c.length);
  if (end != Evidence::Yes) return end;
  return good_frame_inside(in, c.length) ? Evidence::No : Evidence::Yes;
}

// Where the repair scan of this position goes on (see RepairScan).
std::size_t resumed_scan(const DecisionInput& in) {
  const RepairScan* s = in.repair_scan;
  if (s == nullptr || s->offset != in.offset || s->trusted != in.timeline->trusted()) return 1;
  return s->resume;
}

// The scan waits at `q`: every start before it was ruled out, but the one at the last byte gets
// a second look: rtu_candidates.cpp may rule a start of one byte out on that byte alone, by a
// rule that reads no second byte and so records no need for one.
void remember_scan(const DecisionInput& in, std::size_t q) {
  if (in.repair_scan == nullptr) return;
  const std::size_t last_byte = in.bytes.size() - 1;
  *in.repair_scan = RepairScan{in.offset, std::max<std::size_t>(1, std::min(q, last_byte)),
                               in.timeline->trusted()};
}

// A pinned start that no reading fits: a frame sent with a byte count that lies or of a
// user-defined code, if the CRC holds over the span, or one whose length field was damaged,
// if the CRC says so. Its end is the
// first proven silence, good frame or end of input after it; a segment end on the way (gateways) is
// tried too, since the frame may end there. When no repair fits, the whole span up to that end is
// noise: nothing inside it is pinned, and the scan found no frame starting inside it, so each of
// its bytes would be noise on its own.
Decision repaired_at(const DecisionInput& in) {
  std::size_t scanned = 1;
  const auto repaired = [&](std::size_t length) -> std::optional<Decision> {
    scanned = length;
    const auto frame = in.bytes.first(length);
    auto c = lying_count_reading(frame, hint_at(in, 0), in.dialects);
    if (!c) c = user_defined_reading(frame, hint_at(in, 0), in.dialects);
    if (!c) c = repaired_reading(frame, hint_at(in, 0), in.dialects);
    if (!c) return std::nullopt;
    return Decision{Decision::Kind::Frame, *c, verify_check(frame, c->dialect)};
  };
  const auto noise = [&] { return Decision{Decision::Kind::Noise, {}, {}, scanned}; };
  const auto wait = [&](std::size_t q) {
    remember_scan(in, q);
    return Decision{Decision::Kind::Wait, {}, {}};
  };
  const std::size_t limit = std::min(in.bytes.size(), kMaxRtuFrameLength);
  for (std::size_t q = resumed_scan(in); q <= limit; ++q) {
    if (in.timeline->silence_before(in.offset + q)) return repaired(q).value_or(noise());
    if (in.timeline->segment_ends_at(in.offset + q)) {
      if (auto d = repaired(q)) return *d;
    }
    if (q == in.bytes.size()) {
      if (in.final || in.silence_after) return repaired(q).value_or(noise());
      return more_possible(in) ? wait(q) : Decision{Decision::Kind::Noise, {}, {}};
    }
    const StartAt next = start_at(in, q);
    if (next.good || next.delimited) return repaired(q).value_or(noise());
    if (next.incomplete && more_possible(in)) return wait(q);
  }
  return Decision{Decision::Kind::Noise, {}, {}};
}

// Checks the candidates one after the other. RTU readings at one position share their first
// bytes, so the CRC of a shorter reading is continued for the longer one instead of restarted.
class CandidateChecker {
 public:
  explicit CandidateChecker(std::span<const std::uint8_t> bytes) : bytes_(bytes) {}

  FrameCheck check(const FrameCandidate& c) {
    if (!detail::dialect_module(c.dialect).rtu_framed || c.length < 2) {
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

// GoodScan: the first reading with a good check, or whether one may still come.
struct GoodScan {
  const FrameCandidate* frame = nullptr;
  FrameCheck check;
  bool waiting = false;
};

GoodScan find_good(const DecisionInput& in, const CandidateList& cands, CandidateChecker& checker) {
  GoodScan s;
  s.waiting = cands.need_header > 0 && more_possible(in);
  for (std::size_t i = 0; i < cands.size; ++i) {
    const FrameCandidate& c = cands.items[i];
    if (c.length > in.bytes.size()) {
      s.waiting = s.waiting || more_possible(in);
      continue;
    }
    s.check = checker.check(c);
    if (s.check.ok) {
      s.frame = &c;
      return s;
    }
  }
  return s;
}

Decision bad_or_noise(const DecisionInput& in, const CandidateList& cands, bool pinned) {
  // No plausible reading has a good check (the rare path): checks are computed again.
  for (std::size_t i = 0; i < cands.size; ++i) {
    const FrameCandidate& c = cands.items[i];
    if (c.length > in.bytes.size()) continue;
    const Evidence e = bad_frame_evidence(in, c, pinned);
    if (e == Evidence::Yes) {
      return Decision{Decision::Kind::Frame, c, verify_check(in.bytes.first(c.length), c.dialect)};
    }
    if (e == Evidence::Wait) return Decision{Decision::Kind::Wait, {}, {}};
  }
  if (pinned && in.dialects.rtu()) return repaired_at(in);
  return Decision{Decision::Kind::Noise, {}, {}};
}

}  // namespace

Decision decide_at(const DecisionInput& in) {
  const RoleHint hint = hint_at(in, 0);
  CandidateChecker checker(in.bytes);
  // Plausible readings first: a good check on an implausible reading (8 bytes of a longer
  // reply whose CRC matches by chance) must not beat the real frame.
  const CandidateList plausible = frame_candidates(in.bytes, hint, in.dialects);
  const GoodScan first = find_good(in, plausible, checker);
  if (first.frame) return Decision{Decision::Kind::Frame, *first.frame, first.check};
  if (first.waiting) return Decision{Decision::Kind::Wait, {}, {}};
  const bool pinned = in.after_frame || in.timeline->silence_before(in.offset);
  if (!pinned) return bad_or_noise(in, plausible, false);
  // A pinned start: structure alone decides, whatever the fields say, but a reading with
  // implausible fields needs both ends pinned even when its check is good (random bytes
  // after a frame pass a CRC once in 65536 readings).
  return bad_or_noise(in, frame_candidates(in.bytes, hint, in.dialects, Plausibility::Ignore),
                      true);
}

}  // namespace pvtap::detail
