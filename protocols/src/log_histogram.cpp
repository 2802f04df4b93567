#include "pvtap/log_histogram.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <vector>

namespace pvtap {
namespace {

// Built on first use rather than at namespace scope, so that no static initializer elsewhere
// can see it unset.
struct Geometry {
  double gamma;
  double log_gamma;
  std::size_t regular;  // buckets 1..regular cover (kMinValue, kMinValue * gamma^regular]
  std::size_t overflow;
  std::size_t buckets;
  // Upper bound of each bucket 0..regular, computed once: finding a value's bucket is then a
  // binary search instead of a log and a pow per value (a latency is added for every reply).
  std::vector<double> bounds;
  double log2_min;  // log2(kMinValue)
  double per_log2;  // buckets per unit of log2
};

// log2 of a positive normal number to within about 0.01, from its exponent bits and a
// quadratic for the mantissa: a fraction of the cost of std::log.
double approximate_log2(double x) {
  std::uint64_t bits = 0;
  std::memcpy(&bits, &x, sizeof bits);
  const int exponent = static_cast<int>((bits >> 52) & 0x7FF) - 1023;
  bits = (bits & 0xFFFFFFFFFFFFFull) | 0x3FF0000000000000ull;  // the mantissa, in [1, 2)
  double mantissa = 0;
  std::memcpy(&mantissa, &bits, sizeof mantissa);
  const double f = mantissa - 1.0;
  return exponent + f * (1.3465553 - 0.3465553 * f);
}

const Geometry& geometry() {
  static const Geometry g = [] {
    Geometry r{};
    r.gamma = (1.0 + LogHistogram::kRelativeError) / (1.0 - LogHistogram::kRelativeError);
    r.log_gamma = std::log(r.gamma);
    r.regular = static_cast<std::size_t>(
        std::ceil(std::log(LogHistogram::kMaxValue / LogHistogram::kMinValue) / r.log_gamma));
    r.log2_min = std::log2(LogHistogram::kMinValue);
    r.per_log2 = std::log(2.0) / r.log_gamma;
    r.overflow = r.regular + 1;
    r.buckets = r.regular + 2;
    r.bounds.resize(r.regular + 1);
    for (std::size_t b = 0; b <= r.regular; ++b) {
      r.bounds[b] = LogHistogram::kMinValue * std::pow(r.gamma, static_cast<double>(b));
    }
    return r;
  }();
  return g;
}

}  // namespace

void LogHistogram::add(double value) {
  if (std::isnan(value)) return;
  if (counts_.empty()) counts_.assign(geometry().buckets, 0);
  ++counts_[bucket_of(value)];
  ++count_;
}

double LogHistogram::quantile(double q) const {
  if (count_ == 0) return 0.0;
  q = std::clamp(q, 0.0, 1.0);
  const auto rank = std::max<std::uint64_t>(
      1, static_cast<std::uint64_t>(std::ceil(q * static_cast<double>(count_))));
  std::uint64_t seen = 0;
  for (std::size_t b = 0; b < counts_.size(); ++b) {
    seen += counts_[b];
    if (seen >= rank) return representative(b);
  }
  return representative(geometry().overflow);
}

std::size_t LogHistogram::bucket_of(double value) {
  const Geometry& g = geometry();
  if (!(value > kMinValue)) return 0;
  if (value > g.bounds[g.regular]) return g.overflow;
  // Bucket b holds (bounds[b - 1], bounds[b]]. An approximate logarithm lands on b or a
  // bucket or two from it; the table settles which, so the result is exact.
  const double estimate = std::ceil((approximate_log2(value) - g.log2_min) * g.per_log2);
  auto b = static_cast<std::size_t>(std::clamp(estimate, 1.0, static_cast<double>(g.regular)));
  while (b < g.regular && value > g.bounds[b]) ++b;
  while (b > 1 && value <= g.bounds[b - 1]) --b;
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
