// Latency, poll-period and bus-gap statistics of a whole capture.
#pragma once

#include <cstdint>
#include <map>
#include <tuple>
#include <vector>

#include "pvtap/bus_gap_statistics.h"
#include "pvtap/bus_timing.h"
#include "pvtap/distribution_summary.h"
#include "pvtap/frame_timing.h"
#include "pvtap/interval_series.h"

namespace pvtap {

// StationLatency: reply latencies of one answering station.
struct StationLatency {
  std::uint8_t station = 0;
  DistributionSummary latency;
};

// PollPeriod: how regularly the master sends one station one function.
struct PollPeriod {
  Dialect dialect = Dialect::Gsl;
  std::uint8_t station = 0;  // 0xFF for Hybrid broadcasts
  std::uint8_t function = 0;
  IntervalSummary period;
};

// TimingReport: everything TimingStatistics measured, ready to print as text or JSON.
// Latency quantiles are within latency_relative_error of the nearest-rank quantile of the
// exact values; count, min, max and mean are exact. Stations and poll keys are sorted.
struct TimingReport {
  double latency_relative_error = LogHistogram::kRelativeError;
  DistributionSummary latency;
  std::vector<StationLatency> latency_by_station;
  std::vector<PollPeriod> poll_periods;
  BusGapReport bus;
};

// TimingStatistics: accumulates a capture's timing in memory bounded by the number of
// stations and station+function pairs (not by its length).
//
// Feed every frame in bus order with add_frame (requests drive the poll periods; give the
// role as the TransactionMatcher returned it, so that GSL 0x06 echoes are not counted as
// polls) and every Transaction's latency with add_latency. Negative latencies (possible with
// coarse clocks) count in min and mean as they are and fall in the histogram's lowest bucket.
class TimingStatistics {
 public:
  explicit TimingStatistics(BusTiming timing) : gaps_(timing) {}

  void add_frame(const FrameTiming& frame);
  void add_latency(std::uint8_t station, double seconds);
  TimingReport report(const TimestampQuality& quality) const;

 private:
  using PollKey = std::tuple<Dialect, std::uint8_t, std::uint8_t>;

  DistributionAccumulator latency_;
  std::map<std::uint8_t, DistributionAccumulator> latency_by_station_;
  std::map<PollKey, IntervalSeries> polls_;
  BusGapStatistics gaps_;
};

}  // namespace pvtap
