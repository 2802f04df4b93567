// TcpDirectionStream: one direction of a TCP connection back in order, holes reported as lost.
#include "pvtap/carriers/tcp_stream.h"

#include <gtest/gtest.h>

#include <optional>
#include <string>
#include <vector>

namespace pvtap {
namespace {

// Records what the stream delivers: bytes as text, gaps as "[lost N]".
struct Recorder : TcpStreamSink {
  void on_stream_data(std::span<const std::uint8_t> bytes, double time) override {
    text.append(bytes.begin(), bytes.end());
    times.push_back(time);
  }
  void on_stream_gap(std::uint64_t lost, double time) override {
    text += "[lost " + std::to_string(lost) + "]";
    gap_times.push_back(time);
  }
  std::string text;
  std::vector<double> times;
  std::vector<double> gap_times;
};

std::span<const std::uint8_t> bytes_of(const std::string& s) {
  return {reinterpret_cast<const std::uint8_t*>(s.data()), s.size()};
}

class TcpStreamTest : public ::testing::Test {
 protected:
  void segment(std::uint32_t seq, const std::string& payload, double time = 0) {
    stream_.on_segment(seq, bytes_of(payload), static_cast<std::uint32_t>(payload.size()), false,
                       false, time);
  }
  Recorder sink_;
  TcpDirectionStream stream_{sink_, TcpDirectionStream::Limits{2.0, 64}};
};

TEST_F(TcpStreamTest, InOrderSegmentsAfterTheHandshake) {
  stream_.on_segment(999, {}, 0, true, false, 0.0);  // SYN
  segment(1000, "abc");
  segment(1003, "def");
  EXPECT_EQ(sink_.text, "abcdef");
  EXPECT_EQ(stream_.stats().delivered_bytes, 6u);
}

TEST_F(TcpStreamTest, OutOfOrderSegmentWaitsForTheHole) {
  segment(100, "ab");
  segment(105, "fg", 1.0);
  EXPECT_EQ(sink_.text, "ab");
  EXPECT_TRUE(stream_.has_hole());
  segment(102, "cde", 1.1);
  EXPECT_EQ(sink_.text, "abcdefg");
  EXPECT_FALSE(stream_.has_hole());
  EXPECT_EQ(stream_.stats().out_of_order_segments, 1u);
}

TEST_F(TcpStreamTest, RetransmissionsAndOverlapsAreDeliveredOnce) {
  segment(100, "abcd");
  segment(100, "abcd");    // exact repeat
  segment(102, "cdefgh");  // repacketized: two old bytes, four new
  segment(105, "fg");      // inside what was delivered
  EXPECT_EQ(sink_.text, "abcdefgh");
  EXPECT_EQ(stream_.stats().retransmitted_bytes, 4u + 2u + 2u);
}

TEST_F(TcpStreamTest, PendingCopiesOfOneStartKeepTheLonger) {
  segment(100, "a");
  segment(103, "d");
  segment(103, "def");
  segment(101, "bc");
  EXPECT_EQ(sink_.text, "abcdef");
}

TEST_F(TcpStreamTest, PeerAckBeyondAHoleMakesItALossOfKnownSize) {
  segment(100, "ab", 1.0);
  segment(110, "klm", 1.2);
  stream_.on_peer_ack(113, 1.3);
  EXPECT_EQ(sink_.text, "ab[lost 8]klm");
  EXPECT_EQ(stream_.stats().lost_bytes, 8u);
  // The gap is placed where the data went missing: after the last bytes before it.
  ASSERT_EQ(sink_.gap_times.size(), 1u);
  EXPECT_DOUBLE_EQ(sink_.gap_times[0], 1.0);
}

TEST_F(TcpStreamTest, PeerAckOfUnseenTailIsALoss) {
  segment(100, "ab");
  stream_.on_peer_ack(102, 0.1);  // acknowledges what was seen: nothing lost
  EXPECT_EQ(sink_.text, "ab");
  stream_.on_peer_ack(107, 0.2);
  EXPECT_EQ(sink_.text, "ab[lost 5]");
  segment(107, "h");
  EXPECT_EQ(sink_.text, "ab[lost 5]h");
}

TEST_F(TcpStreamTest, AckOfTheFinIsNotALoss) {
  segment(100, "ab");
  stream_.on_segment(102, {}, 0, false, true, 0.5);  // FIN
  stream_.on_peer_ack(103, 0.6);
  EXPECT_EQ(sink_.text, "ab");
  EXPECT_EQ(stream_.stats().lost_bytes, 0u);
}

TEST_F(TcpStreamTest, OldHoleExpires) {
  segment(100, "ab", 1.0);
  segment(104, "ef", 1.5);
  stream_.expire(3.0);
  EXPECT_EQ(sink_.text, "ab");
  stream_.expire(3.6);
  EXPECT_EQ(sink_.text, "ab[lost 2]ef");
}

// A live capture wakes at the deadline the stream gives: the hole must go then, not a wake
// later, and not before it.
TEST_F(TcpStreamTest, AHoleGoesAtItsDeadline) {
  EXPECT_FALSE(stream_.hole_deadline().has_value());
  segment(100, "ab", 1.0);
  segment(106, "gh", 1.7);
  segment(104, "ef", 1.5);
  const std::optional<double> due = stream_.hole_deadline();
  ASSERT_TRUE(due.has_value());
  EXPECT_GT(*due, 3.5);  // the oldest waiting segment, 1.5, and 2 s
  EXPECT_LT(*due, 3.5 + 1e-9);
  stream_.expire(3.5);
  EXPECT_EQ(sink_.text, "ab");
  stream_.expire(*due);
  EXPECT_EQ(sink_.text, "ab[lost 2]efgh");
  EXPECT_FALSE(stream_.hole_deadline().has_value());
}

TEST_F(TcpStreamTest, TooMuchWaitingDataGivesTheHoleUp) {
  segment(0, "a");
  segment(10, std::string(70, 'x'));  // more than max_buffered (64) behind the hole
  EXPECT_EQ(sink_.text, "a[lost 9]" + std::string(70, 'x'));
}

TEST_F(TcpStreamTest, TooManyWaitingSegmentsGiveTheHoleUp) {
  Recorder sink;
  TcpDirectionStream stream(sink, TcpDirectionStream::Limits{2.0, 1 << 20, 3});
  const std::string one = "x";
  stream.on_segment(0, bytes_of("a"), 1, false, false, 0);
  for (std::uint32_t seq = 13; seq >= 10; --seq) {  // four one-byte segments behind a hole
    stream.on_segment(seq, bytes_of(one), 1, false, false, 0);
  }
  EXPECT_EQ(sink.text, "a[lost 9]xxxx");
  EXPECT_FALSE(stream.has_hole());
}

TEST_F(TcpStreamTest, FlushLosesEveryRemainingHole) {
  segment(0, "a");
  segment(3, "d");
  segment(6, "g");
  stream_.flush(9.0);
  EXPECT_EQ(sink_.text, "a[lost 2]d[lost 2]g");
  EXPECT_EQ(stream_.stats().gaps, 2u);
}

TEST_F(TcpStreamTest, SequenceNumbersWrapAroundZero) {
  stream_.on_segment(0xFFFFFFFDu, {}, 0, true, false, 0.0);  // data starts at 0xFFFFFFFE
  segment(0xFFFFFFFEu, "abcd");                              // wraps to 2
  segment(2, "ef");
  EXPECT_EQ(sink_.text, "abcdef");
}

TEST_F(TcpStreamTest, SnapLengthCutIsALoss) {
  const std::string captured = "abc";
  stream_.on_segment(10, bytes_of(captured), 8, false, false, 0.0);
  segment(18, "ij");
  EXPECT_EQ(sink_.text, "abc[lost 5]ij");
}

}  // namespace
}  // namespace pvtap
