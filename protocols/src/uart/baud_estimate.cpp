// estimate_baud: the shortest common pulse, refined by its multiples, snapped to a standard.
#include "pvtap/uart/baud_estimate.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

namespace pvtap {
namespace {

constexpr std::array<std::uint32_t, 9> kStandard = {1200,  2400,  4800,  9600,  14400,
                                                    19200, 38400, 57600, 115200};

// A bit's width is common when this share of the pulses (or at least kMinPulses) lies between
// it and a quarter more: a few glitches are shorter, and are not a bit. Nor is a pulse a driver
// makes at every turn of a bus line, as common as 2 % of the pulses and of one width: a bit's
// band also holds at least 1/kCrowdDivisor as many pulses as the most crowded band.
constexpr std::size_t kCommonShareDivisor = 50;  // 2 %
constexpr std::size_t kCrowdDivisor = 8;
constexpr std::size_t kMinPulses = 4;
constexpr double kBand = 1.25;
constexpr unsigned kMaxMultiple = 10;  // the longest pulse inside a character
// Refining stops once a round moves the bit by under this many samples, or after kMaxRounds.
constexpr double kSettled = 1e-3;
constexpr int kMaxRounds = 16;

// For each pulse (sorted), how many lie in its band: from it to a quarter more.
std::vector<std::size_t> band_counts(const std::vector<std::uint64_t>& sorted) {
  std::vector<std::size_t> counts(sorted.size());
  std::size_t hi = 0;
  for (std::size_t lo = 0; lo < sorted.size(); ++lo) {
    const double top = kBand * static_cast<double>(sorted[lo]);
    hi = std::max(hi, lo);
    while (hi < sorted.size() && static_cast<double>(sorted[hi]) < top) ++hi;
    counts[lo] = hi - lo;
  }
  return counts;
}

double shortest_common(const std::vector<std::uint64_t>& sorted) {
  const std::vector<std::size_t> counts = band_counts(sorted);
  const std::size_t crowd = counts.empty() ? 0 : *std::max_element(counts.begin(), counts.end());
  const std::size_t need =
      std::max({kMinPulses, sorted.size() / kCommonShareDivisor, crowd / kCrowdDivisor});
  for (std::size_t lo = 0; lo < sorted.size(); ++lo)
    if (counts[lo] >= need) return static_cast<double>(sorted[lo]);
  return 0;
}

// Every pulse of k bits (k <= kMaxMultiple) counts as k bits of its length: the mean bit is
// exact to a fraction of a sample where one pulse's edges are only exact to a sample.
double refined_bit(const std::vector<std::uint64_t>& sorted, double first) {
  double samples = 0;
  double bits = 0;
  for (std::uint64_t w : sorted) {
    const double k = std::round(static_cast<double>(w) / first);
    if (k < 1 || k > kMaxMultiple) continue;
    if (std::abs(static_cast<double>(w) - k * first) > 0.25 * first) continue;
    samples += static_cast<double>(w);
    bits += k;
  }
  return bits > 0 ? samples / bits : first;
}

}  // namespace

std::span<const std::uint32_t> standard_bauds() {
  return kStandard;
}

BaudEstimate snap_baud(double measured) {
  BaudEstimate e;
  e.measured = measured;
  std::uint32_t nearest = kStandard.front();
  for (std::uint32_t b : kStandard) {
    if (std::abs(measured / b - 1) < std::abs(measured / nearest - 1)) nearest = b;
  }
  e.deviation = measured / nearest - 1;
  e.snapped = std::abs(e.deviation) <= BaudEstimate::kSnapTolerance;
  e.baud = e.snapped ? nearest : static_cast<std::uint32_t>(std::lround(measured));
  return e;
}

std::optional<BaudEstimate> estimate_baud(std::span<const std::uint64_t> widths,
                                          double sample_rate) {
  std::vector<std::uint64_t> sorted(widths.begin(), widths.end());
  std::sort(sorted.begin(), sorted.end());
  double bit = shortest_common(sorted);
  if (bit < 1) return std::nullopt;
  // The shortest common width is the short end of the bits when edges jitter, and a band
  // around its multiples then takes the short pulses of each and leaves the long ones out.
  // Refining from the refined bit centres the bands. Where pulses of no whole bit (a driver's
  // lead before a frame) crowd the short end, the first width is a fifth of a bit short and
  // takes a few more rounds to settle.
  for (int round = 0; round < kMaxRounds; ++round) {
    const double next = refined_bit(sorted, bit);
    const bool settled = std::abs(next - bit) < kSettled;
    bit = next;
    if (settled) break;
  }
  return snap_baud(sample_rate / bit);
}

}  // namespace pvtap
