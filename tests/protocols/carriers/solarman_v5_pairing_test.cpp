// SolarmanV5Pairing: a stick's responses paired with requests by the sequence byte it echoes,
// and its codes read as what they answer.
#include <gtest/gtest.h>

#include <optional>
#include <string>
#include <vector>

#include "pvtap/carriers/solarman_v5_pairing.h"

namespace pvtap::solarman_v5 {
namespace {

constexpr std::uint32_t kStick = 4068039735u;
constexpr std::uint32_t kWrong = 2111130827u;
const std::vector<std::uint8_t> kRequest = {1, 3, 0, 0, 0, 1, 0x84, 0x0A};
const std::vector<std::uint8_t> kReply = {1, 3, 2, 0, 7, 0xF9, 0x86};

struct Recorder : ReleaseSink {
  void release(const Release& r) override {
    std::string s;
    switch (r.kind) {
      case Release::Kind::Request:
        s = "req";
        break;
      case Release::Kind::Reply:
        s = r.answers_request ? (r.late ? "late" : "rep") : "unpaired";
        break;
      case Release::Kind::NoReply:
        s = "code05:";
        break;
      case Release::Kind::Refused:
        s = "refused:" + describe_refusal(r.addressed_serial, r.serial) + ":";
        break;
      case Release::Kind::Code:
        s = "code" + std::to_string(r.code) + ":";
        break;
    }
    order.push_back(s + std::to_string(r.sequence));
  }
  std::vector<std::string> order;
};

// A frame as the reader gives it: `bytes` keeps its storage alive.
struct Built {
  std::vector<std::uint8_t> bytes;
  Frame frame;
};

Built build(std::uint16_t control, std::uint8_t sequence, std::uint32_t serial,
            const std::vector<std::uint8_t>& payload) {
  Built b;
  Header h;
  h.control = control;
  h.sequence = sequence;
  h.serial = serial;
  b.bytes = encode_frame(h, payload);
  b.frame = parse_frame(b.bytes);
  return b;
}

Built request(std::uint8_t seq, std::uint32_t serial = kStick) {
  return build(control::kRequest, seq, serial, request_payload(kRequest));
}
Built reply(std::uint8_t seq) {
  return build(control::kResponse, seq, kStick, response_payload(kReply));
}
Built code(std::uint8_t seq, std::uint8_t c) {
  const std::vector<std::uint8_t> two = {c, 0};
  return build(control::kResponse, seq, kStick, response_payload(two));
}
Built heartbeat() {
  return build(control::kHeartbeat, 1, kStick, {0});
}

struct Flow {
  Recorder rec;
  SolarmanV5Pairing pairing{1.0, rec};
  std::vector<Built> kept;
  void at(double t, Built b) {
    kept.push_back(std::move(b));
    pairing.frame(kept.back().frame, t);
  }
};

TEST(SolarmanV5Pairing, TwoBytesWhereTheRtuFrameBelongsAreTheSticksCode) {
  const Built c = code(1, 0x05);
  ASSERT_TRUE(c.frame.stick_code.has_value());
  EXPECT_EQ(*c.frame.stick_code, 0x05);
  EXPECT_EQ(c.frame.rtu_length, 0u);
  EXPECT_EQ(c.frame.carrier_bytes(), c.bytes.size());
  EXPECT_FALSE(reply(1).frame.stick_code.has_value());
}

// The stick: a heartbeat where the reply to 0x98 was due, the client's next request
// 0xd4, then both replies. By order, the first reply would answer 0xd4.
TEST(SolarmanV5Pairing, AHeartbeatInPlaceOfAReplyShiftsNothing) {
  Flow run;
  run.at(0.0, heartbeat());  // the stick's serial
  run.at(0.1, request(0x97));
  run.at(0.3, reply(0x97));
  run.at(0.4, request(0x98));
  run.at(0.6, heartbeat());
  run.at(0.8, request(0xd4));
  run.at(1.0, reply(0x98));
  run.at(1.4, reply(0xd4));
  EXPECT_EQ(run.rec.order, (std::vector<std::string>{"req151", "rep151", "req152", "late152",
                                                     "req212", "rep212"}));
  Totals t;
  run.pairing.add_counts(t);
  EXPECT_EQ(t.replies_after_next_request, 1u);
  EXPECT_EQ(t.unpaired_replies, 0u);
}

TEST(SolarmanV5Pairing, ARequestWhoseNewerOneWasAnsweredFirstGotNoReply) {
  Flow run;
  run.at(0.0, heartbeat());
  run.at(0.1, request(1));
  run.at(0.3, request(2));
  run.at(0.4, reply(2));
  run.at(0.5, reply(1));  // too late for its turn on the bus: the matcher judges it
  EXPECT_EQ(run.rec.order, (std::vector<std::string>{"req1", "req2", "rep2", "unpaired1"}));
}

TEST(SolarmanV5Pairing, Code05IsNoReplyAndCode06WithAnotherSerialARefusal) {
  Flow run;
  run.at(0.0, heartbeat());
  run.at(0.1, request(1));
  run.at(0.6, code(1, 0x05));
  run.at(1.0, request(2, kWrong));  // held: the stick may refuse it
  EXPECT_EQ(run.pairing.held(), 1u);
  run.at(1.1, code(2, 0x06));
  run.at(1.2, code(9, 0x07));  // a code that answers nothing waiting
  EXPECT_EQ(
      run.rec.order,
      (std::vector<std::string>{
          "req1", "code05:1",
          "refused:the client addressed logger 2111130827; the stick is 4068039735:2", "code7:9"}));
  Totals t;
  run.pairing.add_counts(t);
  EXPECT_EQ(t.stick_timeouts, 1u);
  EXPECT_EQ(t.refused_requests, 1u);
  EXPECT_EQ(t.other_codes, 1u);
}

// A live capture wakes at the deadline the pairing gives: at the end of the wait of the
// request on the bus, the held one goes on it, as a frame arriving then would let it.
TEST(SolarmanV5Pairing, AHeldRequestGoesOnTheBusAtTheDeadlineWithoutAnotherFrame) {
  Flow run;
  run.at(0.0, heartbeat());
  EXPECT_FALSE(run.pairing.next_deadline().has_value());
  run.at(0.1, request(1));
  EXPECT_FALSE(run.pairing.next_deadline().has_value());  // nothing held behind it
  run.at(0.2, request(2));
  const std::optional<double> due = run.pairing.next_deadline();
  ASSERT_TRUE(due.has_value());
  EXPECT_GT(*due, 1.1);
  EXPECT_LT(*due, 1.1 + 1e-9);
  run.pairing.idle(1.1);
  EXPECT_EQ(run.rec.order, (std::vector<std::string>{"req1"}));
  run.pairing.idle(*due);
  EXPECT_EQ(run.rec.order, (std::vector<std::string>{"req1", "req2"}));
  EXPECT_FALSE(run.pairing.next_deadline().has_value());
}

TEST(SolarmanV5Pairing, ARequestWaitsAtMostTheTimeoutAndIsHandedOnAtTheEnd) {
  Flow run;
  run.at(0.0, heartbeat());
  run.at(0.1, request(1));
  run.at(0.2, request(2));    // held behind 1
  run.at(1.15, heartbeat());  // 1 waited out its timeout: 2 goes on the bus
  EXPECT_EQ(run.rec.order, (std::vector<std::string>{"req1", "req2"}));
  run.at(1.3, request(3));
  run.pairing.finish();
  EXPECT_EQ(run.rec.order, (std::vector<std::string>{"req1", "req2", "req3"}));
  EXPECT_EQ(run.pairing.held(), 0u);
}

}  // namespace
}  // namespace pvtap::solarman_v5
