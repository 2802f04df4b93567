#include "pvtap/statistics/log_histogram.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <vector>

namespace pvtap {
namespace {

// A value's bucket is looked up by its top bits: the exponent and kSliceBits of the mantissa
// cut each power of two into 2^kSliceBits slices, each narrower than a bucket (2^(1/128) =
// 1.0054 < gamma = 1.0202), so a slice holds at most one bucket bound and the table entry,
// the bucket of the slice's lowest value, is either the value's bucket or the one before.
constexpr int kSliceBits = 7;
constexpr int kSliceShift = 52 - kSliceBits;

std::uint64_t slice_of(double value) {
  std::uint64_t bits = 0;
  std::memcpy(&bits, &value, sizeof bits);
  return bits >> kSliceShift;
}

double slice_start(std::uint64_t slice) {
  const std::uint64_t bits = slice << kSliceShift;
  double value = 0;
  std::memcpy(&value, &bits, sizeof value);
  return value;
}

// Built on first use rather than at namespace scope, so that no static initializer elsewhere
// can see it unset.
struct Geometry {
  double gamma;
  std::size_t regular;  // buckets 1..regular cover (kMinValue, kMinValue * gamma^regular]
  std::size_t overflow;
  std::size_t buckets;
  std::vector<double> bounds;                  // upper bound of each bucket 0..regular
  std::uint64_t first_slice;                   // the slice of kMinValue
  std::vector<std::uint16_t> bucket_by_slice;  // from first_slice up to the last bound's slice

  // The bucket by binary search over the bounds: what the table is built from.
  std::size_t search(double value) const {
    return static_cast<std::size_t>(std::lower_bound(bounds.begin(), bounds.end(), value) -
                                    bounds.begin());
  }
};

Geometry build_geometry() {
  Geometry r{};
  r.gamma = (1.0 + LogHistogram::kRelativeError) / (1.0 - LogHistogram::kRelativeError);
  r.regular = static_cast<std::size_t>(
      std::ceil(std::log(LogHistogram::kMaxValue / LogHistogram::kMinValue) / std::log(r.gamma)));
  r.overflow = r.regular + 1;
  r.buckets = r.regular + 2;
  r.bounds.resize(r.regular + 1);
  for (std::size_t b = 0; b <= r.regular; ++b) {
    r.bounds[b] = LogHistogram::kMinValue * std::pow(r.gamma, static_cast<double>(b));
  }
  r.first_slice = slice_of(LogHistogram::kMinValue);
  const std::uint64_t last_slice = slice_of(r.bounds[r.regular]);
  const double above_min = std::nextafter(LogHistogram::kMinValue, 1.0);
  for (std::uint64_t slice = r.first_slice; slice <= last_slice; ++slice) {
    const double lowest = std::max(slice_start(slice), above_min);
    r.bucket_by_slice.push_back(static_cast<std::uint16_t>(r.search(lowest)));
  }
  return r;
}

// Small enough to be inlined into bucket_of: a call per value added cost as much as the
// lookup itself (every latency and silence of an audit is added).
const Geometry& geometry() {
  static const Geometry g = build_geometry();
  return g;
}

}  // namespace

void LogHistogram::cover(std::size_t b) {
  if (counts_.empty()) {
    first_ = b;
    counts_.assign(1, 0);
  } else if (b < first_) {
    counts_.insert(counts_.begin(), first_ - b, 0);
    first_ = b;
  } else if (b >= first_ + counts_.size()) {
    counts_.resize(b - first_ + 1, 0);
  }
}

void LogHistogram::add(double value) {
  if (std::isnan(value)) return;
  const std::size_t b = bucket_of(value);
  // Almost every value falls inside the window already: one comparison on the usual path.
  if (b - first_ >= counts_.size()) cover(b);
  ++counts_[b - first_];
  ++count_;
}

void LogHistogram::merge(const LogHistogram& other) {
  if (other.count_ == 0) return;
  cover(other.first_);
  cover(other.first_ + other.counts_.size() - 1);
  for (std::size_t i = 0; i < other.counts_.size(); ++i) {
    counts_[other.first_ + i - first_] += other.counts_[i];
  }
  count_ += other.count_;
}

double LogHistogram::quantile(double q) const {
  if (count_ == 0) return 0.0;
  q = std::clamp(q, 0.0, 1.0);
  const auto rank = std::max<std::uint64_t>(
      1, static_cast<std::uint64_t>(std::ceil(q * static_cast<double>(count_))));
  std::uint64_t seen = 0;
  for (std::size_t i = 0; i < counts_.size(); ++i) {
    seen += counts_[i];
    if (seen >= rank) return representative(first_ + i);
  }
  return representative(geometry().overflow);
}

std::size_t LogHistogram::bucket_of(double value) {
  const Geometry& g = geometry();
  if (!(value > kMinValue)) return 0;
  if (value > g.bounds[g.regular]) return g.overflow;
  // Bucket b holds (bounds[b - 1], bounds[b]].
  std::size_t b = g.bucket_by_slice[slice_of(value) - g.first_slice];
  if (value > g.bounds[b]) ++b;
  return b;
}

double LogHistogram::upper_bound(std::size_t bucket) {
  return geometry().bounds[bucket];
}

// The point of (upper/gamma, upper] whose relative distance to both ends is kRelativeError.
double LogHistogram::representative(std::size_t bucket) {
  const Geometry& g = geometry();
  if (bucket == 0) return kMinValue / 2;
  if (bucket >= g.overflow) return upper_bound(g.regular);
  return 2.0 * upper_bound(bucket) / (g.gamma + 1.0);
}

}  // namespace pvtap
