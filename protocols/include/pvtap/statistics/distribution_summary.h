// Exact extremes and mean plus histogram quantiles of a stream of durations.
#pragma once

#include <cstdint>
#include <limits>

#include "pvtap/statistics/log_histogram.h"

namespace pvtap {

// DistributionSummary: count, exact min/max/mean and quantiles (within
// LogHistogram::kRelativeError) of some durations in seconds; all zero when count is 0.
struct DistributionSummary {
  std::uint64_t count = 0;
  double min = 0;
  double max = 0;
  double mean = 0;
  double p50 = 0;
  double p95 = 0;
  double p99 = 0;
};

// DistributionAccumulator: collects durations into a DistributionSummary in bounded memory.
class DistributionAccumulator {
 public:
  void add(double value);  // NaN is ignored
  // Adds the values of another accumulator (quantiles as exact as either's; the mean may
  // differ from adding the values one by one in its last digits).
  void merge(const DistributionAccumulator& other);
  std::uint64_t count() const { return histogram_.count(); }
  DistributionSummary summary() const;

 private:
  double quantile(double q) const;

  LogHistogram histogram_;
  double sum_ = 0;
  double min_ = std::numeric_limits<double>::infinity();
  double max_ = -std::numeric_limits<double>::infinity();
};

}  // namespace pvtap
