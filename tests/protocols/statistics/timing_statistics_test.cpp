#include "pvtap/statistics/timing_statistics.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>
#include <vector>

#include "pvtap/statistics/bus_timing.h"
#include "pvtap/statistics/distribution_summary.h"
#include "pvtap/statistics/interval_series.h"
#include "pvtap/statistics/log_histogram.h"

namespace pvtap {
namespace {

// The nearest-rank quantile of exact values: the value of rank max(1, ceil(q * n)).
double nearest_rank(std::vector<double> values, double q) {
  std::sort(values.begin(), values.end());
  const auto n = static_cast<double>(values.size());
  const auto rank = std::max<std::size_t>(1, static_cast<std::size_t>(std::ceil(q * n)));
  return values[rank - 1];
}

// Log-uniform values between lo and hi from a fixed linear congruential generator, so the
// test sees spread-out data without depending on a library's random engine.
std::vector<double> spread_values(std::size_t n, double lo, double hi) {
  std::vector<double> out;
  std::uint64_t state = 0x9E3779B97F4A7C15u;
  for (std::size_t i = 0; i < n; ++i) {
    state = state * 6364136223846793005u + 1442695040888963407u;
    const double u = static_cast<double>(state >> 11) / 9007199254740992.0;  // [0, 1)
    out.push_back(lo * std::pow(hi / lo, u));
  }
  return out;
}

void expect_within_relative(double actual, double expected, double relative) {
  EXPECT_LE(std::abs(actual - expected), relative * std::abs(expected) + 1e-15)
      << "actual " << actual << " expected " << expected;
}

FrameTiming rtu_frame(std::uint64_t id, double start, double end, double inner_gap = 0) {
  FrameTiming f;
  f.id = id;
  f.dialect = Dialect::Gsl;
  f.role = Role::Request;
  f.station = 1;
  f.function = 0x03;
  f.start_time = start;
  f.end_time = end;
  f.max_internal_gap = inner_gap;
  return f;
}

const TimestampQuality kFine{true, "", ""};

TEST(TimingHistogramTest, EmptyHistogramAndSummaryAreZero) {
  LogHistogram h;
  EXPECT_EQ(h.count(), 0u);
  EXPECT_EQ(h.quantile(0.5), 0.0);
  const DistributionSummary s = DistributionAccumulator{}.summary();
  EXPECT_EQ(s.count, 0u);
  EXPECT_EQ(s.min, 0.0);
  EXPECT_EQ(s.p99, 0.0);
}

TEST(TimingHistogramTest, EveryQuantileIsWithinTheStatedRelativeError) {
  const std::vector<double> values = spread_values(20000, 50e-6, 5.0);
  LogHistogram h;
  for (double v : values) h.add(v);
  ASSERT_EQ(h.count(), values.size());
  for (double q : {0.001, 0.01, 0.1, 0.25, 0.5, 0.75, 0.9, 0.95, 0.99, 0.999, 1.0}) {
    expect_within_relative(h.quantile(q), nearest_rank(values, q), LogHistogram::kRelativeError);
  }
}

TEST(TimingHistogramTest, OrderOfAddsAndMergesDoesNotChangeAQuantile) {
  // Only the window of buckets in use is kept: values arriving below it, above it, or in
  // another histogram merged in must give the quantiles of one histogram fed in order.
  const std::vector<double> values = spread_values(5000, 1e-7, 2e4);  // beyond both ends
  LogHistogram in_order;
  for (double v : values) in_order.add(v);
  std::vector<double> sorted = values;
  std::sort(sorted.rbegin(), sorted.rend());
  LogHistogram descending;  // every add below the window so far
  for (double v : sorted) descending.add(v);
  LogHistogram low, high, middle, merged;  // three windows apart
  for (std::size_t i = 0; i < sorted.size(); ++i) {
    (i < 1000 ? high : i < 4000 ? middle : low).add(sorted[i]);
  }
  merged.merge(middle);
  merged.merge(high);
  merged.merge(low);
  merged.merge(LogHistogram{});
  for (double q : {0.0, 0.001, 0.1, 0.5, 0.9, 0.999, 1.0}) {
    EXPECT_EQ(descending.quantile(q), in_order.quantile(q)) << q;
    EXPECT_EQ(merged.quantile(q), in_order.quantile(q)) << q;
  }
  EXPECT_EQ(merged.count(), values.size());
}
TEST(TimingHistogramTest, ValuesOnBucketBoundariesKeepTheBound) {
  // Powers of the bucket ratio sit exactly where a rounded logarithm could misplace them.
  const double gamma = (1 + LogHistogram::kRelativeError) / (1 - LogHistogram::kRelativeError);
  for (int k = 1; k < 1100; k += 37) {
    LogHistogram h;
    const double v = LogHistogram::kMinValue * std::pow(gamma, k);
    h.add(v);
    expect_within_relative(h.quantile(0.5), v, LogHistogram::kRelativeError);
  }
}

TEST(TimingHistogramTest, EveryBoundBelongsToItsBucketAndTheNextValueToTheNext) {
  // The bucket of a value is looked up by its leading bits and settled against the bounds:
  // on every bound, and one representable value above it, the value must land exactly. A
  // bucket's representative is 2 * upper / (gamma + 1), which tells the buckets apart.
  const double gamma = (1 + LogHistogram::kRelativeError) / (1 - LogHistogram::kRelativeError);
  const auto representative = [&](int b) {
    return 2.0 * LogHistogram::kMinValue * std::pow(gamma, b) / (gamma + 1.0);
  };
  const auto median_of = [](double v) {
    LogHistogram h;
    h.add(v);
    return h.quantile(0.5);
  };
  int checked = 0;
  for (int b = 1;; ++b) {
    const double bound = LogHistogram::kMinValue * std::pow(gamma, b);
    if (bound > LogHistogram::kMaxValue) break;
    ASSERT_EQ(median_of(bound), representative(b)) << "bound " << b;
    ASSERT_EQ(median_of(std::nextafter(bound, 0.0)), representative(b)) << "below bound " << b;
    if (LogHistogram::kMinValue * std::pow(gamma, b + 1) <= LogHistogram::kMaxValue) {
      ASSERT_EQ(median_of(std::nextafter(bound, 1e9)), representative(b + 1))
          << "above bound " << b;
    }
    ++checked;
  }
  EXPECT_GT(checked, 1100);
  EXPECT_EQ(median_of(LogHistogram::kMinValue), LogHistogram::kMinValue / 2);
  EXPECT_EQ(median_of(std::nextafter(LogHistogram::kMinValue, 1.0)), representative(1));
}

TEST(TimingStatisticsTest, KnownLatenciesGiveExactExtremesAndMean) {
  TimingStatistics stats(BusTiming(9600));
  std::vector<double> values;
  for (int i = 1; i <= 200; ++i) values.push_back(0.0005 * i);     // 0.5 ms .. 100 ms
  std::rotate(values.begin(), values.begin() + 77, values.end());  // order must not matter
  double sum = 0;
  for (double v : values) {
    stats.add_latency(1, v);
    sum += v;
  }
  const TimingReport r = stats.report(kFine);
  EXPECT_EQ(r.latency.count, 200u);
  EXPECT_DOUBLE_EQ(r.latency.min, 0.0005);
  EXPECT_DOUBLE_EQ(r.latency.max, 0.1);
  EXPECT_DOUBLE_EQ(r.latency.mean, sum / 200);
  EXPECT_DOUBLE_EQ(r.latency_relative_error, 0.01);
  expect_within_relative(r.latency.p50, 0.0005 * 100, r.latency_relative_error);
  expect_within_relative(r.latency.p95, 0.0005 * 190, r.latency_relative_error);
  expect_within_relative(r.latency.p99, 0.0005 * 198, r.latency_relative_error);
}

TEST(TimingStatisticsTest, SpreadLatenciesHavePercentilesWithinTheStatedError) {
  TimingStatistics stats(BusTiming(9600));
  const std::vector<double> values = spread_values(5000, 1e-3, 2.0);
  for (double v : values) stats.add_latency(7, v);
  const TimingReport r = stats.report(kFine);
  EXPECT_DOUBLE_EQ(r.latency.min, *std::min_element(values.begin(), values.end()));
  EXPECT_DOUBLE_EQ(r.latency.max, *std::max_element(values.begin(), values.end()));
  expect_within_relative(r.latency.p50, nearest_rank(values, 0.50), r.latency_relative_error);
  expect_within_relative(r.latency.p95, nearest_rank(values, 0.95), r.latency_relative_error);
  expect_within_relative(r.latency.p99, nearest_rank(values, 0.99), r.latency_relative_error);
}

TEST(TimingStatisticsTest, LatencyIsKeptPerStation) {
  TimingStatistics stats(BusTiming(9600));
  stats.add_latency(6, 0.020);
  stats.add_latency(2, 0.100);
  stats.add_latency(6, 0.040);
  const TimingReport r = stats.report(kFine);
  EXPECT_EQ(r.latency.count, 3u);
  ASSERT_EQ(r.latency_by_station.size(), 2u);
  EXPECT_EQ(r.latency_by_station[0].station, 2);
  EXPECT_EQ(r.latency_by_station[0].latency.count, 1u);
  EXPECT_DOUBLE_EQ(r.latency_by_station[0].latency.mean, 0.100);
  EXPECT_EQ(r.latency_by_station[1].station, 6);
  EXPECT_DOUBLE_EQ(r.latency_by_station[1].latency.mean, 0.030);
  EXPECT_DOUBLE_EQ(r.latency_by_station[1].latency.max, 0.040);
}

TEST(TimingStatisticsTest, PollPeriodAndJitterOfAKnownSchedule) {
  TimingStatistics stats(BusTiming(9600));
  const double polls[] = {10.0, 11.0, 12.1, 12.9, 14.0};  // periods 1.0 1.1 0.8 1.1
  std::uint64_t id = 0;
  for (double t : polls) {
    stats.add_frame(rtu_frame(++id, t, t + 0.008));
    FrameTiming reply = rtu_frame(++id, t + 0.05, t + 0.06);
    reply.role = Role::Response;  // replies must not count as polls
    stats.add_frame(reply);
    FrameTiming other = rtu_frame(++id, t + 0.1, t + 0.108);
    other.function = 0x04;  // another function of the same station is a separate schedule
    stats.add_frame(other);
  }
  const TimingReport r = stats.report(kFine);
  ASSERT_EQ(r.poll_periods.size(), 2u);
  const PollPeriod& p = r.poll_periods[0];
  EXPECT_EQ(p.block.station, 1);
  EXPECT_EQ(p.block.function, 0x03);
  EXPECT_EQ(p.period.intervals, 4u);
  EXPECT_NEAR(p.period.mean, 1.0, 1e-12);
  EXPECT_NEAR(p.period.min, 0.8, 1e-12);
  EXPECT_NEAR(p.period.max, 1.1, 1e-12);
  EXPECT_NEAR(p.period.stddev, std::sqrt((0.0 + 0.01 + 0.04 + 0.01) / 4), 1e-12);
  EXPECT_NEAR(p.period.max_deviation, 0.2, 1e-12);
  EXPECT_EQ(r.poll_periods[1].block.function, 0x04);
  EXPECT_EQ(r.poll_periods[1].period.intervals, 4u);
}

FrameTiming block_read(std::uint64_t id, double start, std::uint16_t address, std::uint16_t count) {
  FrameTiming f = rtu_frame(id, start, start + 0.008);
  f.start = address;
  f.count = count;
  return f;
}

// The case: four FC 0x03 blocks of one station every 5 s. Keyed by station and
// function alone, this was one "period" of 1.25 s with a jitter of seconds.
TEST(TimingStatisticsTest, EachPollBlockHasItsOwnPeriod) {
  TimingStatistics stats(BusTiming(9600));
  const std::uint16_t blocks[][2] = {{1000, 10}, {1030, 4}, {1050, 46}, {1100, 8}};
  std::uint64_t id = 0;
  for (int round = 0; round < 12; ++round) {
    for (int b = 0; b < 4; ++b) {
      const double t = 100.0 + 5.0 * round + 0.3 * b + (round % 2 == 0 ? 0.0 : 0.002);
      stats.add_frame(block_read(++id, t, blocks[b][0], blocks[b][1]));
    }
  }
  const TimingReport r = stats.report(kFine);
  ASSERT_EQ(r.poll_periods.size(), 4u);
  for (std::size_t b = 0; b < 4; ++b) {
    const PollPeriod& p = r.poll_periods[b];  // sorted by start address
    EXPECT_EQ(p.block.dialect, Dialect::Gsl);
    EXPECT_EQ(p.block.station, 1);
    EXPECT_EQ(p.block.function, 0x03);
    EXPECT_EQ(p.block.start, blocks[b][0]);
    EXPECT_EQ(p.block.count, blocks[b][1]);
    EXPECT_EQ(p.period.intervals, 11u);
    // Intervals alternate 5.002 s and 4.998 s: 6 of one, 5 of the other.
    EXPECT_NEAR(p.period.mean, 5.0 + 0.002 / 11, 1e-9);
    EXPECT_LT(p.period.stddev, 0.0021);
    EXPECT_GT(p.period.stddev, 0.0019);
    EXPECT_NEAR(p.period.max_deviation, 0.002 + 0.002 / 11, 1e-9);
  }
  EXPECT_EQ(r.untracked_poll_requests, 0u);
}

// The same function and start with another count, or another start, is another block; a
// request without start or count (a one-register write has no count, an unknown function
// neither) keys with the field absent, apart from a request whose field is 0.
TEST(TimingStatisticsTest, AbsentStartOrCountIsItsOwnKeyApartFromZero) {
  TimingStatistics stats(BusTiming(9600));
  std::uint64_t id = 0;
  for (int i = 0; i < 3; ++i) {
    const double t = 10.0 + 2.0 * i;
    stats.add_frame(block_read(++id, t, 0, 0));
    stats.add_frame(block_read(++id, t + 0.1, 0, 1));
    FrameTiming write = rtu_frame(++id, t + 0.2, t + 0.208);
    write.function = 0x06;
    write.start = 0;  // a one-register write names its register and no count
    stats.add_frame(write);
    FrameTiming unknown = rtu_frame(++id, t + 0.3, t + 0.308);
    unknown.function = 0x03;  // keyed as a frame of an unknown function: no start, no count
    stats.add_frame(unknown);
  }
  const TimingReport r = stats.report(kFine);
  ASSERT_EQ(r.poll_periods.size(), 4u);
  // Sorted by function, then start, then count, an absent field first.
  EXPECT_EQ(r.poll_periods[0].block.start, std::nullopt);
  EXPECT_EQ(r.poll_periods[0].block.count, std::nullopt);
  EXPECT_EQ(r.poll_periods[1].block.start, std::optional<std::uint16_t>(0));
  EXPECT_EQ(r.poll_periods[1].block.count, std::optional<std::uint16_t>(0));
  EXPECT_EQ(r.poll_periods[2].block.count, std::optional<std::uint16_t>(1));
  EXPECT_EQ(r.poll_periods[3].block.function, 0x06);
  EXPECT_EQ(r.poll_periods[3].block.start, std::optional<std::uint16_t>(0));
  EXPECT_EQ(r.poll_periods[3].block.count, std::nullopt);
  for (const PollPeriod& p : r.poll_periods) {
    EXPECT_EQ(p.period.intervals, 2u);
    EXPECT_NEAR(p.period.mean, 2.0, 1e-9);
    EXPECT_NEAR(p.period.stddev, 0.0, 1e-9);
  }
}

// A damaged request's fields cannot be trusted: it is in no block, not even its own.
TEST(TimingStatisticsTest, BadCheckRequestIsInNoPollBlock) {
  TimingStatistics stats(BusTiming(9600));
  stats.add_frame(block_read(1, 10.0, 1000, 10));
  FrameTiming damaged = block_read(2, 15.0, 1000, 10);
  damaged.check_ok = false;
  stats.add_frame(damaged);
  FrameTiming damaged_elsewhere = block_read(3, 16.0, 9000, 10);
  damaged_elsewhere.check_ok = false;
  stats.add_frame(damaged_elsewhere);
  stats.add_frame(block_read(4, 20.0, 1000, 10));
  const TimingReport r = stats.report(kFine);
  ASSERT_EQ(r.poll_periods.size(), 1u);
  EXPECT_EQ(r.poll_periods[0].period.intervals, 1u);
  EXPECT_NEAR(r.poll_periods[0].period.mean, 10.0, 1e-9);
  EXPECT_EQ(r.poll_periods[0].period.stddev, 0.0);
  EXPECT_EQ(r.poll_periods[0].period.max_deviation, 0.0);
}

// Memory is bounded by the number of blocks: past the cap, requests of new blocks are only
// counted, while the blocks already tracked go on.
TEST(TimingStatisticsTest, PollBlocksAreCappedAndTheRestCounted) {
  TimingStatistics stats(BusTiming(9600));
  const std::size_t cap = TimingStatistics::kMaxPollBlocks;
  std::uint64_t id = 0;
  double t = 0;
  for (std::size_t i = 0; i < cap + 10; ++i) {
    stats.add_frame(block_read(++id, t += 0.01, static_cast<std::uint16_t>(i), 1));
  }
  stats.add_frame(block_read(++id, t += 0.01, 0, 1));  // tracked: a second poll
  stats.add_frame(block_read(++id, t += 0.01, 0, 2));  // new: not tracked
  stats.add_frame(block_read(++id, t += 0.01, static_cast<std::uint16_t>(cap), 1));  // nor this
  const TimingReport r = stats.report(kFine);
  ASSERT_EQ(r.poll_periods.size(), cap);
  EXPECT_EQ(r.untracked_poll_requests, 12u);
  EXPECT_EQ(r.poll_periods[0].block.start, std::optional<std::uint16_t>(0));
  EXPECT_EQ(r.poll_periods[0].period.intervals, 1u);
  EXPECT_EQ(r.poll_periods.back().block.start, static_cast<std::uint16_t>(cap - 1));
}

TEST(TimingStatisticsTest, SteadyScheduleHasNoJitter) {
  IntervalSeries s;
  for (int i = 0; i < 6; ++i) s.add_event(2.0 + 0.5 * i);
  const IntervalSummary sum = s.summary();
  EXPECT_EQ(sum.intervals, 5u);
  EXPECT_NEAR(sum.mean, 0.5, 1e-12);
  EXPECT_NEAR(sum.stddev, 0.0, 1e-12);
  EXPECT_NEAR(sum.max_deviation, 0.0, 1e-12);
}

TEST(TimingStatisticsTest, RtuRuleViolationsAreCounted) {
  const BusTiming timing(9600);  // t1.5 = 1.5625 ms, t3.5 = 3.646 ms
  TimingStatistics stats(timing);
  stats.add_frame(rtu_frame(1, 0.000, 0.008, 0.0010));  // inner gap fine
  stats.add_frame(rtu_frame(2, 0.013, 0.021, 0.0020));  // inner gap > t1.5; spacing 5 ms fine
  stats.add_frame(rtu_frame(3, 0.023, 0.031, 0.0001));  // spacing 2 ms < t3.5
  stats.add_frame(rtu_frame(4, 0.032, 0.040, 0.0030));  // both rules broken
  FrameTiming ascii = rtu_frame(5, 0.041, 0.056, 0.0100);
  ascii.dialect = Dialect::Ascii;  // ASCII is delimited, neither rule applies
  stats.add_frame(ascii);
  stats.add_frame(rtu_frame(6, 0.057, 0.065, 0.0));  // after ASCII: not an RTU spacing
  const TimingReport r = stats.report(kFine);
  ASSERT_TRUE(r.bus.measurable);
  EXPECT_DOUBLE_EQ(r.bus.t15, timing.t15);
  EXPECT_DOUBLE_EQ(r.bus.t35, timing.t35);
  EXPECT_EQ(r.bus.inner_gap_t15.count, 2u);
  EXPECT_EQ(r.bus.inner_gap_t15.example_ids, (std::vector<std::uint64_t>{2, 4}));
  EXPECT_EQ(r.bus.spacing_t35.count, 2u);
  EXPECT_EQ(r.bus.spacing_t35.example_ids, (std::vector<std::uint64_t>{3, 4}));
  EXPECT_EQ(r.bus.gaps.count, 5u);
  EXPECT_NEAR(r.bus.gaps.min, 0.001, 1e-12);
  EXPECT_NEAR(r.bus.gaps.max, 0.005, 1e-12);
}

TEST(TimingStatisticsTest, ExampleIdsAreBounded) {
  TimingStatistics stats(BusTiming(9600));
  for (std::uint64_t i = 0; i < 50; ++i) {
    const double t = 0.02 * static_cast<double>(i);
    stats.add_frame(rtu_frame(i, t, t + 0.008, 0.005));
  }
  const TimingReport r = stats.report(kFine);
  EXPECT_EQ(r.bus.inner_gap_t15.count, 50u);
  EXPECT_EQ(r.bus.inner_gap_t15.example_ids.size(), BusGapStatistics::kMaxExamples);
}

TEST(TimingStatisticsTest, CoarseTimestampsMakeGapsNotMeasurable) {
  TimingStatistics stats(BusTiming(9600));
  stats.add_frame(rtu_frame(1, 0.000, 0.008, 0.004));
  stats.add_frame(rtu_frame(2, 0.009, 0.017, 0.004));
  stats.add_latency(1, 0.016);
  const TimingReport r = stats.report({false, "chunked timestamps from a USB adapter", ""});
  EXPECT_FALSE(r.bus.measurable);
  EXPECT_EQ(r.bus.not_measurable_reason, "chunked timestamps from a USB adapter");
  EXPECT_EQ(r.bus.inner_gap_t15.count, 0u);
  EXPECT_EQ(r.bus.spacing_t35.count, 0u);
  EXPECT_EQ(r.bus.gaps.count, 0u);
  EXPECT_EQ(r.latency.count, 1u) << "latencies are still reported";

  const TimingReport fine = stats.report(kFine);
  EXPECT_TRUE(fine.bus.measurable);
  EXPECT_EQ(fine.bus.inner_gap_t15.count, 2u);
  EXPECT_EQ(fine.bus.spacing_t35.count, 1u);
}

}  // namespace
}  // namespace pvtap
