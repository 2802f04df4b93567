// SilenceHistogram: a binary search over fixed edges per silence (one per frame, not per byte).
#include "pvtap/statistics/silence_histogram.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <numeric>

namespace pvtap {

SilenceHistogram::SilenceHistogram(double char_time, double line, LineSide equal)
    : char_time_(char_time), equal_(equal) {
  std::size_t i = 0;
  for (int k = kLowestOctave * kPerOctave; k <= kHighestOctave * kPerOctave; ++k) {
    edges_[i++] = char_time * std::exp2(static_cast<double>(k) / kPerOctave);
  }
  edges_[i] = line;
  std::sort(edges_.begin(), edges_.end());
  // The line's own edge: the last equal to it, so that an edge of the ladder that happens to
  // equal the line leaves an empty bucket below, never one on the wrong side.
  line_edge_ = static_cast<std::size_t>(std::upper_bound(edges_.begin(), edges_.end(), line) -
                                        edges_.begin()) -
               1;
}

// A silence equal to an edge goes below it for LineSide::Below, above it otherwise; every
// edge follows the line's rule, so the line splits the buckets exactly as the rule does.
void SilenceHistogram::add(double seconds) {
  if (std::isnan(seconds)) return;
  const auto at = equal_ == LineSide::Below
                      ? std::lower_bound(edges_.begin(), edges_.end(), seconds)
                      : std::upper_bound(edges_.begin(), edges_.end(), seconds);
  ++counts_[static_cast<std::size_t>(at - edges_.begin())];
}

std::uint64_t SilenceHistogram::below_line() const {
  return std::accumulate(counts_.begin(),
                         counts_.begin() + static_cast<std::ptrdiff_t>(line_edge_) + 1,
                         std::uint64_t{0});
}

std::uint64_t SilenceHistogram::above_line() const {
  return std::accumulate(counts_.begin() + static_cast<std::ptrdiff_t>(line_edge_) + 1,
                         counts_.end(), std::uint64_t{0});
}

}  // namespace pvtap
