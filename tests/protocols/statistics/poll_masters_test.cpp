// Masters told apart by their poll cycles: the cycle of a block, the grouping of blocks into
// masters, and the requests sent while another request's reply was due.
#include "pvtap/statistics/poll_masters.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <vector>

#include "pvtap/statistics/bus_timing.h"
#include "pvtap/statistics/timing_statistics.h"

namespace pvtap {
namespace {

TEST(ModalInterval, ACycleSurvivesRoundsThatOverran) {
  ModalInterval m;
  for (int i = 0; i < 40; ++i) m.add(i % 5 == 4 ? 2.3 : 1.0 + 0.01 * (i % 3));
  ASSERT_TRUE(m.cycle());
  EXPECT_NEAR(*m.cycle(), 1.01, 0.02);
}

TEST(ModalInterval, IntervalsAllOverThePlaceHaveNoCycle) {
  ModalInterval m;
  for (int i = 0; i < 40; ++i) m.add(1.0 + 0.17 * (i % 9));
  EXPECT_FALSE(m.cycle());
  EXPECT_TRUE(m.mode());
}

TEST(CoarseMedian, MedianWithinItsBin) {
  CoarseMedian c;
  for (int i = 0; i < 9; ++i) c.add(0.040);
  c.add(0.9);
  ASSERT_TRUE(c.median());
  EXPECT_NEAR(*c.median(), 0.040, 0.040 * 0.4);
  EXPECT_FALSE(CoarseMedian{}.median());
}

// A bus of requests (no replies) at the given times: station, start address, time.
struct Poll {
  std::uint8_t station;
  std::uint16_t start;
  double time;
};

TimingReport timing_of(std::vector<Poll> polls) {
  std::sort(polls.begin(), polls.end(), [](auto& a, auto& b) { return a.time < b.time; });
  TimingStatistics stats(BusTiming(9600, 10));
  std::uint64_t id = 0;
  for (const Poll& p : polls) {
    FrameTiming f;
    f.id = id++;
    f.station = p.station;
    f.function = 3;
    f.start = p.start;
    f.count = 4;
    f.start_time = p.time;
    f.end_time = p.time + 0.008;
    stats.add_frame(f);
  }
  return stats.report(TimestampQuality{});
}

// One master reads two stations every second, now and then a round late; a fast block every
// round and a slow one every fifth round are still one master.
std::vector<Poll> one_master(double first, double period, std::uint8_t station_base) {
  std::vector<Poll> out;
  double t = first;
  for (int round = 0; round < 60; ++round) {
    out.push_back({station_base, 1030, t});
    out.push_back({static_cast<std::uint8_t>(station_base + 1), 1030, t + 0.2});
    if (round % 5 == 0) out.push_back({station_base, 1000, t + 0.4});
    t += round % 7 == 6 ? period * 1.8 : period;
  }
  return out;
}

TEST(RecogniseMasters, OneMasterWithFastAndSlowBlocksIsOne) {
  const TimingReport r = timing_of(one_master(0.0, 1.0, 1));
  ASSERT_EQ(r.masters.size(), 1u);
  EXPECT_NEAR(r.masters[0].period, 1.0, 0.02);
  EXPECT_EQ(r.masters[0].polls.size(), 3u);
  EXPECT_DOUBLE_EQ(r.masters[0].share, 1.0);
}

TEST(RecogniseMasters, TwoIndependentCyclesAreTwoMastersEvenOnOneStation) {
  std::vector<Poll> bus = one_master(0.0, 1.0, 1);
  // A second logger reads station 1 too, with a block of its own, every 1.37 s.
  for (int i = 0; i < 40; ++i) bus.push_back({1, 1086, 0.55 + 1.37 * i});
  const TimingReport r = timing_of(bus);
  ASSERT_EQ(r.masters.size(), 2u);
  EXPECT_NEAR(r.masters[0].period, 1.0, 0.02);
  EXPECT_NEAR(r.masters[1].period, 1.37, 0.03);
  ASSERT_EQ(r.masters[1].polls.size(), 1u);
  EXPECT_EQ(r.poll_periods[r.masters[1].polls[0]].block.start, 1086);
  EXPECT_NEAR(r.masters[0].share + r.masters[1].share, 1.0, 1e-9);
}

TEST(RecogniseMasters, ARequestWhileAReplyWasDueIsCounted) {
  TimingStatistics stats(BusTiming(9600, 10));
  const auto frame = [](std::uint64_t id, Role role, std::uint8_t station, double t) {
    FrameTiming f;
    f.id = id;
    f.role = role;
    f.station = station;
    f.function = 3;
    f.start = 1030;
    f.count = 4;
    f.start_time = t;
    f.end_time = t + 0.008;
    return f;
  };
  stats.add_frame(frame(0, Role::Request, 1, 0.0));
  stats.add_frame(frame(1, Role::Response, 1, 0.048));
  stats.add_latency(1, 0.040);
  // A request 300 ms after one that got no reply: its master gave up. Not counted.
  stats.add_frame(frame(2, Role::Request, 2, 0.1));
  stats.add_frame(frame(3, Role::Request, 1, 0.408));
  EXPECT_EQ(stats.report(TimestampQuality{}).requests_while_reply_due, 0u);
  // A request 5 ms after another, whose reply usually takes 40 ms: counted.
  stats.add_frame(frame(4, Role::Request, 2, 0.421));
  // Its own copy at once (an echoing adapter): not counted.
  stats.add_frame(frame(5, Role::Request, 2, 0.430));
  EXPECT_EQ(stats.report(TimestampQuality{}).requests_while_reply_due, 1u);
}

}  // namespace
}  // namespace pvtap
