// Unit tests of the simulator's LAN carriers: V5 frames as the protocol notes lay them out,
// carrier fault plans, and sessions whose drops, quirks and gateway exceptions are what the
// ground truth counts.
#include <gtest/gtest.h>

#include <algorithm>

#include "bus/bus_master.h"
#include "lan/carrier_faults.h"
#include "lan/mbap_session.h"
#include "lan/v5_frame.h"
#include "lan/v5_session.h"

namespace pvtap::sim {
namespace {

std::uint64_t count(const LanTruth& truth, const std::string& key) {
  for (const auto& [name, value] : truth.counts)
    if (name == key) return value;
  ADD_FAILURE() << "no count " << key;
  return 0;
}

std::size_t responses(const BusTimeline& t) {
  return static_cast<std::size_t>(std::count_if(t.events.begin(), t.events.end(),
                                                [](auto& e) { return e.role == Role::Response; }));
}

SimConfig clean_bus(const char* faults) {
  SimConfig c;
  c.seed = 3;
  c.dialects = {Dialect::Gsl, Dialect::Hybrid};
  c.duration_s = 20;
  std::string error;
  c.faults = *parse_fault_plan(faults, error);
  return c;
}

TEST(V5Frame, HeaderChecksumAndEndAsTheNotesSay) {
  const std::vector<std::uint8_t> payload{0xAA};
  // Worked by hand: 01+00+10+45+12+00+04+03+02+01+AA = 0x11C, the checksum 0x1C.
  const std::vector<std::uint8_t> expected{0xA5, 0x01, 0x00, 0x10, 0x45, 0x12, 0x00,
                                           0x04, 0x03, 0x02, 0x01, 0xAA, 0x1C, 0x15};
  EXPECT_EQ(v5_frame(v5_control::kRequest, 0x12, 0x00, 0x01020304u, payload), expected);
}

TEST(V5Frame, PayloadsWrapTheRtuFrame) {
  const std::vector<std::uint8_t> rtu{0x01, 0x03, 0x00, 0x00, 0x00, 0x01, 0x84, 0x0A};
  const auto request = solarman_v5::request_payload(rtu);
  ASSERT_EQ(request.size(), 15 + rtu.size());
  EXPECT_EQ(request[0], 0x02);
  EXPECT_TRUE(std::equal(rtu.begin(), rtu.end(), request.begin() + 15));
  const auto reply = v5_response_payload(rtu, {1, 2, 3}, 2);
  ASSERT_EQ(reply.size(), 14 + rtu.size() + 2);
  EXPECT_EQ(reply[1], 0x01) << "status";
  EXPECT_EQ(reply[6], 2) << "power-on time, little-endian";
  EXPECT_EQ(reply[reply.size() - 1], 0);
  EXPECT_EQ(reply[reply.size() - 2], 0);
  EXPECT_EQ(reply[reply.size() - 3], 0x0A) << "the CRC's last byte before the quirk";
}

TEST(CarrierFaults, ParsesKnownKindsOnly) {
  std::string error;
  const auto f = parse_carrier_faults("quirk=20,drop=3", v5_fault_kinds(), error);
  ASSERT_TRUE(f);
  EXPECT_EQ((*f)["quirk"], 20u);
  EXPECT_EQ((*f)["split"], 0u);
  EXPECT_FALSE(parse_carrier_faults("pipeline=5", v5_fault_kinds(), error));
  EXPECT_FALSE(parse_carrier_faults("quirk=101", v5_fault_kinds(), error));
  EXPECT_NE(error.find("quirk drop"), std::string::npos) << error;
}

TEST(V5Session, ADroppedReplyIsGoneAndItsRequestATimeout) {
  BusTimeline t = BusMaster(clean_bus("none")).run();
  const std::size_t replies = responses(t);
  ASSERT_GT(replies, 10u);
  V5Options o;
  o.faults.percent["drop"] = 100;
  const LanCapture lan = plan_v5_session(t, o, clean_bus("none").start, 3);
  EXPECT_EQ(responses(t), 0u);
  EXPECT_EQ(t.timeouts.size() + t.unanswered_at_end.size(), replies);
  EXPECT_EQ(count(lan.truth, "dropped_replies"), replies);
  EXPECT_EQ(count(lan.truth, "responses"), 0u);
  EXPECT_EQ(static_cast<std::size_t>(std::count_if(t.faults.begin(), t.faults.end(),
                                                   [](auto& f) { return f.kind == "stick_drop"; })),
            replies);
}

TEST(V5Session, EveryQuirkIsTwoBytesOfAReply) {
  BusTimeline t = BusMaster(clean_bus("none")).run();
  V5Options o;
  o.faults.percent["quirk"] = 100;
  const LanCapture lan = plan_v5_session(t, o, clean_bus("none").start, 3);
  EXPECT_EQ(count(lan.truth, "quirk_bytes"), 2 * responses(t));
  EXPECT_EQ(count(lan.truth, "frames"), t.events.size());
}

TEST(MbapSession, TheGatewayAnswersEveryBusTimeoutWith0x0B) {
  BusTimeline t = BusMaster(clean_bus("missing=30")).run();
  ASSERT_GT(t.timeouts.size(), 2u);
  const LanCapture lan = plan_mbap_session(t, MbapOptions{}, 3);
  EXPECT_EQ(count(lan.truth, "gateway_exceptions"), t.timeouts.size());
  EXPECT_EQ(count(lan.truth, "responses"), responses(t) + t.timeouts.size());
  std::size_t exceptions = 0;
  for (const LanSegment& s : lan.segments)
    if (!s.from_client && s.payload.size() == 9 && s.payload[8] == 0x0B) ++exceptions;
  EXPECT_EQ(exceptions, t.timeouts.size());
}

}  // namespace
}  // namespace pvtap::sim
