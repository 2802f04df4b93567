#include "pvtap/statistics/silence_histogram.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <vector>

#include "pvtap/statistics/bus_timing.h"
#include "pvtap/statistics/timing_statistics.h"

namespace pvtap {
namespace {

const BusTiming k9600(9600, 11);  // 8N2: t1.5 = 1.719 ms, t3.5 = 4.010 ms

// Silences from 1/20 of a character to 40 s, log-uniform, from a fixed generator.
std::vector<double> spread_silences(std::size_t n, double char_time) {
  std::vector<double> out;
  std::uint64_t state = 0x2545F4914F6CDD1Du;
  for (std::size_t i = 0; i < n; ++i) {
    state = state * 6364136223846793005u + 1442695040888963407u;
    const double u = static_cast<double>(state >> 11) / 9007199254740992.0;
    out.push_back(char_time / 20 * std::pow(4e4 / char_time * 20, u));
  }
  return out;
}

// The bucket a silence belongs to, by a plain scan of the edges: how many lie below it (or
// at it, for a line whose equal side is Above).
std::size_t scanned_bucket(const SilenceHistogram& h, double v, LineSide equal) {
  std::size_t i = 0;
  for (double e : h.edges()) i += (equal == LineSide::Below ? e < v : e <= v) ? 1u : 0u;
  return i;
}

TEST(SilenceHistogram, EdgesAreLogSpacedInCharacterTimesWithTheLineAmongThem) {
  const SilenceHistogram h(k9600.char_time, k9600.t35, LineSide::Above);
  ASSERT_EQ(h.edges().size(), SilenceHistogram::kEdges);
  EXPECT_EQ(h.counts().size(), SilenceHistogram::kBuckets);
  EXPECT_TRUE(std::is_sorted(h.edges().begin(), h.edges().end()));
  EXPECT_DOUBLE_EQ(h.edges().front(), k9600.char_time / 8);
  EXPECT_DOUBLE_EQ(h.edges().back(), k9600.char_time * 16384);
  EXPECT_DOUBLE_EQ(h.line(), k9600.t35);
  // 3.5 lies between 2^(7/4) = 3.36 and 2^2 = 4 character times.
  const auto at = std::find(h.edges().begin(), h.edges().end(), k9600.t35);
  ASSERT_NE(at, h.edges().end());
  EXPECT_NEAR(*(at - 1) / k9600.char_time, std::exp2(7.0 / 4), 1e-12);
  EXPECT_NEAR(*(at + 1) / k9600.char_time, 4.0, 1e-12);
}

TEST(SilenceHistogram, EverySilenceFallsInItsBucketAndTheLineSplitsAsTheRuleDoes) {
  for (const LineSide equal : {LineSide::Below, LineSide::Above}) {
    const double line = equal == LineSide::Below ? k9600.t15 : k9600.t35;
    SilenceHistogram h(k9600.char_time, line, equal);
    std::vector<std::uint64_t> expected(SilenceHistogram::kBuckets, 0);
    std::uint64_t broken = 0;
    for (double v : spread_silences(5000, k9600.char_time)) {
      h.add(v);
      ++expected[scanned_bucket(h, v, equal)];
      broken += (equal == LineSide::Below ? v > line : v < line) ? 1 : 0;
    }
    EXPECT_EQ(std::vector<std::uint64_t>(h.counts().begin(), h.counts().end()), expected);
    const std::uint64_t beyond = equal == LineSide::Below ? h.above_line() : h.below_line();
    EXPECT_EQ(beyond, broken);
    EXPECT_EQ(h.below_line() + h.above_line(), 5000u);
    EXPECT_GT(broken, 0u);
    EXPECT_LT(broken, 5000u);
  }
}

TEST(SilenceHistogram, ASilenceExactlyAtTheLineIsWithinTheRule) {
  SilenceHistogram t15(k9600.char_time, k9600.t15, LineSide::Below);
  t15.add(k9600.t15);  // t1.5 is broken only by a longer silence
  EXPECT_EQ(t15.below_line(), 1u);
  EXPECT_EQ(t15.above_line(), 0u);
  SilenceHistogram t35(k9600.char_time, k9600.t35, LineSide::Above);
  t35.add(k9600.t35);  // t3.5 is broken only by a shorter one
  EXPECT_EQ(t35.below_line(), 0u);
  EXPECT_EQ(t35.above_line(), 1u);
}

TEST(SilenceHistogram, ALineOnAnEdgeOfTheLadderStillSplitsExactly) {
  // Two character times is the ladder's edge 2^(4/4): the line's edge is a duplicate.
  const double line = 2 * k9600.char_time;
  for (const LineSide equal : {LineSide::Below, LineSide::Above}) {
    SilenceHistogram h(k9600.char_time, line, equal);
    h.add(std::nextafter(line, 0.0));
    h.add(line);
    h.add(std::nextafter(line, 1.0));
    EXPECT_EQ(h.below_line(), equal == LineSide::Below ? 2u : 1u);
    EXPECT_EQ(h.above_line(), equal == LineSide::Below ? 1u : 2u);
  }
}

TEST(SilenceHistogram, OverlapsAndLongPausesFallInTheEndBucketsAndNaNNowhere) {
  SilenceHistogram h(k9600.char_time, k9600.t35, LineSide::Above);
  h.add(-0.002);  // frames that overlap
  h.add(0.0);
  h.add(3600.0);
  h.add(std::nan(""));
  EXPECT_EQ(h.counts().front(), 2u);
  EXPECT_EQ(h.counts().back(), 1u);
  EXPECT_EQ(std::accumulate(h.counts().begin(), h.counts().end(), std::uint64_t{0}), 3u);
}

FrameTiming frame(std::uint64_t id, double start, double end, double inner_gap,
                  Dialect dialect = Dialect::Modbus) {
  FrameTiming f;
  f.id = id;
  f.dialect = dialect;
  f.start_time = start;
  f.end_time = end;
  f.max_internal_gap = inner_gap;
  return f;
}

TEST(SilenceHistogram, TheBusReportsHistogramsWhoseCountsBeyondTheLinesAreItsViolations) {
  TimingStatistics stats(k9600);
  std::uint64_t id = 0;
  double t = 0;
  // Frames 20 ms long with inner silences and spacings on both sides of the lines.
  const double inner[] = {0, 0.0005, 0.0017, 0.0018, 0.003, 0, 0.01, 0.0001};
  const double spacing[] = {0.05, 0.002, 0.0041, 0.0039, 0.5, 0.001, 3.0, 0.004};
  for (std::size_t i = 0; i < 8; ++i) {
    stats.add_frame(frame(++id, t, t + 0.02, inner[i]));
    t += 0.02 + spacing[i];
  }
  // ASCII frames are judged by neither rule, nor counted in either histogram.
  stats.add_frame(frame(++id, t, t + 0.02, 0.05, Dialect::Ascii));
  stats.add_frame(frame(++id, t + 0.021, t + 0.04, 0.0, Dialect::Gsl));
  const BusGapReport r = stats.report({true, "", "logic analyzer at 1 MS/s"}).bus;
  ASSERT_TRUE(r.inner_silences && r.frame_silences);
  EXPECT_EQ(r.inner_gap_t15.count, 3u);
  EXPECT_EQ(r.inner_silences->above_line(), r.inner_gap_t15.count);
  EXPECT_EQ(r.inner_silences->below_line(), 6u);
  EXPECT_EQ(r.spacing_t35.count, 3u);
  EXPECT_EQ(r.frame_silences->below_line(), r.spacing_t35.count);
  EXPECT_EQ(r.frame_silences->above_line(), 4u);

  const BusGapReport coarse = stats.report({false, "timestamps are batched", ""}).bus;
  EXPECT_FALSE(coarse.inner_silences || coarse.frame_silences);
}

}  // namespace
}  // namespace pvtap
