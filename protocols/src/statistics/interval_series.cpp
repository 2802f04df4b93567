#include "pvtap/statistics/interval_series.h"

#include <algorithm>
#include <cmath>

namespace pvtap {

void IntervalSeries::add_event(double time) {
  if (last_) {
    const double interval = time - *last_;
    ++n_;
    const double delta = interval - mean_;
    mean_ += delta / static_cast<double>(n_);
    sum_squared_deviation_ += delta * (interval - mean_);
    min_ = n_ == 1 ? interval : std::min(min_, interval);
    max_ = n_ == 1 ? interval : std::max(max_, interval);
  }
  last_ = time;
}

IntervalSummary IntervalSeries::summary() const {
  IntervalSummary s;
  s.intervals = n_;
  if (n_ == 0) return s;
  s.min = min_;
  s.max = max_;
  s.mean = mean_;
  s.stddev = std::sqrt(std::max(0.0, sum_squared_deviation_ / static_cast<double>(n_)));
  // The interval farthest from the mean is always the smallest or the largest.
  s.max_deviation = std::max(max_ - mean_, mean_ - min_);
  return s;
}

}  // namespace pvtap
