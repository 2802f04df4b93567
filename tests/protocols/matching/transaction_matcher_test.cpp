#include "pvtap/matching/transaction_matcher.h"

#include <gtest/gtest.h>

#include "frame_builders.h"

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "pvtap/codec/frame.h"
#include "pvtap/codec/function_codes.h"
#include "pvtap/matching/frame_summary.h"
#include "pvtap/matching/match_events.h"

namespace pvtap {
namespace {

// Keeps every finding, so that a test can check both what was decided and what was not.
struct RecordingSink {
  std::vector<Transaction> transactions;
  std::vector<Timeout> timeouts;
  std::vector<UnsolicitedReply> unsolicited;
  std::vector<DuplicateReply> duplicates;
  std::vector<ByteCountMismatch> mismatches;
  std::vector<RoleCorrection> corrections;
  std::vector<EchoedRequest> echoes;

  void record(std::span<const Timeout> decided) {
    timeouts.insert(timeouts.end(), decided.begin(), decided.end());
  }
  void record(const FrameMatch& m) {
    record(m.timeouts);
    if (m.role_correction) corrections.push_back(*m.role_correction);
    if (m.transaction) transactions.push_back(*m.transaction);
    if (m.duplicate) duplicates.push_back(*m.duplicate);
    if (m.unsolicited) unsolicited.push_back(*m.unsolicited);
    if (m.count_mismatch) mismatches.push_back(*m.count_mismatch);
    if (m.echo) echoes.push_back(*m.echo);
  }

  std::size_t total() const {
    return transactions.size() + timeouts.size() + unsolicited.size() + duplicates.size() +
           mismatches.size() + corrections.size() + echoes.size();
  }
};

// A matcher whose findings are kept in a RecordingSink.
class RecordingMatcher {
 public:
  explicit RecordingMatcher(RecordingSink& sink, MatcherConfig config = {})
      : sink_(sink), matcher_(config) {}
  Role on_frame(const ObservedFrame& frame) {
    const FrameMatch m = matcher_.on_frame(frame);
    sink_.record(m);
    return m.role;
  }
  void advance(double now) { sink_.record(matcher_.advance(now)); }
  void finish() { sink_.record(matcher_.finish()); }
  std::size_t pending_count() const { return matcher_.pending_count(); }

 private:
  RecordingSink& sink_;
  TransactionMatcher matcher_;
};

Frame rtu_reply(Dialect d, std::uint8_t station, std::uint8_t function, std::uint8_t n) {
  Frame f;
  f.dialect = d;
  f.role = Role::Response;
  f.station = station;
  f.function = function;
  f.byte_count = n;
  return f;
}

Frame ascii_reply(std::uint8_t station, std::uint16_t start, std::size_t words) {
  Frame f;
  f.dialect = Dialect::Ascii;
  f.role = Role::Response;
  f.station = station;
  f.function = fc::kAsciiRead;
  f.start = start;
  for (std::size_t i = 0; i < words; ++i) f.words.push_back(static_cast<std::uint16_t>(i));
  return f;
}

Frame gsl_write(std::uint8_t station, std::uint16_t reg, std::uint16_t value) {
  Frame f;
  f.dialect = Dialect::Gsl;
  f.role = Role::Request;  // what a reassembler without direction reports for both copies
  f.station = station;
  f.function = fc::kGslWriteSingle;
  f.start = reg;
  f.words.push_back(value);
  return f;
}

ObservedFrame observed(std::uint64_t id, const Frame& f, double start, double end,
                       bool check_ok = true) {
  ObservedFrame o;
  o.id = id;
  o.frame = summarize(f);
  o.start_time = start;
  o.end_time = end;
  o.check_ok = check_ok;
  return o;
}

class TransactionMatcherTest : public ::testing::Test {
 protected:
  RecordingSink sink;
  RecordingMatcher matcher{sink};
};

TEST_F(TransactionMatcherTest, PlainRequestReplyGivesLatency) {
  matcher.on_frame(
      observed(1, test::read_request(Dialect::Gsl, 1, fc::kGslReadHolding, 0, 10), 0.000, 0.008));
  EXPECT_EQ(matcher.pending_count(), 1u);
  matcher.on_frame(observed(2, rtu_reply(Dialect::Gsl, 1, fc::kGslReadHolding, 20), 0.050, 0.075));
  matcher.finish();

  ASSERT_EQ(sink.transactions.size(), 1u);
  const Transaction& t = sink.transactions[0];
  EXPECT_EQ(t.request_id, 1u);
  EXPECT_EQ(t.response_id, 2u);
  EXPECT_DOUBLE_EQ(t.latency, 0.042);
  EXPECT_EQ(t.station, 1);
  EXPECT_EQ(t.function, fc::kGslReadHolding);
  EXPECT_EQ(t.dialect, Dialect::Gsl);
  EXPECT_EQ(t.reply_kind, ReplyKind::Normal);
  EXPECT_FALSE(t.broadcast);
  EXPECT_TRUE(t.reply_check_ok);
  EXPECT_EQ(sink.total(), 1u);
  EXPECT_EQ(matcher.pending_count(), 0u);
}

TEST_F(TransactionMatcherTest, ReplyWithOtherFunctionDoesNotAnswer) {
  matcher.on_frame(
      observed(1, test::read_request(Dialect::Gsl, 1, fc::kGslReadHolding, 0, 2), 0, 0.008));
  matcher.on_frame(observed(2, rtu_reply(Dialect::Gsl, 1, fc::kGslReadInput, 4), 0.02, 0.03));
  EXPECT_TRUE(sink.transactions.empty());
  ASSERT_EQ(sink.unsolicited.size(), 1u);
  EXPECT_EQ(matcher.pending_count(), 1u);
}

TEST_F(TransactionMatcherTest, HybridBroadcastIsAnsweredFromTheRealAddress) {
  matcher.on_frame(observed(
      1,
      test::read_request(Dialect::Hybrid, fc::kHybridBroadcast, fc::kHybridDeviceInfo, 0x1060, 2),
      0.0, 0.008));
  matcher.on_frame(
      observed(2, rtu_reply(Dialect::Hybrid, 6, fc::kHybridDeviceInfo, 8), 0.030, 0.043));
  ASSERT_EQ(sink.transactions.size(), 1u);
  EXPECT_EQ(sink.transactions[0].request_id, 1u);
  EXPECT_EQ(sink.transactions[0].station, 6);
  EXPECT_TRUE(sink.transactions[0].broadcast);
  EXPECT_DOUBLE_EQ(sink.transactions[0].latency, 0.022);

  // A second device answers the same broadcast; the first one answering again is a duplicate.
  matcher.on_frame(
      observed(3, rtu_reply(Dialect::Hybrid, 9, fc::kHybridDeviceInfo, 8), 0.060, 0.073));
  matcher.on_frame(
      observed(4, rtu_reply(Dialect::Hybrid, 6, fc::kHybridDeviceInfo, 8), 0.090, 0.103));
  matcher.finish();
  ASSERT_EQ(sink.transactions.size(), 2u);
  EXPECT_EQ(sink.transactions[1].station, 9);
  EXPECT_EQ(sink.transactions[1].request_id, 1u);
  ASSERT_EQ(sink.duplicates.size(), 1u);
  EXPECT_EQ(sink.duplicates[0].original_request_id, 1u);
  EXPECT_EQ(sink.duplicates[0].station, 6);
  EXPECT_TRUE(sink.timeouts.empty()) << "an answered broadcast must not time out";
}

TEST_F(TransactionMatcherTest, UnansweredHybridBroadcastTimesOut) {
  matcher.on_frame(observed(
      1,
      test::read_request(Dialect::Hybrid, fc::kHybridBroadcast, fc::kHybridDeviceInfo, 0x1060, 2),
      0.0, 0.008));
  matcher.advance(2.0);
  ASSERT_EQ(sink.timeouts.size(), 1u);
  EXPECT_EQ(sink.timeouts[0].station, fc::kHybridBroadcast);
  EXPECT_EQ(sink.timeouts[0].reason, TimeoutReason::NoReply);
}

// Reads may not be broadcast: no station answers one, so it never times out (the session
// makes it a finding). A damaged read to address 0 may be one whose address was damaged.
TEST_F(TransactionMatcherTest, ABroadcastReadWaitsForNoReply) {
  matcher.on_frame(observed(
      1, test::read_request(Dialect::Modbus, fc::kModbusBroadcast, fc::kGslReadHolding, 0, 2), 0.0,
      0.008));
  matcher.advance(2.0);
  EXPECT_TRUE(sink.timeouts.empty());
  matcher.on_frame(observed(
      2, test::read_request(Dialect::Modbus, fc::kModbusBroadcast, fc::kGslReadHolding, 0, 2), 3.0,
      3.008, false));
  matcher.advance(5.0);
  ASSERT_EQ(sink.timeouts.size(), 1u);
  EXPECT_EQ(sink.timeouts[0].request_id, 2u);
}

TEST_F(TransactionMatcherTest, HybridErrorReplyAnswersThePendingRequest) {
  matcher.on_frame(observed(
      1, test::read_request(Dialect::Hybrid, 6, fc::kHybridRunningData, 0x1000, 0x24), 0.0, 0.008));
  matcher.on_frame(observed(2, rtu_reply(Dialect::Hybrid, 6, fc::kHybridError, 8), 0.02, 0.033));
  matcher.finish();
  ASSERT_EQ(sink.transactions.size(), 1u);
  EXPECT_EQ(sink.transactions[0].request_id, 1u);
  EXPECT_EQ(sink.transactions[0].function, fc::kHybridRunningData);
  EXPECT_EQ(sink.transactions[0].reply_function, fc::kHybridError);
  EXPECT_EQ(sink.transactions[0].reply_kind, ReplyKind::HybridError);
  EXPECT_TRUE(sink.mismatches.empty()) << "an error reply has no data to count";
  EXPECT_TRUE(sink.timeouts.empty());
}

TEST_F(TransactionMatcherTest, GslExceptionAnswersItsBaseFunctionOnly) {
  matcher.on_frame(
      observed(1, test::read_request(Dialect::Gsl, 3, fc::kGslReadHolding, 1050, 4), 0.0, 0.008));
  Frame wrong_base = rtu_reply(Dialect::Gsl, 3, fc::kGslWriteMultiple | fc::kExceptionFlag, 0);
  wrong_base.byte_count.reset();
  wrong_base.exception_code = 1;
  matcher.on_frame(observed(2, wrong_base, 0.02, 0.025));
  EXPECT_EQ(sink.unsolicited.size(), 1u);

  Frame exception = wrong_base;
  exception.function = fc::kGslReadHolding | fc::kExceptionFlag;
  exception.exception_code = 2;
  matcher.on_frame(observed(3, exception, 0.03, 0.035));
  ASSERT_EQ(sink.transactions.size(), 1u);
  EXPECT_EQ(sink.transactions[0].request_id, 1u);
  EXPECT_EQ(sink.transactions[0].response_id, 3u);
  EXPECT_EQ(sink.transactions[0].reply_kind, ReplyKind::GslException);
  EXPECT_TRUE(sink.mismatches.empty());
}

TEST_F(TransactionMatcherTest, GslWriteEchoIsCorrectedToResponse) {
  EXPECT_EQ(matcher.on_frame(observed(1, gsl_write(1, 1250, 500), 0.0, 0.008)), Role::Request);
  EXPECT_EQ(matcher.on_frame(observed(2, gsl_write(1, 1250, 500), 0.030, 0.038)), Role::Response);
  ASSERT_EQ(sink.corrections.size(), 1u);
  EXPECT_EQ(sink.corrections[0].frame_id, 2u);
  EXPECT_EQ(sink.corrections[0].request_id, 1u);
  EXPECT_EQ(sink.corrections[0].reported, Role::Request);
  EXPECT_EQ(sink.corrections[0].corrected, Role::Response);
  ASSERT_EQ(sink.transactions.size(), 1u);
  EXPECT_EQ(sink.transactions[0].request_id, 1u);
  EXPECT_EQ(sink.transactions[0].response_id, 2u);
  EXPECT_DOUBLE_EQ(sink.transactions[0].latency, 0.022);

  // The same write once more, after the echo, is a new request and not a duplicate reply.
  EXPECT_EQ(matcher.on_frame(observed(3, gsl_write(1, 1250, 500), 0.5, 0.508)), Role::Request);
  EXPECT_EQ(sink.corrections.size(), 1u);
  EXPECT_EQ(matcher.pending_count(), 1u);
}

TEST_F(TransactionMatcherTest, GslWriteWithOtherValueIsANewRequest) {
  matcher.on_frame(observed(1, gsl_write(1, 1250, 500), 0.0, 0.008));
  EXPECT_EQ(matcher.on_frame(observed(2, gsl_write(1, 1250, 501), 0.030, 0.038)), Role::Request);
  EXPECT_TRUE(sink.corrections.empty());
  ASSERT_EQ(sink.timeouts.size(), 1u);
  EXPECT_EQ(sink.timeouts[0].reason, TimeoutReason::NextRequestFirst);
}

TEST_F(TransactionMatcherTest, KnownRoleIsNeverCorrected) {
  matcher.on_frame(observed(1, gsl_write(1, 1250, 500), 0.0, 0.008));
  ObservedFrame repeat = observed(2, gsl_write(1, 1250, 500), 0.030, 0.038);
  repeat.role_known = true;
  EXPECT_EQ(matcher.on_frame(repeat), Role::Request);
  EXPECT_TRUE(sink.corrections.empty());
  EXPECT_TRUE(sink.transactions.empty());
}

TEST_F(TransactionMatcherTest, TimeoutWhenNoReplyWithinTheTimeout) {
  RecordingSink short_sink;
  RecordingMatcher short_matcher(short_sink, MatcherConfig{0.2, std::nullopt, 0});
  short_matcher.on_frame(
      observed(1, test::read_request(Dialect::Gsl, 1, fc::kGslReadHolding, 0, 2), 0.0, 0.008));
  // The reply comes 0.292 s after the request: too late for a 0.2 s timeout.
  short_matcher.on_frame(
      observed(2, rtu_reply(Dialect::Gsl, 1, fc::kGslReadHolding, 4), 0.300, 0.309));
  ASSERT_EQ(short_sink.timeouts.size(), 1u);
  EXPECT_EQ(short_sink.timeouts[0].request_id, 1u);
  EXPECT_EQ(short_sink.timeouts[0].reason, TimeoutReason::NoReply);
  EXPECT_DOUBLE_EQ(short_sink.timeouts[0].waited, 0.2);
  EXPECT_TRUE(short_sink.transactions.empty());
  ASSERT_EQ(short_sink.unsolicited.size(), 1u);
  EXPECT_EQ(short_sink.unsolicited[0].late_for_request_id, std::optional<std::uint64_t>{1u});
  EXPECT_NEAR(short_sink.unsolicited[0].since_request, 0.292, 1e-12);

  // The default 1 s timeout accepts the same reply.
  matcher.on_frame(
      observed(1, test::read_request(Dialect::Gsl, 1, fc::kGslReadHolding, 0, 2), 0.0, 0.008));
  matcher.on_frame(observed(2, rtu_reply(Dialect::Gsl, 1, fc::kGslReadHolding, 4), 0.300, 0.309));
  EXPECT_EQ(sink.transactions.size(), 1u);
  EXPECT_TRUE(sink.timeouts.empty());
}

TEST_F(TransactionMatcherTest, TimeoutWhenTheNextRequestCameFirst) {
  matcher.on_frame(
      observed(1, test::read_request(Dialect::Ascii, 1, fc::kAsciiRead, 0x0004, 4), 0.0, 0.015));
  matcher.on_frame(
      observed(2, test::read_request(Dialect::Ascii, 2, fc::kAsciiRead, 0x0004, 4), 0.2, 0.215));
  EXPECT_TRUE(sink.timeouts.empty()) << "a request to another station leaves station 1 waiting";
  matcher.on_frame(
      observed(3, test::read_request(Dialect::Ascii, 1, fc::kAsciiRead, 0x0020, 2), 0.5, 0.515));
  ASSERT_EQ(sink.timeouts.size(), 1u);
  EXPECT_EQ(sink.timeouts[0].request_id, 1u);
  EXPECT_EQ(sink.timeouts[0].reason, TimeoutReason::NextRequestFirst);
  EXPECT_EQ(sink.timeouts[0].next_request_id, std::optional<std::uint64_t>{3u});
  EXPECT_DOUBLE_EQ(sink.timeouts[0].waited, 0.485);
  EXPECT_EQ(matcher.pending_count(), 2u);
}

TEST_F(TransactionMatcherTest, TimeoutWhenTheCaptureEnds) {
  matcher.on_frame(
      observed(1, test::read_request(Dialect::Gsl, 1, fc::kGslReadHolding, 0, 2), 0.0, 0.008));
  matcher.on_frame(
      observed(2, test::read_request(Dialect::Gsl, 2, fc::kGslReadHolding, 0, 2), 0.3, 0.308));
  matcher.finish();
  ASSERT_EQ(sink.timeouts.size(), 2u);
  EXPECT_EQ(sink.timeouts[0].request_id, 1u);
  EXPECT_EQ(sink.timeouts[1].request_id, 2u);
  for (const Timeout& t : sink.timeouts) EXPECT_EQ(t.reason, TimeoutReason::CaptureEnded);
  EXPECT_DOUBLE_EQ(sink.timeouts[0].waited, 0.3);
  EXPECT_EQ(matcher.pending_count(), 0u);
}

TEST_F(TransactionMatcherTest, ReplyWithoutRequestIsUnsolicited) {
  matcher.on_frame(
      observed(7, rtu_reply(Dialect::Hybrid, 6, fc::kHybridRunningData, 0x4C), 0.0, 0.08));
  ASSERT_EQ(sink.unsolicited.size(), 1u);
  EXPECT_EQ(sink.unsolicited[0].response_id, 7u);
  EXPECT_EQ(sink.unsolicited[0].station, 6);
  EXPECT_FALSE(sink.unsolicited[0].late_for_request_id.has_value());
  EXPECT_EQ(sink.total(), 1u);
}

TEST_F(TransactionMatcherTest, RepeatedReplyIsADuplicateOfTheOriginalRequest) {
  matcher.on_frame(
      observed(1, test::read_request(Dialect::Gsl, 4, fc::kGslReadHolding, 0, 2), 0.0, 0.008));
  matcher.on_frame(observed(2, rtu_reply(Dialect::Gsl, 4, fc::kGslReadHolding, 4), 0.02, 0.029));
  matcher.on_frame(observed(3, rtu_reply(Dialect::Gsl, 4, fc::kGslReadHolding, 4), 0.04, 0.049));
  ASSERT_EQ(sink.duplicates.size(), 1u);
  EXPECT_EQ(sink.duplicates[0].response_id, 3u);
  EXPECT_EQ(sink.duplicates[0].original_request_id, 1u);
  EXPECT_EQ(sink.transactions.size(), 1u);
  EXPECT_TRUE(sink.unsolicited.empty());

  // After a new request the same reply answers it instead.
  matcher.on_frame(
      observed(4, test::read_request(Dialect::Gsl, 4, fc::kGslReadHolding, 0, 2), 0.1, 0.108));
  matcher.on_frame(observed(5, rtu_reply(Dialect::Gsl, 4, fc::kGslReadHolding, 4), 0.12, 0.129));
  EXPECT_EQ(sink.duplicates.size(), 1u);
  ASSERT_EQ(sink.transactions.size(), 2u);
  EXPECT_EQ(sink.transactions[1].request_id, 4u);
}

// A reply of other contents after the first is a second device at the address; the same
// contents again are a repetition. Without contents known (0), nothing can be told.
TEST_F(TransactionMatcherTest, SecondReplyWithOtherContentsIsAnAddressConflict) {
  const auto reply = [](std::uint64_t id, double start, std::uint32_t content,
                        bool check_ok = true) {
    ObservedFrame o = observed(id, rtu_reply(Dialect::Modbus, 2, fc::kGslReadHolding, 4), start,
                               start + 0.009, check_ok);
    o.content = content;
    return o;
  };
  const auto request = [](std::uint64_t id, double start) {
    return observed(id, test::read_request(Dialect::Modbus, 2, fc::kGslReadHolding, 0, 2), start,
                    start + 0.008);
  };
  matcher.on_frame(request(1, 0.0));
  matcher.on_frame(reply(2, 0.02, 0xABCD0009));
  matcher.on_frame(reply(3, 0.04, 0x12340009));
  matcher.on_frame(reply(4, 0.06, 0xABCD0009));
  ASSERT_EQ(sink.duplicates.size(), 2u);
  EXPECT_TRUE(sink.duplicates[0].other_content);
  EXPECT_NEAR(sink.duplicates[0].since_request, 0.032, 1e-9);
  EXPECT_FALSE(sink.duplicates[1].other_content);

  // A damaged second reply, or a first reply whose contents are unknown, is a duplicate.
  matcher.on_frame(request(5, 0.1));
  matcher.on_frame(reply(6, 0.12, 0xABCD0009));
  matcher.on_frame(reply(7, 0.14, 0x55550009, false));
  matcher.on_frame(request(8, 0.2));
  matcher.on_frame(reply(9, 0.22, 0));
  matcher.on_frame(reply(10, 0.24, 0x12340009));
  ASSERT_EQ(sink.duplicates.size(), 4u);
  EXPECT_FALSE(sink.duplicates[2].other_content);
  EXPECT_FALSE(sink.duplicates[3].other_content);
}

// A second reply of other contents answers the same request only within the timeout: later,
// or in an input without timestamps, it may answer a request the capture lost, and is a
// duplicate (a raw dump of a real bus whose sniffer skipped bytes has such replies).
TEST(TransactionMatcherConflict, OnlyTimeTellsASecondDevice) {
  const auto reply = [](std::uint64_t id, double start, std::uint32_t content) {
    ObservedFrame o =
        observed(id, rtu_reply(Dialect::Modbus, 2, fc::kGslReadHolding, 4), start, start + 0.009);
    o.content = content;
    return o;
  };
  const auto request =
      observed(1, test::read_request(Dialect::Modbus, 2, fc::kGslReadHolding, 0, 2), 0.0, 0.008);
  for (const bool timed : {true, false}) {
    RecordingSink sink;
    MatcherConfig config;
    config.timeout = 1.0;
    config.timed = timed;
    RecordingMatcher matcher(sink, config);
    matcher.on_frame(request);
    matcher.on_frame(reply(2, 0.02, 0xABCD0009));
    matcher.on_frame(reply(3, 0.5, 0x12340009));
    matcher.on_frame(reply(4, 1.5, 0x55550009));
    ASSERT_EQ(sink.duplicates.size(), 2u) << timed;
    EXPECT_EQ(sink.duplicates[0].other_content, timed);
    EXPECT_FALSE(sink.duplicates[1].other_content) << "beyond the timeout";
  }
}

// A request repeated byte for byte within the echo window is the tap's adapter: one request,
// which waits for its reply from the echo's end. Later, or with other bytes, or with no window
// (no timestamps), it is the master's own next request.
TEST(TransactionMatcherEcho, RequestRepeatedAtOnceIsAnEcho) {
  RecordingSink sink;
  RecordingMatcher matcher(sink, MatcherConfig{1.0, 0.004, 0.0015});
  const auto request = [](std::uint64_t id, double start, std::uint32_t content) {
    ObservedFrame o = observed(id, test::read_request(Dialect::Gsl, 3, fc::kGslReadHolding, 0, 2),
                               start, start + 0.008);
    o.content = content;
    return o;
  };
  matcher.on_frame(request(1, 0.0, 0x45BD0008));
  matcher.on_frame(request(2, 0.008, 0x45BD0008));
  ASSERT_EQ(sink.echoes.size(), 1u);
  EXPECT_EQ(sink.echoes[0].echo_id, 2u);
  EXPECT_EQ(sink.echoes[0].request_id, 1u);
  // A third copy is no second echo of the first.
  matcher.on_frame(request(3, 0.016, 0x45BD0008));
  EXPECT_EQ(sink.echoes.size(), 1u);
  matcher.on_frame(observed(4, rtu_reply(Dialect::Gsl, 3, fc::kGslReadHolding, 4), 0.05, 0.06));
  ASSERT_EQ(sink.transactions.size(), 1u);
  EXPECT_EQ(sink.transactions[0].request_id, 3u);
  EXPECT_NEAR(sink.transactions[0].latency, 0.026, 1e-9);
  ASSERT_EQ(sink.timeouts.size(), 1u);  // request 1, given up for request 3
  EXPECT_EQ(sink.timeouts[0].request_id, 1u);

  // The echo's end starts the wait: the reply 40 ms later pairs with the request.
  matcher.on_frame(request(5, 1.0, 0x11110008));
  matcher.on_frame(request(6, 1.0085, 0x11110008));
  matcher.on_frame(observed(7, rtu_reply(Dialect::Gsl, 3, fc::kGslReadHolding, 4), 1.0565, 1.07));
  ASSERT_EQ(sink.echoes.size(), 2u);
  ASSERT_EQ(sink.transactions.size(), 2u);
  EXPECT_EQ(sink.transactions[1].request_id, 5u);
  EXPECT_NEAR(sink.transactions[1].latency, 0.04, 1e-9);

  // Other bytes, or a copy after the window: requests of their own.
  matcher.on_frame(request(8, 2.0, 0x22220008));
  matcher.on_frame(request(9, 2.008, 0x33330008));
  matcher.on_frame(request(10, 2.5, 0x33330008));
  EXPECT_EQ(sink.echoes.size(), 2u);
  EXPECT_EQ(sink.timeouts.size(), 3u);

  RecordingSink untimed;
  RecordingMatcher without_window(untimed);
  without_window.on_frame(request(1, 0.0, 0x45BD0008));
  without_window.on_frame(request(2, 0.008, 0x45BD0008));
  EXPECT_TRUE(untimed.echoes.empty());
  EXPECT_EQ(untimed.timeouts.size(), 1u);
}

// A single write's reply is its request's bytes again: a copy 2.5 characters later is a
// slave answering too early (the reply), one at once is the adapter's echo (the window: one
// character, 1.04 ms at 9600 baud).
TEST(TransactionMatcherEcho, AWritesEchoComesAtOnceItsEarlyReplyLater) {
  RecordingSink sink;
  RecordingMatcher matcher(sink, MatcherConfig{1.0, 0.004, 0.00104});
  const auto write = [](std::uint64_t id, double start) {
    ObservedFrame o = observed(id, test::read_request(Dialect::Gsl, 3, fc::kGslWriteSingle, 7, 1),
                               start, start + 0.008);
    o.content = 0x12340008;
    return o;
  };
  matcher.on_frame(write(1, 0.0));
  EXPECT_EQ(matcher.on_frame(write(2, 0.0106)), Role::Response);  // 2.6 ms after
  EXPECT_TRUE(sink.echoes.empty());
  ASSERT_EQ(sink.transactions.size(), 1u);
  EXPECT_EQ(sink.transactions[0].request_id, 1u);

  matcher.on_frame(write(3, 1.0));
  EXPECT_EQ(matcher.on_frame(write(4, 1.008)), Role::Request);
  EXPECT_EQ(matcher.on_frame(write(5, 1.05)), Role::Response);
  ASSERT_EQ(sink.echoes.size(), 1u);
  EXPECT_EQ(sink.echoes[0].request_id, 3u);
  ASSERT_EQ(sink.transactions.size(), 2u);
  EXPECT_EQ(sink.transactions[1].request_id, 3u);
  EXPECT_TRUE(sink.timeouts.empty());
}

// Two masters poll one station: the second request gives up the first, and the station answers
// both in turn. The first reply has the length of the first request, not of the one it is
// paired with, so the second reply is no second device.
TEST_F(TransactionMatcherTest, RepliesToTwoMastersAreNoAddressConflict) {
  const auto reply = [](std::uint64_t id, double start, std::uint8_t n, std::uint32_t content) {
    ObservedFrame o =
        observed(id, rtu_reply(Dialect::Modbus, 2, fc::kGslReadHolding, n), start, start + 0.009);
    o.content = content;
    return o;
  };
  matcher.on_frame(
      observed(1, test::read_request(Dialect::Modbus, 2, fc::kGslReadHolding, 0, 2), 0.0, 0.008));
  matcher.on_frame(
      observed(2, test::read_request(Dialect::Modbus, 2, fc::kGslReadHolding, 10, 4), 0.01, 0.018));
  matcher.on_frame(reply(3, 0.05, 4, 0xABCD0009));
  matcher.on_frame(reply(4, 0.08, 8, 0x1234000D));
  ASSERT_EQ(sink.mismatches.size(), 1u);
  ASSERT_EQ(sink.duplicates.size(), 1u);
  EXPECT_FALSE(sink.duplicates[0].other_content);
}

TEST_F(TransactionMatcherTest, HybridByteCountMismatch) {
  // The seed's own example: a 0x17 read of 0x49 registers answered with n = 0x5E.
  matcher.on_frame(
      observed(1, test::read_request(Dialect::Hybrid, 6, fc::kHybridManufacturer, 0x104B, 0x49),
               0.0, 0.008));
  matcher.on_frame(
      observed(2, rtu_reply(Dialect::Hybrid, 6, fc::kHybridManufacturer, 0x5E), 0.02, 0.12));
  ASSERT_EQ(sink.mismatches.size(), 1u);
  EXPECT_EQ(sink.mismatches[0].request_id, 1u);
  EXPECT_EQ(sink.mismatches[0].response_id, 2u);
  EXPECT_EQ(sink.mismatches[0].expected, 4u + 2u * 0x49);
  EXPECT_EQ(sink.mismatches[0].found, 0x5Eu);
  EXPECT_EQ(sink.mismatches[0].unit, CountUnit::Bytes);
  EXPECT_EQ(sink.transactions.size(), 1u);

  // Restore-factory replies are always 8 bytes, whatever the request's count.
  matcher.on_frame(
      observed(3, test::read_request(Dialect::Hybrid, 6, fc::kHybridRestoreFactory, 0x1024, 0x7B),
               0.2, 0.208));
  matcher.on_frame(
      observed(4, rtu_reply(Dialect::Hybrid, 6, fc::kHybridRestoreFactory, 8), 0.22, 0.233));
  EXPECT_EQ(sink.mismatches.size(), 1u);
  EXPECT_EQ(sink.transactions.size(), 2u);
}

TEST_F(TransactionMatcherTest, GslByteCountMismatch) {
  matcher.on_frame(
      observed(1, test::read_request(Dialect::Gsl, 1, fc::kGslReadInput, 1050, 10), 0.0, 0.008));
  matcher.on_frame(observed(2, rtu_reply(Dialect::Gsl, 1, fc::kGslReadInput, 18), 0.02, 0.044));
  ASSERT_EQ(sink.mismatches.size(), 1u);
  EXPECT_EQ(sink.mismatches[0].expected, 20u);
  EXPECT_EQ(sink.mismatches[0].found, 18u);
  EXPECT_EQ(sink.mismatches[0].unit, CountUnit::Bytes);

  matcher.on_frame(
      observed(3, test::read_request(Dialect::Gsl, 1, fc::kGslReadInput, 1050, 10), 0.1, 0.108));
  matcher.on_frame(observed(4, rtu_reply(Dialect::Gsl, 1, fc::kGslReadInput, 20), 0.12, 0.146));
  EXPECT_EQ(sink.mismatches.size(), 1u) << "a matching count must not be reported";
}

TEST_F(TransactionMatcherTest, AsciiWordCountMismatch) {
  matcher.on_frame(
      observed(1, test::read_request(Dialect::Ascii, 1, fc::kAsciiRead, 0x0050, 7), 0.0, 0.015));
  matcher.on_frame(observed(2, ascii_reply(1, 0x0050, 6), 0.05, 0.09));
  ASSERT_EQ(sink.transactions.size(), 1u);
  ASSERT_EQ(sink.mismatches.size(), 1u);
  EXPECT_EQ(sink.mismatches[0].expected, 7u);
  EXPECT_EQ(sink.mismatches[0].found, 6u);
  EXPECT_EQ(sink.mismatches[0].unit, CountUnit::Words);
}

TEST_F(TransactionMatcherTest, AsciiReplyMustRepeatTheStartAddress) {
  matcher.on_frame(
      observed(1, test::read_request(Dialect::Ascii, 1, fc::kAsciiRead, 0x0050, 7), 0.0, 0.015));
  matcher.on_frame(observed(2, ascii_reply(1, 0x0020, 7), 0.05, 0.09));
  EXPECT_TRUE(sink.transactions.empty());
  EXPECT_EQ(sink.unsolicited.size(), 1u);
  matcher.on_frame(observed(3, ascii_reply(1, 0x0050, 7), 0.1, 0.14));
  ASSERT_EQ(sink.transactions.size(), 1u);
  EXPECT_EQ(sink.transactions[0].response_id, 3u);
}

TEST_F(TransactionMatcherTest, ReplyWithBadCheckStillAnswers) {
  matcher.on_frame(observed(
      1, test::read_request(Dialect::Hybrid, 6, fc::kHybridDeviceInfo, 0x1060, 2), 0.0, 0.008));
  // Wrong length too: a corrupted reply's length field is not judged.
  matcher.on_frame(observed(2, rtu_reply(Dialect::Hybrid, 6, fc::kHybridDeviceInfo, 9), 0.02, 0.034,
                            /*check_ok=*/false));
  matcher.finish();
  ASSERT_EQ(sink.transactions.size(), 1u);
  EXPECT_EQ(sink.transactions[0].request_id, 1u);
  EXPECT_FALSE(sink.transactions[0].reply_check_ok);
  EXPECT_TRUE(sink.transactions[0].request_check_ok);
  EXPECT_TRUE(sink.mismatches.empty());
  EXPECT_TRUE(sink.timeouts.empty());
}

TEST_F(TransactionMatcherTest, AdvanceReportsTimeoutsWhileTheBusIsSilent) {
  matcher.on_frame(
      observed(1, test::read_request(Dialect::Gsl, 2, fc::kGslReadHolding, 0, 2), 0.0, 0.010));
  matcher.on_frame(
      observed(2, test::read_request(Dialect::Gsl, 1, fc::kGslReadHolding, 0, 2), 0.1, 0.105));
  matcher.advance(0.9);
  EXPECT_TRUE(sink.timeouts.empty());
  matcher.advance(1.02);
  ASSERT_EQ(sink.timeouts.size(), 1u);
  EXPECT_EQ(sink.timeouts[0].request_id, 1u);
  matcher.advance(1.2);
  ASSERT_EQ(sink.timeouts.size(), 2u);
  EXPECT_EQ(sink.timeouts[1].request_id, 2u);
  EXPECT_EQ(sink.timeouts[1].reason, TimeoutReason::NoReply);
  matcher.finish();
  EXPECT_EQ(sink.timeouts.size(), 2u) << "finish must not report a request twice";
}

TEST_F(TransactionMatcherTest, SimultaneousTimeoutsComeInDeadlineOrder) {
  matcher.on_frame(
      observed(1, test::read_request(Dialect::Gsl, 9, fc::kGslReadHolding, 0, 2), 0.0, 0.01));
  matcher.on_frame(
      observed(2, test::read_request(Dialect::Gsl, 3, fc::kGslReadHolding, 0, 2), 0.02, 0.03));
  matcher.advance(5.0);
  ASSERT_EQ(sink.timeouts.size(), 2u);
  EXPECT_EQ(sink.timeouts[0].station, 9);
  EXPECT_EQ(sink.timeouts[1].station, 3);
}

}  // namespace
}  // namespace pvtap
