#include "flow_probe.h"

#include "pvtap/framing_probe.h"

namespace pvtap::analyzer {
namespace {

// Rescanning from an undecided position after every tiny segment would be quadratic; such a
// rescan waits for this much new data.
constexpr std::size_t kRescanStep = 256;

}  // namespace

FlowProbe::Verdict FlowProbe::add_data(Direction d, std::span<const std::uint8_t> bytes,
                                       double time) {
  items_.push_back(Item{d, time, false, 0, {bytes.begin(), bytes.end()}});
  bytes_ += bytes.size();
  Scan& s = scans_[static_cast<std::size_t>(d)];
  s.bytes.insert(s.bytes.end(), bytes.begin(), bytes.end());
  // Only new bytes need a look, unless an undecided position waits before them.
  const bool nothing_undecided = s.next >= s.scanned_to;
  if (nothing_undecided || s.bytes.size() - s.scanned_to >= kRescanStep) scan(d, false);
  if (good_frames_ >= kGoodFramesNeeded) return Verdict::Bus;
  return bytes_ > kMaxBytes ? Verdict::NotBus : Verdict::Undecided;
}

void FlowProbe::add_gap(Direction d, std::uint64_t lost, double time) {
  items_.push_back(Item{d, time, true, lost, {}});
  // Bytes on both sides of a gap never join into one frame.
  scan(d, true);
  scans_[static_cast<std::size_t>(d)] = Scan{};
}

FlowProbe::Verdict FlowProbe::final_verdict() {
  for (std::size_t d = 0; d < 3; ++d) scan(static_cast<Direction>(d), true);
  return good_frames_ > 0 ? Verdict::Bus : Verdict::NotBus;
}

void FlowProbe::scan(Direction d, bool final) {
  Scan& s = scans_[static_cast<std::size_t>(d)];
  s.scanned_to = s.bytes.size();
  const std::span<const std::uint8_t> all(s.bytes);
  std::size_t at = s.next;
  std::size_t resume = all.size();
  while (at < all.size()) {
    const ProbeResult r = probe_frame(all.subspan(at), role_hint(d), dialects_);
    if (r.status == ProbeResult::Status::Complete && r.check.ok) {
      // A rescan from an undecided position meets frames it counted before.
      if (at >= s.counted_end) ++good_frames_;
      at += r.length;
      s.counted_end = at;
      continue;
    }
    if (r.status == ProbeResult::Status::NeedMore && !final && resume == all.size()) resume = at;
    ++at;
  }
  s.next = resume;
}

void FlowProbe::clear() {
  items_.clear();
  items_.shrink_to_fit();
  for (Scan& s : scans_) s = Scan{};
}

}  // namespace pvtap::analyzer
