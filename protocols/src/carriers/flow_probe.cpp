#include "pvtap/carriers/flow_probe.h"

#include "pvtap/carriers/mbap_structure.h"

namespace pvtap {

FlowProbe::FlowProbe(DialectSet dialects, bool listed) : dialects_(dialects), listed_(listed) {}

FlowProbe::~FlowProbe() = default;

// Each direction is read by the same framing decision as the bus it may become, with no
// timing evidence: whether frames are there does not depend on segment times.
StreamReassembler& FlowProbe::stream(Direction d) {
  auto& slot = streams_[index_of(d)];
  if (!slot) {
    ReassemblerOptions o;
    o.dialects = dialects_;
    o.timestamps = TimestampTrust::Untrusted;
    o.boundary_gap = 0;
    slot = std::make_unique<StreamReassembler>(o, good_);
  }
  return *slot;
}

FlowProbe::Verdict FlowProbe::add_data(Direction d, std::span<const std::uint8_t> bytes,
                                       double time) {
  items_.push_back(Item{d, time, false, 0, {bytes.begin(), bytes.end()}});
  bytes_ += bytes.size();
  if (bytes_ == bytes.size()) first_piece_mbap_ = whole_mbap_adus(bytes);
  if (recognize_v5(d, bytes) == solarman_v5::Recognition::Yes) return Verdict::SolarmanV5;
  if (whole_mbap_adus(bytes)) ++mbap_pieces_;
  if (mbap_pieces_ >= kGoodFramesNeeded) return Verdict::Mbap;
  stream(d).feed(BusChunk{bytes, time, d});
  // Bare RTU frames are trusted only once no direction may still open with a V5 frame.
  if (v5_undecided()) return bytes_ > kMaxBytes ? Verdict::NotBus : Verdict::Undecided;
  if (listed_) return listed_verdict();
  if (good_.count >= kGoodFramesNeeded) return Verdict::Bus;
  return bytes_ > kMaxBytes ? Verdict::NotBus : Verdict::Undecided;
}

solarman_v5::Recognition FlowProbe::recognize_v5(Direction d, std::span<const std::uint8_t> bytes) {
  solarman_v5::Recognition& verdict = v5_[index_of(d)];
  if (verdict != solarman_v5::Recognition::NeedMore) return verdict;
  std::vector<std::uint8_t>& head = v5_head_[index_of(d)];
  head.insert(head.end(), bytes.begin(), bytes.end());
  verdict = solarman_v5::recognize(head);
  if (verdict != solarman_v5::Recognition::NeedMore) head = {};
  return verdict;
}

// A flow on --port whose first piece is whole MBAP ADUs is read as Modbus/TCP, as a flow on
// --port always was; any other is bare frames.
FlowProbe::Verdict FlowProbe::listed_verdict() const {
  return first_piece_mbap_ ? Verdict::Mbap : Verdict::Bus;
}

bool FlowProbe::v5_undecided() const {
  for (std::size_t i = 0; i < kDirections; ++i) {
    if (v5_[i] == solarman_v5::Recognition::NeedMore && !v5_head_[i].empty()) return true;
  }
  return false;
}

void FlowProbe::add_gap(Direction d, std::uint64_t lost, double time) {
  items_.push_back(Item{d, time, true, lost, {}});
  // Bytes on both sides of a gap never join into one frame.
  stream(d).discontinuity();
  // Bytes after a gap do not continue the first frame.
  if (!v5_head_[index_of(d)].empty()) {
    v5_[index_of(d)] = solarman_v5::Recognition::No;
    v5_head_[index_of(d)] = {};
  }
}

FlowProbe::Verdict FlowProbe::final_verdict() {
  for (auto& s : streams_) {
    if (s) s->finish();
  }
  if (listed_) return listed_verdict();
  if (mbap_pieces_ > good_.count) return Verdict::Mbap;
  return good_.count > 0 ? Verdict::Bus : Verdict::NotBus;
}

void FlowProbe::clear() {
  items_.clear();
  items_.shrink_to_fit();
  for (auto& s : streams_) s.reset();
  for (auto& head : v5_head_) head = {};
}

}  // namespace pvtap
