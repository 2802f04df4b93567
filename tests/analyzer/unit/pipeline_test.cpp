// Pipeline with in-memory sources: capture records of each kind, plain bytes and the live
// clock go in; the events and the report come out, without files or devices.
#include "pipeline/pipeline.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "frame_builders.h"
#include "pvtap/codec/frame_codec.h"
#include "pvtap/pcap/exported_pdu_tags.h"
#include "pvtap/pcap/link_types.h"
#include "pvtap/pcap/packet_builder.h"

namespace pvtap::analyzer {
namespace {

using Bytes = std::vector<std::uint8_t>;

// Recorded: what the pipeline handed to its consumer, in order.
struct Recorded : EventWriter {
  struct FrameSeen {
    std::string bus;
    Role role;
    std::optional<double> latency;
  };
  std::vector<FrameSeen> frames;
  std::vector<UnansweredKind> timeouts;
  std::uint64_t noise_bytes = 0;
  std::uint64_t gaps = 0;

  void frame(const EventContext& c, const SessionFrame& f) override {
    frames.push_back({std::string(c.bus), f.role, f.latency});
  }
  void timeout(const EventContext&, const SessionTimeout& t) override {
    timeouts.push_back(t.kind);
  }
  void noise(const EventContext&, const SessionNoise& n) override {
    noise_bytes += n.noise.bytes.size();
  }
  void gap(const EventContext&, const SessionGap&) override { ++gaps; }
};

Bytes request_bytes(std::uint8_t station) {
  return encode_frame(test::read_request(Dialect::Gsl, station, 0x03, 0x041A, 2));
}

Bytes reply_bytes(std::uint8_t station) {
  Frame f = test::frame_of(Dialect::Gsl, Role::Response, station, 0x03);
  f.words = {0x0102, 0x0304};
  f.byte_count = 4;
  return encode_frame(f);
}

CapturedPacket packet(double time, const Bytes& bytes) {
  CapturedPacket p;
  p.time = time;
  p.bytes = bytes;
  p.length_on_wire = static_cast<std::uint32_t>(bytes.size());
  return p;
}

class PipelineTest : public ::testing::Test {
 protected:
  RegisterDecoder decoder_;
  Recorded events_;
  PipelineSettings settings_;
};

TEST_F(PipelineTest, SerialRecordsPairIntoTransactionsWithLatency) {
  Pipeline pipeline(settings_, decoder_, events_);
  pipeline.begin_input(dlt::kUser0, false);
  const Bytes request = request_bytes(1);
  const Bytes reply = reply_bytes(1);
  pipeline.record(packet(100.000, request));
  pipeline.record(packet(100.050, reply));
  pipeline.finish(100.050);

  ASSERT_EQ(events_.frames.size(), 2u);
  EXPECT_EQ(events_.frames[0].role, Role::Request);
  EXPECT_EQ(events_.frames[1].role, Role::Response);
  ASSERT_TRUE(events_.frames[1].latency.has_value());
  EXPECT_GT(*events_.frames[1].latency, 0.0);
  EXPECT_LT(*events_.frames[1].latency, 0.050);
  const AuditReport report = pipeline.report();
  ASSERT_EQ(report.buses.size(), 1u);
  EXPECT_EQ(report.buses[0].name, kSerialBusName);
  EXPECT_EQ(report.totals().transactions, 1u);
  EXPECT_EQ(report.totals().bytes.bytes_in, request.size() + reply.size());
  EXPECT_EQ(pipeline.buses().counts().frames, 2u);
  EXPECT_EQ(report.latency.count, 1u);
}

TEST_F(PipelineTest, TheLiveClockJudgesATimeoutBeforeTheInputEnds) {
  settings_.timeout = 0.5;
  Pipeline pipeline(settings_, decoder_, events_);
  pipeline.begin_input(dlt::kUser0, false);
  const Bytes request = request_bytes(7);
  pipeline.record(packet(50.0, request));
  pipeline.idle(50.2);
  EXPECT_TRUE(events_.timeouts.empty());
  pipeline.idle(51.0);
  ASSERT_EQ(events_.timeouts.size(), 1u);
  EXPECT_EQ(events_.timeouts[0], UnansweredKind::Timeout);
  EXPECT_EQ(pipeline.buses().counts().timeouts, 1u);
  pipeline.finish(51.0);
  EXPECT_EQ(pipeline.report().totals().timeouts, 1u);
}

TEST_F(PipelineTest, GatewayPacketsMakeOneBusPerGatewayEndpoint) {
  Pipeline pipeline(settings_, decoder_, events_);
  pipeline.begin_input(dlt::kEthernet, false);
  const Endpoint master = ipv4_endpoint(10, 0, 0, 1, 50000);
  const Endpoint gateway = ipv4_endpoint(10, 0, 0, 2, 4001);
  std::vector<Bytes> packets;
  std::uint32_t mseq = 1000;
  std::uint32_t sseq = 9000;
  packets.push_back(
      tcp_packet(LinkLayer::Ethernet, {master, gateway}, {mseq - 1, 0, tcp_flag::kSyn}, {}));
  packets.push_back(tcp_packet(LinkLayer::Ethernet, {gateway, master},
                               {sseq - 1, mseq, tcp_flag::kSyn | tcp_flag::kAck}, {}));
  for (int i = 0; i < 4; ++i) {
    const Bytes request = request_bytes(3);
    const Bytes reply = reply_bytes(3);
    packets.push_back(tcp_packet(LinkLayer::Ethernet, {master, gateway},
                                 {mseq, sseq, tcp_flag::kAck | tcp_flag::kPsh}, request));
    mseq += static_cast<std::uint32_t>(request.size());
    packets.push_back(tcp_packet(LinkLayer::Ethernet, {gateway, master},
                                 {sseq, mseq, tcp_flag::kAck | tcp_flag::kPsh}, reply));
    sseq += static_cast<std::uint32_t>(reply.size());
  }
  double t = 10.0;
  for (const Bytes& p : packets) pipeline.record(packet(t += 0.1, p));
  pipeline.finish(t);

  ASSERT_EQ(events_.frames.size(), 8u);
  for (const auto& f : events_.frames) EXPECT_EQ(f.bus, "10.0.0.2:4001");
  const AuditReport report = pipeline.report();
  EXPECT_TRUE(report.network);
  EXPECT_EQ(report.flows.flows_analyzed, 1u);
  EXPECT_EQ(report.totals().transactions, 4u);
}

// Wakes as the live loop does, at each deadline the pipeline gives up to `until`; the number
// of wakes (a deadline that did not move would make them endless).
int wake_at_deadlines(Pipeline& pipeline, double until) {
  int wakes = 0;
  for (std::optional<double> due = pipeline.next_deadline(); due && *due <= until && wakes < 1000;
       due = pipeline.next_deadline()) {
    pipeline.idle(*due);
    ++wakes;
  }
  return wakes;
}

// A live interface: a request segment is missing and nothing more arrives. The hole is given
// up at a deadline the pipeline announces, so that the bytes behind it reach their bus
// without waiting for another segment.
TEST_F(PipelineTest, ALiveTcpHoleIsGivenUpAtItsDeadlineWithoutAnotherSegment) {
  Pipeline pipeline(settings_, decoder_, events_);
  pipeline.begin_input(dlt::kEthernet, false);
  const Endpoint master = ipv4_endpoint(10, 0, 0, 1, 50000);
  const Endpoint gateway = ipv4_endpoint(10, 0, 0, 2, 4001);
  std::uint32_t mseq = 1000;
  std::uint32_t sseq = 9000;
  double t = 10.0;
  for (int i = 0; i < 3; ++i) {
    const Bytes request = request_bytes(3);
    const Bytes reply = reply_bytes(3);
    pipeline.record(packet(t += 0.1, tcp_packet(LinkLayer::Ethernet, {master, gateway},
                                                {mseq, sseq, tcp_flag::kAck}, request)));
    mseq += static_cast<std::uint32_t>(request.size());
    pipeline.record(packet(t += 0.1, tcp_packet(LinkLayer::Ethernet, {gateway, master},
                                                {sseq, mseq, tcp_flag::kAck}, reply)));
    sseq += static_cast<std::uint32_t>(reply.size());
  }
  const Bytes lost = request_bytes(3);
  const Bytes after = request_bytes(3);
  const double hole_time = t += 0.1;
  const auto behind = mseq + static_cast<std::uint32_t>(lost.size());
  pipeline.record(packet(hole_time, tcp_packet(LinkLayer::Ethernet, {master, gateway},
                                               {behind, sseq, tcp_flag::kAck}, after)));
  const std::size_t frames_before = events_.frames.size();

  EXPECT_LT(wake_at_deadlines(pipeline, hole_time + 2.0), 1000);
  EXPECT_EQ(events_.gaps, 0u);  // waited 2 s, not longer
  EXPECT_LT(wake_at_deadlines(pipeline, hole_time + 2.0 + 1e-6), 1000);
  EXPECT_EQ(events_.gaps, 1u);
  // The request behind the hole reached its bus and is judged there by the live clock.
  EXPECT_LT(wake_at_deadlines(pipeline, hole_time + 10.0), 1000);
  EXPECT_EQ(events_.frames.size(), frames_before + 1);
  EXPECT_EQ(events_.timeouts.size(), 1u);
  pipeline.finish(hole_time + 10.0);
  EXPECT_EQ(pipeline.report().flows.lost_bytes, lost.size());
}

// A Modbus/TCP ADU around an RTU frame: the frame without its CRC after the MBAP header.
Bytes mbap_adu(std::uint16_t transaction, const Bytes& rtu) {
  const auto length = static_cast<std::uint16_t>(rtu.size() - 2);
  Bytes adu = {
      static_cast<std::uint8_t>(transaction >> 8), static_cast<std::uint8_t>(transaction), 0, 0,
      static_cast<std::uint8_t>(length >> 8),      static_cast<std::uint8_t>(length)};
  adu.insert(adu.end(), rtu.begin(), rtu.end() - 2);
  return adu;
}

// A live Modbus/TCP flow: the last request gets no reply and nothing more arrives. The request
// is held for its reply (10 s at least) and then handed on at a deadline the pipeline
// announces, so that its bus judges it unanswered without waiting for another segment.
TEST_F(PipelineTest, ALiveModbusTcpRequestHeldForItsReplyGoesOnAtItsDeadline) {
  Pipeline pipeline(settings_, decoder_, events_);
  pipeline.begin_input(dlt::kEthernet, false);
  const Endpoint master = ipv4_endpoint(10, 0, 0, 1, 50000);
  const Endpoint gateway = ipv4_endpoint(10, 0, 0, 2, 502);
  std::uint32_t mseq = 1000;
  std::uint32_t sseq = 9000;
  double t = 10.0;
  auto send = [&](const Endpoint& from, const Endpoint& to, std::uint32_t& seq, std::uint32_t ack,
                  const Bytes& payload) {
    pipeline.record(packet(t += 0.1, tcp_packet(LinkLayer::Ethernet, {from, to},
                                                {seq, ack, tcp_flag::kAck}, payload)));
    seq += static_cast<std::uint32_t>(payload.size());
  };
  for (std::uint16_t tid = 1; tid <= 3; ++tid) {
    send(master, gateway, mseq, sseq, mbap_adu(tid, request_bytes(3)));
    send(gateway, master, sseq, mseq, mbap_adu(tid, reply_bytes(3)));
  }
  send(master, gateway, mseq, sseq, mbap_adu(4, request_bytes(3)));
  const double asked = t;
  EXPECT_EQ(events_.frames.size(), 6u);

  EXPECT_LT(wake_at_deadlines(pipeline, asked + 9.9), 1000);
  EXPECT_EQ(events_.frames.size(), 6u);  // still held for its reply
  EXPECT_LT(wake_at_deadlines(pipeline, asked + 12.0), 1000);
  ASSERT_EQ(events_.frames.size(), 7u);
  EXPECT_EQ(events_.frames.back().role, Role::Request);
  ASSERT_EQ(events_.timeouts.size(), 1u);
  pipeline.finish(asked + 12.0);
  EXPECT_EQ(pipeline.report().flows.mbap_flows, 1u);
}

TEST_F(PipelineTest, PlainBytesHaveOneBusWithoutTimeEvenWhenEmpty) {
  settings_.has_timestamps = false;
  Pipeline pipeline(settings_, decoder_, events_);
  pipeline.begin_raw_input();
  pipeline.finish(0);
  AuditReport report = pipeline.report();
  ASSERT_EQ(report.buses.size(), 1u);
  EXPECT_FALSE(report.settings.has_timestamps);
  EXPECT_FALSE(report.buses[0].report.has_timestamps);

  Recorded more;
  Pipeline fed(settings_, decoder_, more);
  fed.begin_raw_input();
  Bytes bytes = request_bytes(2);
  const Bytes reply = reply_bytes(2);
  bytes.insert(bytes.end(), reply.begin(), reply.end());
  fed.raw_bytes(bytes);
  fed.finish(0);
  ASSERT_EQ(more.frames.size(), 2u);
  EXPECT_FALSE(more.frames[1].latency.has_value());
  EXPECT_EQ(fed.report().totals().bytes.frame_bytes, bytes.size());
}

TEST_F(PipelineTest, ExportedPdusOfOtherDissectorsAndBrokenRecordsAreCountedNotFed) {
  Pipeline pipeline(settings_, decoder_, events_);
  pipeline.begin_input(dlt::kUpperPdu, false);
  // A dissector name tag of "http" (padded to 4), the end tag, then a PDU.
  const Bytes foreign = {0x00, 0x0C, 0x00, 0x04, 'h', 't', 't', 'p', 0x00, 0x00, 0x00, 0x00, 0x01};
  const Bytes cut = {0x00, 0x0C, 0x00, 0x10, 'p'};
  pipeline.record(packet(1.0, foreign));
  pipeline.record(packet(1.1, cut));
  pipeline.finish(1.1);
  const AuditReport report = pipeline.report();
  EXPECT_EQ(report.skipped.foreign_pdus, 1u);
  EXPECT_EQ(report.skipped.malformed, 1u);
  EXPECT_TRUE(events_.frames.empty());
  EXPECT_EQ(events_.noise_bytes, 0u);
}

}  // namespace
}  // namespace pvtap::analyzer
