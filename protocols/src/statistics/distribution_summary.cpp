#include "pvtap/statistics/distribution_summary.h"

#include <algorithm>
#include <cmath>

namespace pvtap {

void DistributionAccumulator::add(double value) {
  if (std::isnan(value)) return;
  histogram_.add(value);
  sum_ += value;
  min_ = std::min(min_, value);
  max_ = std::max(max_, value);
}

void DistributionAccumulator::merge(const DistributionAccumulator& other) {
  histogram_.merge(other.histogram_);
  sum_ += other.sum_;
  min_ = std::min(min_, other.min_);
  max_ = std::max(max_, other.max_);
}

DistributionSummary DistributionAccumulator::summary() const {
  DistributionSummary s;
  s.count = count();
  if (s.count == 0) return s;
  s.min = min_;
  s.max = max_;
  s.mean = sum_ / static_cast<double>(s.count);
  s.p50 = quantile(0.50);
  s.p95 = quantile(0.95);
  s.p99 = quantile(0.99);
  return s;
}

// The true quantile lies in [min, max], so clamping can only bring the estimate closer; it
// also makes the outer buckets (below 1 us, above the histogram's range) exact at the ends.
double DistributionAccumulator::quantile(double q) const {
  return std::clamp(histogram_.quantile(q), min_, max_);
}

}  // namespace pvtap
