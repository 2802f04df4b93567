// Silence between and inside frames, judged against the Modbus RTU t1.5 / t3.5 rules.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "pvtap/statistics/bus_timing.h"
#include "pvtap/statistics/distribution_summary.h"
#include "pvtap/statistics/frame_timing.h"
#include "pvtap/statistics/silence_histogram.h"

namespace pvtap {

// RuleViolations: how often a timing rule was broken, with the first few frame ids.
struct RuleViolations {
  std::uint64_t count = 0;
  std::vector<std::uint64_t> example_ids;
};

// BusGapReport: inter-frame silence and RTU timing-rule violations. When the timestamps are
// too coarse, measurable is false, not_measurable_reason says why and the rest is empty.
struct BusGapReport {
  bool measurable = false;
  std::string not_measurable_reason;
  std::string timestamp_source;  // when measurable and known: what stamped the characters
  double t15 = 0;                // seconds, for the configured baud
  double t35 = 0;
  DistributionSummary gaps;      // silence from one frame's end to the next frame's start
  RuleViolations inner_gap_t15;  // RTU frames with a gap inside longer than t1.5
  RuleViolations spacing_t35;    // RTU frames starting less than t3.5 after an RTU frame
  // When measurable: each RTU frame's largest silence inside, against t1.5 (those above the
  // line are inner_gap_t15), and each silence between two RTU frames, against t3.5 (those
  // below it are spacing_t35).
  std::optional<SilenceHistogram> inner_silences;
  std::optional<SilenceHistogram> frame_silences;
};

// BusGapStatistics: collects gaps as frames pass; the timestamp verdict comes at report time,
// since the reassembler may only know it after seeing part of the capture.
class BusGapStatistics {
 public:
  static constexpr std::size_t kMaxExamples = 10;

  explicit BusGapStatistics(BusTiming timing)
      : timing_(timing),
        inner_silences_(timing.char_time, timing.t15, LineSide::Below),
        frame_silences_(timing.char_time, timing.t35, LineSide::Above) {}
  void add_frame(const FrameTiming& frame);
  // The last frame went on until `end_time` (its echo): the next gap is measured from there.
  void extend_last(double end_time) {
    if (previous_) previous_->end_time = std::max(previous_->end_time, end_time);
  }
  BusGapReport report(const TimestampQuality& quality) const;

 private:
  static void record(RuleViolations& v, std::uint64_t id);

  BusTiming timing_;
  DistributionAccumulator gaps_;
  RuleViolations inner_gap_t15_;
  RuleViolations spacing_t35_;
  SilenceHistogram inner_silences_;
  SilenceHistogram frame_silences_;
  std::optional<FrameTiming> previous_;
};

}  // namespace pvtap
