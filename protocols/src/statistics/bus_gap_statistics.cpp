#include "pvtap/statistics/bus_gap_statistics.h"

namespace pvtap {

void BusGapStatistics::add_frame(const FrameTiming& frame) {
  // The silent-interval rules are Modbus RTU's; ASCII frames are delimited by ENQ/ACK..EOT.
  if (rtu_framed(frame.dialect)) {
    inner_silences_.add(frame.max_internal_gap);
    if (frame.max_internal_gap > timing_.t15) record(inner_gap_t15_, frame.id);
  }
  if (previous_) {
    const double gap = frame.start_time - previous_->end_time;
    gaps_.add(gap);
    if (rtu_framed(frame.dialect) && rtu_framed(previous_->dialect)) {
      frame_silences_.add(gap);
      if (gap < timing_.t35) record(spacing_t35_, frame.id);
    }
  }
  previous_ = frame;
}

BusGapReport BusGapStatistics::report(const TimestampQuality& quality) const {
  BusGapReport r;
  r.t15 = timing_.t15;
  r.t35 = timing_.t35;
  if (!quality.fine) {
    r.not_measurable_reason = quality.reason.empty() ? "timestamps too coarse" : quality.reason;
    return r;
  }
  r.measurable = true;
  r.timestamp_source = quality.source;
  r.gaps = gaps_.summary();
  r.inner_gap_t15 = inner_gap_t15_;
  r.spacing_t35 = spacing_t35_;
  r.inner_silences = inner_silences_;
  r.frame_silences = frame_silences_;
  return r;
}

void BusGapStatistics::record(RuleViolations& v, std::uint64_t id) {
  ++v.count;
  if (v.example_ids.size() < kMaxExamples) v.example_ids.push_back(id);
}

}  // namespace pvtap
