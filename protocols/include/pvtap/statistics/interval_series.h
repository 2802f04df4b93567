// Regularity of a repeating event: the intervals between its occurrences.
#pragma once

#include <cstdint>
#include <optional>

namespace pvtap {

// IntervalSummary: the intervals between consecutive events, seconds; all zero when fewer than
// two events were seen. stddev is the population standard deviation (jitter), max_deviation
// the largest distance of any interval from the mean.
struct IntervalSummary {
  std::uint64_t intervals = 0;
  double min = 0;
  double max = 0;
  double mean = 0;
  double stddev = 0;
  double max_deviation = 0;
};

// IntervalSeries: accumulates the intervals of one event stream in constant memory
// (Welford's running mean and variance; exact min and max).
class IntervalSeries {
 public:
  void add_event(double time);
  IntervalSummary summary() const;

 private:
  std::optional<double> last_;
  std::uint64_t n_ = 0;
  double mean_ = 0;
  double sum_squared_deviation_ = 0;
  double min_ = 0;
  double max_ = 0;
};

}  // namespace pvtap
