// next_deadline(): the core says when its driver must wake it, and a wake then decides.
#include <gtest/gtest.h>

#include <vector>

#include "bus_script.h"
#include "frame_builders.h"
#include "hex_bytes.h"
#include "pvtap/codec/frame_codec.h"
#include "pvtap/framing/stream_reassembler.h"
#include "pvtap/session/bus_session.h"
#include "pvtap/statistics/bus_timing.h"

namespace pvtap {
namespace {

using Bytes = std::vector<std::uint8_t>;
using test::hex_bytes;

const Bytes kGoodRequest = hex_bytes("01 03 00 00 00 0A C5 CD");
const Bytes kBadEcho = hex_bytes("06 18 08 31 00 00 67 10 2A 09 3C 2A 86");

TEST(ReassemblerDeadline, NothingPendingNeedsNoWake) {
  test::CapturingSink sink;
  StreamReassembler r({}, sink);
  EXPECT_FALSE(r.next_deadline().has_value());
  r.feed(BusChunk{kGoodRequest, 1.0, Direction::Unknown});
  ASSERT_EQ(sink.events.size(), 1u);  // a good frame is decided at its last byte
  EXPECT_FALSE(r.next_deadline().has_value());
}

TEST(ReassemblerDeadline, ABadFrameIsDecidedAtTheEndOfTheT35Silence) {
  const BusTiming timing(9600);
  test::CapturingSink sink;
  StreamReassembler r({}, sink);
  r.feed(BusChunk{kBadEcho, 1000.0, Direction::FromSlave});
  const auto due = r.next_deadline();
  ASSERT_TRUE(due.has_value());
  EXPECT_GT(*due, 1000.0 + timing.t15);
  EXPECT_LE(*due, 1000.0 + timing.t35);
  r.idle(*due);
  ASSERT_EQ(sink.events.size(), 1u);
  EXPECT_FALSE(sink.events[0].frame.check.ok);
  EXPECT_EQ(sink.events[0].bytes, kBadEcho);
  EXPECT_FALSE(r.next_deadline().has_value());
}

TEST(ReassemblerDeadline, APartialFrameIsGivenUpAtTheSecondDeadline) {
  test::CapturingSink sink;
  ReassemblerOptions options;
  options.give_up_after = 0.1;
  StreamReassembler r(options, sink);
  const std::span<const std::uint8_t> bytes(kGoodRequest);
  r.feed(BusChunk{bytes.first(6), 10.0, Direction::Unknown});
  const auto silence = r.next_deadline();
  ASSERT_TRUE(silence.has_value());
  r.idle(*silence);
  EXPECT_TRUE(sink.events.empty()) << "t3.5 alone does not give up a frame's head";
  const auto give_up = r.next_deadline();
  ASSERT_TRUE(give_up.has_value());
  EXPECT_NEAR(*give_up - *silence, options.give_up_after, 1e-9);
  r.idle(*give_up);
  ASSERT_EQ(sink.events.size(), 1u);
  EXPECT_FALSE(sink.events[0].is_frame);
  EXPECT_EQ(r.pending_bytes(), 0u);
  EXPECT_FALSE(r.next_deadline().has_value());
}

TEST(ReassemblerDeadline, BatchedTimingWaitsForTheBoundaryGapOrForMoreBytes) {
  ReassemblerOptions batched;
  batched.timestamps = TimestampTrust::Untrusted;
  batched.boundary_gap = 0;
  test::CapturingSink sink;
  StreamReassembler never(batched, sink);
  never.feed(BusChunk{kBadEcho, 1.0, Direction::Unknown});
  EXPECT_FALSE(never.next_deadline().has_value()) << "no silence can prove a boundary";

  batched.boundary_gap = 0.05;
  StreamReassembler gateway(batched, sink);
  gateway.feed(BusChunk{kBadEcho, 1.0, Direction::Unknown});
  const auto due = gateway.next_deadline();
  ASSERT_TRUE(due.has_value());
  EXPECT_NEAR(*due, 1.05, 1e-9);
  gateway.idle(*due);
  ASSERT_EQ(sink.events.size(), 1u);
  EXPECT_EQ(sink.events[0].bytes, kBadEcho);
}

// Records what a session reports.
struct SessionLog : BusSessionSink {
  void on_frame(const SessionFrame& f) override {
    frames.push_back(f);
    frames.back().bytes = {};
    frames.back().frame = nullptr;
    frames.back().values = {};
  }
  void on_timeout(const SessionTimeout& t) override { timeouts.push_back(t); }
  std::vector<SessionFrame> frames;
  std::vector<SessionTimeout> timeouts;
};

class SessionDeadlineTest : public ::testing::Test {
 protected:
  void feed(const Bytes& bytes, double time, Direction d = Direction::Unknown,
            bool previous_turn_complete = true) {
    session_.feed(BusChunk{bytes, time, d, previous_turn_complete});
  }
  RegisterDecoder decoder_;
  SessionLog log_;
  BusSession session_{BusSessionOptions{}, decoder_, log_};
};

TEST_F(SessionDeadlineTest, ARequestWithoutReplyTimesOutAtTheDeadlineAndNotBefore) {
  feed(encode_frame(test::read_request(Dialect::Gsl, 1, 0x03, 0x041A, 1)), 5.0);
  ASSERT_EQ(log_.frames.size(), 1u);
  const auto due = session_.next_deadline();
  ASSERT_TRUE(due.has_value());
  EXPECT_NEAR(*due, 5.0 + MatcherConfig{}.timeout, 1e-9);
  session_.idle(*due - 1e-9);
  EXPECT_TRUE(log_.timeouts.empty());
  session_.idle(*due);
  ASSERT_EQ(log_.timeouts.size(), 1u);
  EXPECT_EQ(log_.timeouts[0].kind, UnansweredKind::Timeout);
  EXPECT_FALSE(session_.next_deadline().has_value());
}

TEST_F(SessionDeadlineTest, WakingAtEachDeadlineDecidesEverything) {
  Bytes bad = encode_frame(test::read_request(Dialect::Gsl, 1, 0x03, 0x041A, 1));
  bad[7] ^= 0x55;
  feed(bad, 5.0);
  EXPECT_TRUE(log_.frames.empty());
  int wakes = 0;
  while (const auto due = session_.next_deadline()) {
    session_.idle(*due);
    ASSERT_LT(++wakes, 10);
  }
  ASSERT_EQ(log_.frames.size(), 1u);
  EXPECT_FALSE(log_.frames[0].check.ok);
  ASSERT_EQ(log_.timeouts.size(), 1u);
  EXPECT_EQ(log_.timeouts[0].kind, UnansweredKind::DamagedRequest);
}

TEST_F(SessionDeadlineTest, WithoutTimestampsOnlyTheBytesDecide) {
  BusSessionOptions dump;
  dump.has_timestamps = false;
  dump.reassembler.timestamps = TimestampTrust::Untrusted;
  dump.reassembler.boundary_gap = 0;
  BusSession session(dump, decoder_, log_);
  session.feed(BusChunk{encode_frame(test::read_request(Dialect::Gsl, 1, 0x03, 0, 1)), 0.0});
  ASSERT_EQ(log_.frames.size(), 1u);
  EXPECT_FALSE(session.next_deadline().has_value());
}

// The half-duplex turn rule: the reply's first bytes end the request's turn.
class TurnRuleTest : public SessionDeadlineTest {
 protected:
  void SetUp() override {
    bad_request_ = encode_frame(test::read_request(Dialect::Gsl, 1, 0x03, 0x041A, 1));
    bad_request_[7] ^= 0x55;
    feed(bad_request_, 1.0, Direction::ToSlave);
  }
  Bytes reply_head() const { return Bytes(reply_.begin(), reply_.begin() + 3); }
  static Bytes reply() {
    Frame f = test::frame_of(Dialect::Gsl, Role::Response, 1, 0x03);
    f.byte_count = 2;
    f.words = {2300};
    return encode_frame(f);
  }
  Bytes bad_request_;
  Bytes reply_ = reply();
};

TEST_F(TurnRuleTest, TheOtherDirectionEndsTheTurn) {
  EXPECT_TRUE(log_.frames.empty());
  feed(reply_head(), 1.05, Direction::FromSlave);
  ASSERT_EQ(log_.frames.size(), 1u);
  EXPECT_EQ(log_.frames[0].direction, Direction::ToSlave);
  EXPECT_FALSE(log_.frames[0].check.ok);
}

TEST_F(TurnRuleTest, ATurnStillMissingBytesIsNotEnded) {
  feed(reply_head(), 1.05, Direction::FromSlave, false);
  EXPECT_TRUE(log_.frames.empty());
}

TEST_F(TurnRuleTest, AnUnknownDirectionEndsNoTurn) {
  feed(reply_head(), 1.06, Direction::Unknown);
  feed(reply_head(), 1.07, Direction::FromSlave);  // after an unknown chunk: no known turn
  EXPECT_TRUE(log_.frames.empty());
}

TEST_F(TurnRuleTest, ARestartedStreamEndsNoTurnOfTheOldOne) {
  session_.restart(Direction::FromSlave);
  feed(reply_head(), 1.05, Direction::FromSlave);
  EXPECT_TRUE(log_.frames.empty());
}

}  // namespace
}  // namespace pvtap
