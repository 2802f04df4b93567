// FlowProbe: whether a flow carries inverter frames, decided from its first bytes.
#include "pvtap/carriers/flow_probe.h"

#include <gtest/gtest.h>

#include "pvtap/carriers/solarman_v5_frame.h"

#include <string>
#include <vector>

namespace pvtap {
namespace {

using Bytes = std::vector<std::uint8_t>;

const Bytes kRequest = {0x01, 0x03, 0x00, 0x00, 0x00, 0x0A, 0xC5, 0xCD};
const Bytes kAsciiRequest = {0x05, 0x30, 0x31, 0x52, 0x30, 0x30, 0x30, 0x34,
                             0x30, 0x34, 0x30, 0x31, 0x64, 0x62, 0x04};

TEST(FlowProbe, TwoGoodFramesMakeABus) {
  FlowProbe probe(DialectSet::all());
  EXPECT_EQ(probe.add_data(Direction::ToSlave, kRequest, 1.0), FlowProbe::Verdict::Undecided);
  EXPECT_EQ(probe.add_data(Direction::ToSlave, kAsciiRequest, 2.0), FlowProbe::Verdict::Bus);
  ASSERT_EQ(probe.items().size(), 2u);  // kept for replay
  EXPECT_EQ(probe.items()[1].bytes, kAsciiRequest);
}

TEST(FlowProbe, FramesSplitAcrossSegmentsAreFoundAndCountedOnce) {
  FlowProbe probe(DialectSet::all());
  const Bytes first(kRequest.begin(), kRequest.begin() + 3);
  const Bytes rest(kRequest.begin() + 3, kRequest.end());
  EXPECT_EQ(probe.add_data(Direction::ToSlave, first, 1.0), FlowProbe::Verdict::Undecided);
  EXPECT_EQ(probe.add_data(Direction::ToSlave, rest, 1.0), FlowProbe::Verdict::Undecided);
  EXPECT_EQ(probe.add_data(Direction::ToSlave, Bytes{0x41}, 1.1), FlowProbe::Verdict::Undecided);
  EXPECT_EQ(probe.final_verdict(), FlowProbe::Verdict::Bus);  // one frame at the end suffices
}

// MBAP: transaction 1, protocol 0, length 6, unit 1, read holding 0x0000 x 10; its reply.
const Bytes kMbapRequest = {0x00, 0x01, 0x00, 0x00, 0x00, 0x06, 0x01, 0x03, 0x00, 0x00, 0x00, 0x0A};
const Bytes kMbapException = {0x00, 0x01, 0x00, 0x00, 0x00, 0x03, 0x01, 0x83, 0x0B};

TEST(FlowProbe, TwoPiecesOfWholeMbapAdusMakeAModbusTcpFlow) {
  FlowProbe probe(DialectSet::all());
  EXPECT_EQ(probe.add_data(Direction::ToSlave, kMbapRequest, 1.0), FlowProbe::Verdict::Undecided);
  EXPECT_EQ(probe.add_data(Direction::FromSlave, kMbapException, 1.1), FlowProbe::Verdict::Mbap);
  FlowProbe one(DialectSet::all());
  one.add_data(Direction::ToSlave, kMbapRequest, 1.0);
  EXPECT_EQ(one.final_verdict(), FlowProbe::Verdict::Mbap);  // one at the end suffices
  FlowProbe cut(DialectSet::all());
  cut.add_data(Direction::ToSlave, Bytes(kMbapRequest.begin(), kMbapRequest.end() - 1), 1.0);
  EXPECT_EQ(cut.final_verdict(), FlowProbe::Verdict::NotBus);
}

TEST(FlowProbe, TextTrafficIsNotABus) {
  FlowProbe probe(DialectSet::all());
  const std::string line = "GET /index.html HTTP/1.1\r\nHost: portal\r\n\r\n";
  FlowProbe::Verdict v = FlowProbe::Verdict::Undecided;
  for (int i = 0; i < 500 && v == FlowProbe::Verdict::Undecided; ++i) {
    v = probe.add_data(Direction::ToSlave, Bytes(line.begin(), line.end()), i);
  }
  EXPECT_EQ(v, FlowProbe::Verdict::NotBus);
  FlowProbe short_text(DialectSet::all());
  short_text.add_data(Direction::FromSlave, Bytes(line.begin(), line.end()), 0);
  EXPECT_EQ(short_text.final_verdict(), FlowProbe::Verdict::NotBus);
}

TEST(FlowProbe, FramesNeverJoinAcrossAGap) {
  FlowProbe probe(DialectSet::all());
  probe.add_data(Direction::ToSlave, Bytes(kRequest.begin(), kRequest.begin() + 4), 1.0);
  probe.add_gap(Direction::ToSlave, 10, 1.1);
  probe.add_data(Direction::ToSlave, Bytes(kRequest.begin() + 4, kRequest.end()), 1.2);
  EXPECT_EQ(probe.final_verdict(), FlowProbe::Verdict::NotBus);
  EXPECT_TRUE(probe.items()[1].gap);
}

TEST(FlowProbe, OnlyTheChosenDialectsCount) {
  FlowProbe probe(DialectSet::only(Dialect::Hybrid));
  probe.add_data(Direction::ToSlave, kRequest, 1.0);
  probe.add_data(Direction::ToSlave, kAsciiRequest, 1.0);
  EXPECT_EQ(probe.final_verdict(), FlowProbe::Verdict::NotBus);
}

// A logger stick's request around kRequest: the RTU frame inside must not make it a bare bus.
Bytes v5_request() {
  using namespace solarman_v5;
  return encode_frame(Header{0, control::kRequest, 1, 2712345678u}, request_payload(kRequest));
}

TEST(FlowProbe, AWholeFirstV5FrameMakesALoggerStickFlow) {
  FlowProbe probe(DialectSet::all());
  const Bytes frame = v5_request();
  const Bytes head(frame.begin(), frame.begin() + 20);
  const Bytes rest(frame.begin() + 20, frame.end());
  EXPECT_EQ(probe.add_data(Direction::ToSlave, head, 1.0), FlowProbe::Verdict::Undecided);
  EXPECT_EQ(probe.add_data(Direction::ToSlave, rest, 1.0), FlowProbe::Verdict::SolarmanV5);
  EXPECT_EQ(probe.items().size(), 2u);
}

TEST(FlowProbe, BareFramesWaitWhileAV5FrameMayBeOpening) {
  // Two RTU frames would make a bus, but the other direction opened like a V5 frame.
  FlowProbe probe(DialectSet::all());
  const Bytes frame = v5_request();
  EXPECT_EQ(probe.add_data(Direction::FromSlave, Bytes(frame.begin(), frame.begin() + 12), 1.0),
            FlowProbe::Verdict::Undecided);
  EXPECT_EQ(probe.add_data(Direction::ToSlave, kRequest, 1.1), FlowProbe::Verdict::Undecided);
  EXPECT_EQ(probe.add_data(Direction::ToSlave, kAsciiRequest, 1.2), FlowProbe::Verdict::Undecided);
  EXPECT_EQ(probe.add_data(Direction::FromSlave, Bytes(30, 0x00), 1.3), FlowProbe::Verdict::Bus);
}

TEST(FlowProbe, AFlowOnAPortIsABusUnlessItOpensWithV5) {
  FlowProbe bare(DialectSet::all(), true);
  EXPECT_EQ(bare.add_data(Direction::ToSlave, kRequest, 1.0), FlowProbe::Verdict::Bus);
  FlowProbe stick(DialectSet::all(), true);
  EXPECT_EQ(stick.add_data(Direction::ToSlave, v5_request(), 1.0), FlowProbe::Verdict::SolarmanV5);
}

}  // namespace
}  // namespace pvtap
