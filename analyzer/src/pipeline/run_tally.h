// RunTally: what a run counts across all its buses as events happen: the latency over every
// bus for the report, and frames, timeouts and the last latency for --count and the status line.
#pragma once

#include <cstdint>
#include <optional>

#include "output/event_writer.h"
#include "pvtap/statistics/distribution_summary.h"

namespace pvtap::analyzer {

class RunTally : public EventWriter {
 public:
  void frame(const EventContext&, const SessionFrame& f) override {
    ++frames_;
    if (f.latency) {
      latency_.add(*f.latency);
      last_latency_ = f.latency;
    }
  }
  void timeout(const EventContext&, const SessionTimeout& t) override {
    if (t.kind == UnansweredKind::Timeout) ++timeouts_;
  }
  void noise(const EventContext&, const SessionNoise&) override {}
  void gap(const EventContext&, const SessionGap&) override {}

  std::uint64_t frames() const { return frames_; }
  std::uint64_t timeouts() const { return timeouts_; }
  std::optional<double> last_latency() const { return last_latency_; }
  DistributionSummary latency() const { return latency_.summary(); }

 private:
  std::uint64_t frames_ = 0;
  std::uint64_t timeouts_ = 0;
  std::optional<double> last_latency_;
  DistributionAccumulator latency_;
};

}  // namespace pvtap::analyzer
