// The comparison behind `pvtap diff` on summaries built by hand: what counts as a difference,
// and what is the noise of sampling.
#include "diff/capture_diff.h"

#include <gtest/gtest.h>

namespace pvtap::analyzer {
namespace {

StationSummary station(std::uint8_t address, std::uint64_t requests, std::uint64_t bad_checks) {
  StationSummary s;
  s.station = address;
  s.requests = requests;
  s.responses = requests;
  s.bad_checks = bad_checks;
  return s;
}

DiffSide side(std::vector<StationSummary> stations, double seconds = 300) {
  DiffSide s;
  BusFindings bus;
  bus.report.first_time = 1000;
  bus.report.last_time = 1000 + seconds;
  for (const StationSummary& st : stations) bus.report.bytes.frames += st.requests * 2;
  bus.report.stations = std::move(stations);
  s.report.buses.push_back(std::move(bus));
  return s;
}

TEST(PoissonNoise, SameRatesAreNoise) {
  EXPECT_FALSE(beyond_poisson_noise(10, 1000, 10, 1000, 3));
  EXPECT_FALSE(beyond_poisson_noise(0, 1000, 0, 1000, 3));
  // Rates, not counts: twice the frames with twice the events is the same rate.
  EXPECT_FALSE(beyond_poisson_noise(10, 1000, 20, 2000, 3));
}

TEST(PoissonNoise, FewEventsAreNoiseManyAreNot) {
  // 3 of 250 against none: well within the noise of such small counts.
  EXPECT_FALSE(beyond_poisson_noise(3, 250, 0, 250, 3));
  EXPECT_TRUE(beyond_poisson_noise(30, 250, 0, 250, 3));
  EXPECT_FALSE(beyond_poisson_noise(30, 250, 0, 0, 3));  // no frames: no rate
}

TEST(CompareSides, ASideAgainstItselfDiffersInNothing) {
  const DiffSide a = side({station(1, 500, 25), station(2, 500, 0)});
  EXPECT_TRUE(compare_sides(a, a, DiffThresholds{}).differences.empty());
}

TEST(CompareSides, BadChecksGoneAreNamedForTheirStation) {
  const DiffSide before = side({station(1, 500, 40), station(2, 500, 1)});
  const DiffSide after = side({station(1, 480, 0), station(2, 480, 0)});
  const DiffResult r = compare_sides(before, after, DiffThresholds{});
  ASSERT_EQ(r.differences.size(), 1u);
  const Difference& d = r.differences.front();
  EXPECT_EQ(d.bus, "serial");
  EXPECT_EQ(d.station, 1);
  EXPECT_EQ(d.what, "bad_checks_per_1000_frames");
  EXPECT_NEAR(*d.before, 40.0 / 1040 * 1000, 1e-9);
  EXPECT_EQ(*d.after, 0);
  EXPECT_TRUE(d.counted);
  EXPECT_EQ(r.counted(), 1u);
}

TEST(CompareSides, AStationThatVanishedIsNamed) {
  const DiffResult r = compare_sides(side({station(1, 500, 0), station(3, 500, 0)}),
                                     side({station(1, 500, 0)}), DiffThresholds{});
  ASSERT_EQ(r.differences.size(), 1u);
  EXPECT_EQ(r.differences.front().what, "station");
  EXPECT_EQ(r.differences.front().station, 3);
  EXPECT_FALSE(r.differences.front().after.has_value());
}

TEST(CompareSides, RequestsPerMinuteNotCountsCompare) {
  // Half the capture, half the requests: the same polling.
  const DiffResult same =
      compare_sides(side({station(1, 600, 0)}, 600), side({station(1, 300, 0)}, 300), {});
  EXPECT_TRUE(same.differences.empty());
  // The same length, half the requests: the master polls less.
  const DiffResult fewer =
      compare_sides(side({station(1, 600, 0)}, 600), side({station(1, 300, 0)}, 600), {});
  ASSERT_EQ(fewer.differences.size(), 1u);
  EXPECT_EQ(fewer.differences.front().what, "requests_per_minute");
}

TEST(CompareSides, RegisterMovesAreReportedAndCountedOnlyWhenAsked) {
  DiffSide before = side({station(1, 500, 0)});
  DiffSide after = side({station(1, 500, 0)});
  const RegisterKey key{"", 1, Dialect::Gsl, 0x0406};
  before.ranges[key] = ValueRange{0, 1, 10, "alarm word 1", ""};
  after.ranges[key] = ValueRange{0, 8, 10, "alarm word 1", ""};
  const RegisterKey steady{"", 1, Dialect::Gsl, 0x0410};
  before.ranges[steady] = ValueRange{200, 300, 10, "voltage", "V"};
  after.ranges[steady] = ValueRange{210, 320, 10, "voltage", "V"};  // within 10 % of 300
  DiffThresholds t;
  const DiffResult reported = compare_sides(before, after, t);
  ASSERT_EQ(reported.differences.size(), 1u);
  EXPECT_EQ(reported.differences.front().what, "register_range");
  EXPECT_EQ(reported.counted(), 0u);
  t.count_values = true;
  EXPECT_EQ(compare_sides(before, after, t).counted(), 1u);
}

}  // namespace
}  // namespace pvtap::analyzer
