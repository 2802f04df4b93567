// MbapFlow: Modbus/TCP ADUs as frames of a bus session: paired by transaction id, timed,
// their exceptions counted, their check said to be TCP's.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "hex_bytes.h"
#include "pvtap/carriers/mbap_flow.h"
#include "pvtap/registers/register_decoder.h"
#include "pvtap/session/event_tally.h"

namespace pvtap {
namespace {

using Bytes = std::vector<std::uint8_t>;

Bytes adu(std::uint16_t tid, std::uint8_t unit, std::string_view pdu) {
  const Bytes body = test::hex_bytes(pdu);
  const std::size_t length = body.size() + 1;
  Bytes out;
  for (const std::size_t field : {std::size_t{tid}, std::size_t{0}, length}) {
    out.push_back(static_cast<std::uint8_t>(field >> 8));
    out.push_back(static_cast<std::uint8_t>(field & 0xFF));
  }
  out.push_back(unit);
  for (const std::uint8_t b : body) out.push_back(b);
  return out;
}

struct Recorder : BusSessionSink {
  void on_frame(const SessionFrame& f) override {
    frames.push_back(f.bytes.size());
    dialects.push_back(f.dialect);
    carried += f.check.carried ? 1 : 0;
    ok += f.check.ok ? 1 : 0;
    if (f.latency) latencies.push_back(*f.latency);
    if (f.request_id) answered.push_back(*f.request_id);
    if (f.frame && f.frame->exception_code) exceptions.push_back(*f.frame->exception_code);
  }
  void on_timeout(const SessionTimeout& t) override { timeouts.push_back(t); }
  std::vector<std::size_t> frames;
  std::vector<Dialect> dialects;
  unsigned carried = 0;
  unsigned ok = 0;
  std::vector<double> latencies;
  std::vector<std::uint64_t> answered;
  std::vector<std::uint8_t> exceptions;
  std::vector<SessionTimeout> timeouts;
};

struct Fixture {
  Fixture() : session(options(), decoder, rec), flow(session, 1.0) {}
  static BusSessionOptions options() {
    BusSessionOptions o;
    o.matcher.timeout = 1.0;
    return o;
  }
  void request(const Bytes& b, double t) { flow.feed(Direction::ToSlave, b, t); }
  void reply(const Bytes& b, double t) { flow.feed(Direction::FromSlave, b, t); }
  void finish(double t) {
    flow.finish(t);
    session.finish();
  }
  RegisterDecoder decoder;
  Recorder rec;
  BusSession session;
  MbapFlow flow;
};

TEST(MbapFlow, PipelinedRequestsToOneUnitPairByTransactionId) {
  Fixture f;
  f.request(adu(1, 3, "03 00 00 00 01"), 10.000);
  f.request(adu(2, 3, "03 00 10 00 01"), 10.001);
  f.reply(adu(2, 3, "03 02 00 07"), 10.050);
  f.reply(adu(1, 3, "03 02 00 09"), 10.080);
  f.finish(10.1);
  EXPECT_TRUE(f.rec.timeouts.empty());
  ASSERT_EQ(f.rec.latencies.size(), 2u);
  EXPECT_NEAR(f.rec.latencies[0], 0.049, 1e-9);  // transaction 2
  EXPECT_NEAR(f.rec.latencies[1], 0.080, 1e-9);  // transaction 1
  EXPECT_EQ(f.rec.carried, 4u);
  EXPECT_EQ(f.rec.ok, 4u);
  const BusReport r = f.session.report();
  EXPECT_EQ(r.requests, 2u);
  EXPECT_EQ(r.responses, 2u);
  EXPECT_EQ(r.bytes.frame_bytes, 6u + 6u + 5u + 5u);  // unit ids and PDUs, no CRC
  EXPECT_EQ(r.bytes.bad_frames, 0u);
  EXPECT_EQ(f.flow.totals().carrier_bytes, 24u);
}

TEST(MbapFlow, AGatewaysTargetNoResponseIsATimeoutBehindIt) {
  Fixture f;
  f.request(adu(1, 4, "03 00 00 00 02"), 1.0);
  f.reply(adu(1, 4, "83 0B"), 1.5);
  f.request(adu(2, 4, "04 00 00 00 02"), 2.0);
  f.reply(adu(2, 4, "84 0A"), 2.1);
  f.finish(2.2);
  EXPECT_EQ(f.rec.exceptions, (std::vector<std::uint8_t>{0x0B, 0x0A}));
  const BusReport r = f.session.report();
  // The 0x0B is the device's timeout behind the gateway, the 0x0A the gateway's exception.
  EXPECT_EQ(r.exceptions, 1u);
  EXPECT_EQ(r.gateway_timeouts, 1u);
  EXPECT_EQ(r.timeouts, 1u);
  EXPECT_EQ(f.session.tally().counts().gateway_timeouts, 1u);
  ASSERT_EQ(r.exception_codes.size(), 1u);
  EXPECT_EQ(r.exception_codes[0].code, 0x0Au);
  EXPECT_TRUE(f.rec.timeouts.empty());  // the gateway answered: no timeout on the TCP side
}

TEST(MbapFlow, AGatewayAnswerLaterThanTheTimeoutStillAnswers) {
  Fixture f;
  f.request(adu(1, 4, "03 00 00 00 02"), 1.0);
  f.reply(adu(1, 4, "83 0B"), 2.5);  // the gateway's own serial timeout is 1.5 s
  f.finish(2.6);
  EXPECT_TRUE(f.rec.timeouts.empty());
  ASSERT_EQ(f.rec.latencies.size(), 1u);
  EXPECT_NEAR(f.rec.latencies[0], 1.5, 1e-9);
  EXPECT_EQ(f.session.report().unsolicited, 0u);
  EXPECT_EQ(f.session.report().gateway_timeouts, 1u);
}

TEST(MbapFlow, AHybridFrameIsReadAsHybrid) {
  Fixture f;
  // A Hybrid read of 0x11 (start 0x1000, 2 words) and its reply: device number, 2 words.
  f.request(adu(1, 2, "11 10 00 00 02"), 1.0);
  f.reply(adu(1, 2, "11 08 01 00 00 2A 00 05 00 06"), 1.1);
  f.finish(1.2);
  const BusReport r = f.session.report();
  EXPECT_EQ(r.exceptions, 0u);
  EXPECT_EQ(r.malformed_frames, 0u);
  ASSERT_EQ(f.rec.latencies.size(), 1u);
  EXPECT_EQ(f.rec.dialects, (std::vector<Dialect>{Dialect::Hybrid, Dialect::Hybrid}));
}

TEST(MbapFlow, AReportServerIdReplyIsReadInItsRequestsDialect) {
  Fixture f;
  // Modbus 0x11 (no data) and its reply: byte count 8, "Wingpath"-like text, run indicator.
  // The reply also fits Hybrid's 0x11 (a counted reply with a device number); only the request
  // says which it is (a real gateway's reply was read as Hybrid and left unanswered).
  f.request(adu(1, 10, "11"), 1.0);
  f.reply(adu(1, 10, "11 08 57 69 6E 67 70 61 74 FF"), 1.1);
  f.finish(1.2);
  const BusReport r = f.session.report();
  EXPECT_EQ(r.malformed_frames, 0u);
  EXPECT_EQ(r.timeouts, 0u);
  ASSERT_EQ(f.rec.latencies.size(), 1u);
  EXPECT_EQ(f.rec.dialects, (std::vector<Dialect>{Dialect::Modbus, Dialect::Modbus}));
}

TEST(MbapFlow, ARequestNoReplyCameForTimesOut) {
  Fixture f;
  f.request(adu(1, 4, "03 00 00 00 02"), 1.0);
  f.request(adu(2, 5, "03 00 00 00 02"), 1.1);
  f.reply(adu(2, 5, "03 04 00 01 00 02"), 1.2);
  f.request(adu(3, 5, "03 00 00 00 02"), 3.0);
  f.reply(adu(3, 5, "03 04 00 01 00 02"), 3.1);
  f.finish(3.2);
  ASSERT_EQ(f.rec.timeouts.size(), 1u);
  EXPECT_EQ(f.rec.timeouts[0].kind, UnansweredKind::Timeout);
  EXPECT_EQ(f.rec.timeouts[0].station, std::optional<std::uint8_t>(4));
}

TEST(MbapFlow, AHeaderThatLiedIsAFindingAndTheFlowGoesOn) {
  Fixture f;
  Bytes liar = adu(1, 1, "03 00 00 00 01");
  liar[5] = 40;
  f.request(liar, 1.0);
  f.request(adu(2, 1, "03 00 00 00 01"), 1.1);
  f.reply(adu(2, 1, "03 02 00 01"), 1.2);
  f.finish(1.3);
  ASSERT_EQ(f.flow.finding_examples().size(), 1u);
  EXPECT_EQ(describe(f.flow.finding_examples()[0]),
            "MBAP length overruns what was sent (the next segment is whole ADUs) (protocol id "
            "0, length 40): 12 bytes skipped at offset 0");
  EXPECT_EQ(f.rec.frames.size(), 2u);
  EXPECT_EQ(f.flow.totals().skipped_bytes, 12u);
  EXPECT_EQ(f.flow.totals().adus, 2u);
}

}  // namespace
}  // namespace pvtap
