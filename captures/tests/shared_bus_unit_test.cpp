// Unit tests of the simulator's shared bus: two masters whose exchanges collide, a second
// device at one inverter's address, an adapter that echoes every request.
#include <gtest/gtest.h>

#include <algorithm>
#include <set>

#include "bus/bus_master.h"

namespace pvtap::sim {
namespace {

SimConfig shared_bus(unsigned masters) {
  SimConfig c;
  c.seed = 37;
  c.inverters = 2;
  c.period_s = 1.0;
  c.timeout_s = 0.3;
  c.duration_s = 30;
  c.masters = masters;
  return c;
}

bool on_the_line(const BusEvent& e) {
  return e.fault != "echo";
}

TEST(SharedBus, TwoMastersCollideAndNothingOverlapsOnTheLine) {
  const BusTimeline t = BusMaster(shared_bus(2)).run();
  ASSERT_EQ(t.masters.size(), 2u);
  EXPECT_DOUBLE_EQ(t.masters[0].period_s, 1.0);
  EXPECT_DOUBLE_EQ(t.masters[1].period_s, 1.37);
  std::set<int> senders;
  for (const BusEvent& e : t.events)
    if (e.kind == BusEvent::Kind::Frame && e.role == Role::Request) senders.insert(e.master);
  EXPECT_EQ(senders, (std::set<int>{1, 2}));
  ASSERT_FALSE(t.collisions.empty());
  for (const CollisionTruth& c : t.collisions) {
    ASSERT_EQ(c.destroyed.size(), 2u);
    EXPECT_NE(c.destroyed[0].master, c.destroyed[1].master);
    // The garbage takes the place of both transmissions.
    const auto garbage = std::find_if(t.events.begin(), t.events.end(), [&](const BusEvent& e) {
      return e.fault == "collision" && e.start == c.start;
    });
    ASSERT_NE(garbage, t.events.end());
    EXPECT_EQ(garbage->end, c.end);
    EXPECT_EQ(garbage->kind, BusEvent::Kind::Noise);
  }
  const BusEvent* before = nullptr;
  for (const BusEvent& e : t.events) {
    if (!on_the_line(e)) continue;
    if (before) {
      EXPECT_GE(e.start, before->end) << "two transmissions at once at " << e.start;
    }
    before = &e;
  }
}

TEST(SharedBus, AnExchangeLostInACollisionIsNoTimeout) {
  const BusTimeline t = BusMaster(shared_bus(2)).run();
  std::set<Micros> lost;
  for (const CollisionTruth& c : t.collisions)
    for (const DestroyedExchange& x : c.destroyed) lost.insert(x.request_start);
  for (const TimeoutTruth& timeout : t.timeouts) EXPECT_FALSE(lost.count(timeout.request_start));
  // A request whose reply was destroyed is on the line; one destroyed itself is not.
  for (const CollisionTruth& c : t.collisions)
    for (const DestroyedExchange& x : c.destroyed) {
      const bool heard = std::any_of(t.events.begin(), t.events.end(), [&](const BusEvent& e) {
        return e.kind == BusEvent::Kind::Frame && e.start == x.request_start;
      });
      EXPECT_EQ(heard, !x.request_lost);
    }
}

TEST(SharedBus, OneMasterNeverCollides) {
  const BusTimeline t = BusMaster(shared_bus(1)).run();
  EXPECT_TRUE(t.collisions.empty());
  EXPECT_TRUE(t.masters.empty());  // the truth names masters only on a shared bus
}

TEST(SharedBus, ASecondDeviceAtOneAddressAnswersAfterTheFirstWithOtherValues) {
  SimConfig c = shared_bus(1);
  c.address_conflict = 2;
  const BusTimeline t = BusMaster(c).run();
  ASSERT_EQ(t.conflicts.size(), 1u);
  EXPECT_GT(t.conflicts[0].second_replies, 0u);
  std::uint64_t seen = 0;
  for (std::size_t i = 1; i < t.events.size(); ++i) {
    const BusEvent& e = t.events[i];
    if (e.fault != "address_conflict") continue;
    ++seen;
    const BusEvent& first = t.events[i - 1];
    EXPECT_EQ(first.role, Role::Response);
    EXPECT_EQ(first.station, 2);
    EXPECT_EQ(e.station, 2);
    EXPECT_GE(e.start - first.end, 3000);
    EXPECT_GT(e.latency, first.latency);
  }
  EXPECT_EQ(seen, t.conflicts[0].second_replies);
  // Other values: over a run, some pair of replies differs in its bytes.
  bool differs = false;
  for (std::size_t i = 1; i < t.events.size(); ++i)
    if (t.events[i].fault == "address_conflict")
      differs = differs || t.events[i].bytes != t.events[i - 1].bytes;
  EXPECT_TRUE(differs);
}

TEST(SharedBus, AnEchoingAdapterGivesEveryRequestTwiceBackToBack) {
  SimConfig c = shared_bus(1);
  c.echo = true;
  const BusTimeline t = BusMaster(c).run();
  std::uint64_t requests = 0;
  for (std::size_t i = 0; i < t.events.size(); ++i) {
    const BusEvent& e = t.events[i];
    if (e.kind != BusEvent::Kind::Frame || e.role != Role::Request || e.fault == "echo") continue;
    ++requests;
    ASSERT_LT(i + 1, t.events.size());
    const BusEvent& copy = t.events[i + 1];
    EXPECT_EQ(copy.fault, "echo");
    EXPECT_EQ(copy.bytes, e.bytes);
    EXPECT_EQ(copy.start, e.end);
  }
  EXPECT_GT(requests, 0u);
  EXPECT_EQ(t.echoes, requests);
}

}  // namespace
}  // namespace pvtap::sim
