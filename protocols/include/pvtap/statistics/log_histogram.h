// A fixed-size histogram with logarithmic buckets for quantiles of positive durations.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace pvtap {

// LogHistogram: counts durations in buckets whose bounds grow by a constant ratio
// gamma = (1 + a) / (1 - a), a = kRelativeError, so that a bucket's representative value is
// within a of every value the bucket holds. Covering kMinValue .. kMaxValue takes about 1150
// buckets (9 KiB at most); only the window between the lowest and the highest bucket used is
// kept, since a bus's latencies or silences span a few hundred at most and a session keeps
// dozens of histograms. Memory does not depend on how many values are added. Values at or below
// kMinValue (zero and negatives included) share bucket 0, whose error is absolute (at most
// kMinValue); values above kMaxValue share the last bucket. Callers that keep the exact minimum and
// maximum should clamp quantiles to them.
class LogHistogram {
 public:
  static constexpr double kRelativeError = 0.01;
  static constexpr double kMinValue = 1e-6;  // seconds
  static constexpr double kMaxValue = 1e4;   // seconds

  void add(double value);  // NaN is ignored
  // Adds the counts of another histogram: as if its values had been added here.
  void merge(const LogHistogram& other);
  std::uint64_t count() const { return count_; }

  // The nearest-rank q-quantile: the representative value of the bucket holding the value of
  // rank max(1, ceil(q * count)) in sorted order. 0 when empty; q is clamped to [0, 1].
  double quantile(double q) const;

 private:
  static std::size_t bucket_of(double value);
  static double upper_bound(std::size_t bucket);
  static double representative(std::size_t bucket);
  // Makes counts_ cover bucket b (counts_[0] is bucket first_).
  void cover(std::size_t b);

  std::vector<std::uint64_t> counts_;
  std::size_t first_ = 0;
  std::uint64_t count_ = 0;
};

}  // namespace pvtap
