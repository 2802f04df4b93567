// TimeBuckets: widening the grid keeps every count, sum, extreme and the newest reading.
#include "html/time_buckets.h"

#include <gtest/gtest.h>

#include <cstddef>
#include <vector>

namespace pvtap::analyzer {
namespace {

// Feeds readings at the given times into one series, halving it whenever the grid widens.
BucketSeries fed(TimeGrid& grid, const std::vector<std::pair<double, double>>& readings) {
  BucketSeries s;
  for (const auto& [time, value] : readings) {
    int doublings = 0;
    const std::size_t index = grid.index_of(time, doublings);
    for (int i = 0; i < doublings; ++i) s.halve();
    s.add(index, value);
  }
  return s;
}

TEST(TimeBuckets, ShortRunsKeepEveryReadingApart) {
  TimeGrid grid;
  const BucketSeries s = fed(grid, {{100.0, 1}, {100.5, 2}, {101.0, 3}});
  EXPECT_DOUBLE_EQ(grid.width(), TimeGrid::kFirstWidth);
  ASSERT_EQ(s.buckets().size(), 5u);
  EXPECT_EQ(s.buckets()[0].count, 1u);
  EXPECT_EQ(s.buckets()[2].last, 2);
  EXPECT_EQ(s.buckets()[4].last, 3);
}

TEST(TimeBuckets, ADayFitsTheBucketsAndLosesNothing) {
  TimeGrid grid;
  std::vector<std::pair<double, double>> readings;
  for (int i = 0; i < 86400 / 5; ++i) readings.emplace_back(1e9 + i * 5.0, i % 7);
  const BucketSeries s = fed(grid, readings);
  ASSERT_LE(s.buckets().size(), TimeGrid::kMaxBuckets);
  EXPECT_GT(s.buckets().size(), TimeGrid::kMaxBuckets / 2);
  std::uint64_t count = 0;
  double sum = 0, min = 1e9, max = -1e9;
  for (const Bucket& b : s.buckets()) {
    count += b.count;
    sum += b.sum;
    if (b.count > 0) {
      min = std::min(min, b.min);
      max = std::max(max, b.max);
    }
  }
  double expected_sum = 0;
  for (const auto& r : readings) expected_sum += r.second;
  EXPECT_EQ(count, readings.size());
  EXPECT_DOUBLE_EQ(sum, expected_sum);
  EXPECT_EQ(min, 0);
  EXPECT_EQ(max, 6);
  // The last bucket's last reading is the newest of the run, exactly.
  EXPECT_EQ(s.buckets().back().last, readings.back().second);
}

TEST(TimeBuckets, AnEmptyBucketTakesTheNextOnesReadings) {
  Bucket empty, later;
  later.add(4);
  later.add(2);
  empty.absorb(later);
  EXPECT_EQ(empty.count, 2u);
  EXPECT_EQ(empty.min, 2);
  EXPECT_EQ(empty.max, 4);
  EXPECT_EQ(empty.last, 2);
}

}  // namespace
}  // namespace pvtap::analyzer
