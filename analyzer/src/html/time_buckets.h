// TimeBuckets: a run's time cut into at most kMaxBuckets equal buckets whose width doubles
// as the run grows, so that a day of traffic costs the same memory as a minute; and
// BucketSeries, one measured quantity over those buckets (count, sum, min, max, last).
#pragma once

#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

namespace pvtap::analyzer {

// Bucket: what one series saw within one bucket. `last` is the exact newest reading.
struct Bucket {
  std::uint32_t count = 0;
  double sum = 0;
  double min = std::numeric_limits<double>::infinity();
  double max = -std::numeric_limits<double>::infinity();
  double last = 0;

  void add(double v) {
    ++count;
    sum += v;
    if (v < min) min = v;
    if (v > max) max = v;
    last = v;
  }
  // Joins the next bucket in time into this one.
  void absorb(const Bucket& later) {
    if (later.count == 0) return;
    if (count == 0) {
      *this = later;
      return;
    }
    count += later.count;
    sum += later.sum;
    if (later.min < min) min = later.min;
    if (later.max > max) max = later.max;
    last = later.last;
  }
};

class BucketSeries {
 public:
  void add(std::size_t index, double v) {
    if (index >= buckets_.size()) buckets_.resize(index + 1);
    buckets_[index].add(v);
  }
  // The bucket width doubled: bucket i and i+1 become bucket i/2.
  void halve() {
    const std::size_t n = (buckets_.size() + 1) / 2;
    for (std::size_t i = 0; i < n; ++i) {
      Bucket joined = buckets_[2 * i];
      if (2 * i + 1 < buckets_.size()) joined.absorb(buckets_[2 * i + 1]);
      buckets_[i] = joined;
    }
    buckets_.resize(n);
  }
  const std::vector<Bucket>& buckets() const { return buckets_; }

 private:
  std::vector<Bucket> buckets_;
};

// TimeGrid: where bucket 0 starts and how wide a bucket is now.
class TimeGrid {
 public:
  static constexpr std::size_t kMaxBuckets = 720;
  static constexpr double kFirstWidth = 0.25;  // seconds: polls of a short capture stay apart

  // The bucket of `time`; `doublings` says how often the width had to double first (every
  // series must then halve() as often).
  std::size_t index_of(double time, int& doublings) {
    doublings = 0;
    if (!started_) {
      start_ = time;
      started_ = true;
    }
    const double offset = time > start_ ? time - start_ : 0.0;
    auto index = static_cast<std::size_t>(offset / width_);
    while (index >= kMaxBuckets) {
      width_ *= 2;
      ++doublings;
      index = static_cast<std::size_t>(offset / width_);
    }
    return index;
  }
  double start() const { return start_; }
  double width() const { return width_; }
  bool started() const { return started_; }

 private:
  bool started_ = false;
  double start_ = 0;
  double width_ = kFirstWidth;
};

}  // namespace pvtap::analyzer
