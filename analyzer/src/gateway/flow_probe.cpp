#include "gateway/flow_probe.h"

#include "pvtap/carriers/mbap_structure.h"

namespace pvtap::analyzer {

FlowProbe::FlowProbe(DialectSet dialects) : dialects_(dialects) {}

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
  if (whole_mbap_adus(bytes)) ++mbap_pieces_;
  if (mbap_pieces_ >= kGoodFramesNeeded) return Verdict::Mbap;
  stream(d).feed(BusChunk{bytes, time, d});
  if (good_.count >= kGoodFramesNeeded) return Verdict::Bus;
  return bytes_ > kMaxBytes ? Verdict::NotBus : Verdict::Undecided;
}

void FlowProbe::add_gap(Direction d, std::uint64_t lost, double time) {
  items_.push_back(Item{d, time, true, lost, {}});
  // Bytes on both sides of a gap never join into one frame.
  stream(d).discontinuity();
}

FlowProbe::Verdict FlowProbe::final_verdict() {
  for (auto& s : streams_) {
    if (s) s->finish();
  }
  if (mbap_pieces_ > good_.count) return Verdict::Mbap;
  return good_.count > 0 ? Verdict::Bus : Verdict::NotBus;
}

void FlowProbe::clear() {
  items_.clear();
  items_.shrink_to_fit();
  for (auto& s : streams_) s.reset();
}

}  // namespace pvtap::analyzer
