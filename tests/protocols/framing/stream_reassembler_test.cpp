// Specific behaviours of the stream reassembler: silence, data loss, timing, noise runs.
#include "pvtap/framing/stream_reassembler.h"

#include <gtest/gtest.h>

#include <algorithm>

#include "bus_script.h"
#include "hex_bytes.h"
#include "pvtap/codec/checksums.h"
#include "pvtap/statistics/bus_timing.h"

namespace pvtap {
namespace {

using test::hex_bytes;

const auto kGoodRequest = hex_bytes("01 03 00 00 00 0A C5 CD");
const auto kBadEcho = hex_bytes("06 18 08 31 00 00 67 10 2A 09 3C 2A 86");
const auto kAsciiRequest = hex_bytes("05 30 31 52 30 30 30 34 30 34 30 31 64 62 04");

std::vector<std::uint8_t> join(std::initializer_list<std::vector<std::uint8_t>> parts) {
  std::vector<std::uint8_t> out;
  for (const auto& p : parts) out.insert(out.end(), p.begin(), p.end());
  return out;
}

TEST(StreamReassembler, ByteAtATimeMixedDialectsOnOneBus) {
  test::CapturingSink sink;
  StreamReassembler r({}, sink);
  const auto stream = join({kAsciiRequest, kGoodRequest, kAsciiRequest});
  for (auto b : stream) r.feed(BusChunk{std::span(&b, 1), 0.0, Direction::Unknown});
  ASSERT_EQ(sink.events.size(), 3u);  // good frames are reported without waiting for finish
  EXPECT_EQ(sink.events[0].frame.dialect, Dialect::Ascii);
  EXPECT_EQ(sink.events[1].frame.dialect, Dialect::Gsl);
  EXPECT_EQ(sink.events[2].frame.dialect, Dialect::Ascii);
  EXPECT_EQ(r.pending_bytes(), 0u);
}

TEST(StreamReassembler, BadFrameWaitsForEvidenceThenFinishResolvesIt) {
  test::CapturingSink sink;
  StreamReassembler r({}, sink);
  r.feed(BusChunk{kBadEcho, 0.0, Direction::FromSlave});
  EXPECT_TRUE(sink.events.empty()) << "a bad frame needs evidence for its end";
  r.finish();
  ASSERT_EQ(sink.events.size(), 1u);
  EXPECT_TRUE(sink.events[0].is_frame);
  EXPECT_FALSE(sink.events[0].frame.check.ok);
  EXPECT_EQ(sink.events[0].frame.check.expected, 0x8A2B);
}

TEST(StreamReassembler, SilenceAfterABadFrameResolvesItWhileLive) {
  const BusTiming timing(9600);
  test::CapturingSink sink;
  StreamReassembler r({}, sink);
  const double t = 1000.0;
  r.feed(BusChunk{kBadEcho, t, Direction::FromSlave});
  r.idle(t + timing.t15);
  EXPECT_TRUE(sink.events.empty()) << "t1.5 is not a frame boundary";
  r.idle(t + timing.t35);
  ASSERT_EQ(sink.events.size(), 1u);
  EXPECT_FALSE(sink.events[0].frame.check.ok);
  EXPECT_EQ(sink.events[0].bytes, kBadEcho);
}

TEST(StreamReassembler, TrailingNoiseIsReportedOnceFramesAreGivenUp) {
  const BusTiming timing(9600);
  test::CapturingSink sink;
  StreamReassembler r({}, sink);
  const auto noise = hex_bytes("00 00 07");  // 07 could begin a request to station 7
  r.feed(BusChunk{noise, 5.0, Direction::Unknown});
  r.idle(5.0 + 2 * timing.t35);
  EXPECT_EQ(r.pending_bytes(), 3u) << "a t3.5 silence does not give up a frame yet";
  r.idle(5.0 + ReassemblerOptions{}.give_up_after + 2 * timing.t35);
  ASSERT_EQ(sink.events.size(), 1u);
  EXPECT_FALSE(sink.events[0].is_frame);
  EXPECT_EQ(sink.events[0].bytes, noise);
}

// A live clock reads bytes late when the OS is busy: a frame sent whole can arrive in two
// reads with a silence longer than t3.5 between them. Its good check still makes it a frame.
TEST(StreamReassembler, AGoodFrameWhoseTailComesLateIsStillAFrameWhileLive) {
  const BusTiming timing(9600);
  for (const auto& frame : {kAsciiRequest, kGoodRequest}) {
    test::CapturingSink sink;
    StreamReassembler r({}, sink);
    const std::span<const std::uint8_t> bytes(frame);
    r.feed(BusChunk{bytes.first(bytes.size() - 2), 10.0, Direction::Unknown});
    r.idle(10.0 + 0.020);
    EXPECT_TRUE(sink.events.empty());
    r.feed(BusChunk{bytes.last(2), 10.0 + 0.020, Direction::Unknown});
    ASSERT_EQ(sink.events.size(), 1u);
    EXPECT_TRUE(sink.events[0].is_frame);
    EXPECT_TRUE(sink.events[0].frame.check.ok);
    EXPECT_EQ(sink.events[0].bytes, frame);
    EXPECT_GT(sink.events[0].frame.max_inner_gap, timing.t35);
  }
}

// The same frame whose tail never comes: given up as noise after give_up_after.
TEST(StreamReassembler, AFrameWithoutItsTailIsGivenUpAfterALongSilence) {
  const BusTiming timing(9600);
  test::CapturingSink sink;
  ReassemblerOptions options;
  options.give_up_after = 0.1;
  StreamReassembler r(options, sink);
  const std::span<const std::uint8_t> bytes(kGoodRequest);
  r.feed(BusChunk{bytes.first(6), 10.0, Direction::Unknown});
  r.idle(10.0 + 0.05);
  EXPECT_TRUE(sink.events.empty());
  r.idle(10.0 + 0.1 + timing.t35);
  ASSERT_EQ(sink.events.size(), 1u);
  EXPECT_FALSE(sink.events[0].is_frame);
  EXPECT_EQ(r.pending_bytes(), 0u);
}

TEST(StreamReassembler, DiscontinuityKeepsFramesFromSpanningLostData) {
  test::CapturingSink sink;
  StreamReassembler r({}, sink);
  const std::span<const std::uint8_t> req(kGoodRequest);
  r.feed(BusChunk{req.first(4), 0.0, Direction::Unknown});
  r.discontinuity();
  r.feed(BusChunk{req.subspan(4), 0.0, Direction::Unknown});
  r.feed(BusChunk{kGoodRequest, 0.0, Direction::Unknown});
  r.finish();
  ASSERT_EQ(sink.events.size(), 3u);
  EXPECT_FALSE(sink.events[0].is_frame);
  EXPECT_EQ(sink.events[0].bytes.size(), 4u);
  EXPECT_FALSE(sink.events[1].is_frame);
  EXPECT_TRUE(sink.events[2].is_frame);
  EXPECT_EQ(sink.events[2].offset, 8u);
  EXPECT_EQ(r.totals().bytes_in, r.totals().frame_bytes + r.totals().noise_bytes);
}

TEST(StreamReassembler, EstimatesFrameTimesFromTheLastByteStamp) {
  const BusTiming timing(9600);
  test::CapturingSink sink;
  StreamReassembler r({}, sink);
  r.feed(BusChunk{kGoodRequest, 10.0, Direction::ToSlave});
  ASSERT_EQ(sink.events.size(), 1u);
  EXPECT_DOUBLE_EQ(sink.events[0].frame.end_time, 10.0);
  EXPECT_NEAR(sink.events[0].frame.start_time, 10.0 - 8 * timing.char_time, 1e-9);
}

TEST(StreamReassembler, MeasuresAGapInsideAFrame) {
  const BusTiming timing(9600);
  test::CapturingSink sink;
  StreamReassembler r({}, sink);
  const std::span<const std::uint8_t> req(kGoodRequest);
  const double first_end = 1.0;
  const double pause = 2 * timing.char_time;
  r.feed(BusChunk{req.first(3), first_end, Direction::Unknown});
  r.feed(BusChunk{req.subspan(3), first_end + pause + 5 * timing.char_time, Direction::Unknown});
  ASSERT_EQ(sink.events.size(), 1u);
  EXPECT_NEAR(sink.events[0].frame.max_inner_gap, pause, 1e-9);
  EXPECT_TRUE(r.timing_trusted());
}

TEST(StreamReassembler, BatchedTimestampsAreDetectedAndExplained) {
  test::CapturingSink sink;
  StreamReassembler r({}, sink);
  // 64 bytes cannot arrive in 1 ms at 9600 baud: these stamps are batched.
  std::vector<std::uint8_t> bytes(64, 0x00);
  r.feed(BusChunk{bytes, 1.000, Direction::Unknown});
  r.feed(BusChunk{bytes, 1.001, Direction::Unknown});
  EXPECT_FALSE(r.timing_trusted());
  EXPECT_NE(r.timing_reason().find("batched"), std::string_view::npos);
}

TEST(StreamReassembler, UntrustedTimestampsWithoutABoundaryGapNeverActAsEvidence) {
  test::CapturingSink sink;
  ReassemblerOptions options;
  options.timestamps = TimestampTrust::Untrusted;
  options.boundary_gap = 0;
  StreamReassembler r(options, sink);
  r.feed(BusChunk{kBadEcho, 1.0, Direction::FromSlave});
  r.idle(2.0);
  EXPECT_TRUE(sink.events.empty());
  EXPECT_FALSE(r.timing_trusted());
}

TEST(StreamReassembler, UntrustedTimestampsProveABoundaryOnlyPastTheBoundaryGap) {
  test::CapturingSink sink;
  ReassemblerOptions options;
  options.timestamps = TimestampTrust::Untrusted;
  options.boundary_gap = 0.05;
  StreamReassembler r(options, sink);
  r.feed(BusChunk{kBadEcho, 1.0, Direction::FromSlave});
  r.idle(1.04);
  EXPECT_TRUE(sink.events.empty()) << "a silence shorter than the gap proves nothing";
  r.idle(1.06);
  ASSERT_EQ(sink.events.size(), 1u);
  EXPECT_TRUE(sink.events[0].is_frame);
  EXPECT_FALSE(sink.events[0].frame.check.ok);
}

// A gateway sends a long reply in segments as its packing timer fires: at 9600 baud each
// 16-byte segment is 16.7 ms of wire time, so the time between segments is their own wire
// time (plus the gateway's delay), never a silence past the 50 ms gateway gap. Nothing may
// cut the reply, good or damaged; the silences between replies still pin a damaged one.
TEST(StreamReassembler, ALongReplyInGatewaySegmentsIsNeverCutByTheGapRule) {
  const BusTiming timing(9600);
  std::vector<std::uint8_t> body{0x01, 0x03, 196};
  for (unsigned i = 0; i < 196; ++i) body.push_back(static_cast<std::uint8_t>(i * 37 + 11));
  const std::uint16_t crc = Crc16Modbus::compute(body);
  auto good = body;
  good.push_back(static_cast<std::uint8_t>(crc & 0xFF));
  good.push_back(static_cast<std::uint8_t>(crc >> 8));
  auto damaged = good;
  damaged[120] ^= 0x10;
  ASSERT_EQ(good.size(), 201u);
  test::CapturingSink sink;
  ReassemblerOptions options;
  options.timestamps = TimestampTrust::Untrusted;
  options.boundary_gap = 0.05;
  StreamReassembler r(options, sink);
  double t = 100.0;
  for (const auto* reply : {&good, &damaged, &good}) {
    const std::span<const std::uint8_t> bytes(*reply);
    for (std::size_t at = 0; at < bytes.size(); at += 16) {
      const auto piece = bytes.subspan(at, std::min<std::size_t>(16, bytes.size() - at));
      // Stamped when its last byte was on the wire, plus up to 15 ms of packing delay.
      t += static_cast<double>(piece.size()) * timing.char_time;
      r.feed(BusChunk{piece, t + static_cast<double>(at % 3) * 0.005, Direction::FromSlave});
    }
    t += 1.0;  // the next poll
  }
  r.finish();
  ASSERT_EQ(sink.events.size(), 3u);
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_TRUE(sink.events[i].is_frame) << i;
    EXPECT_EQ(sink.events[i].bytes.size(), 201u) << i;
    EXPECT_EQ(sink.events[i].frame.check.ok, i != 1) << i;
  }
}

TEST(StreamReassembler, LongGarbageIsReportedInBoundedRuns) {
  test::CapturingSink sink;
  StreamReassembler r({}, sink);
  std::vector<std::uint8_t> garbage(100000, 0x00);  // address 0 never starts a frame
  r.feed(BusChunk{garbage, 0.0, Direction::Unknown});
  EXPECT_LT(r.pending_bytes(), 8192u) << "noise must not pile up in the buffer";
  r.finish();
  std::uint64_t noise = 0;
  for (const auto& e : sink.events) {
    EXPECT_FALSE(e.is_frame);
    EXPECT_LE(e.bytes.size(), 4096u);
    noise += e.bytes.size();
  }
  EXPECT_EQ(noise, garbage.size());
}

TEST(StreamReassembler, DialectRestrictionTurnsOtherDialectsIntoNoise) {
  test::CapturingSink sink;
  ReassemblerOptions options;
  options.dialects = DialectSet::only(Dialect::Hybrid);
  StreamReassembler r(options, sink);
  const auto stream = join({kAsciiRequest, kGoodRequest});
  r.feed(BusChunk{stream, 0.0, Direction::Unknown});
  r.finish();
  for (const auto& e : sink.events) EXPECT_FALSE(e.is_frame);
  EXPECT_EQ(r.totals().noise_bytes, stream.size());
}

TEST(StreamReassembler, FrameSplitAtEveryPointIsReassembled) {
  const auto stream = join({kGoodRequest, kAsciiRequest});
  for (std::size_t cut = 1; cut < stream.size(); ++cut) {
    test::CapturingSink sink;
    StreamReassembler r({}, sink);
    const std::span<const std::uint8_t> all(stream);
    r.feed(BusChunk{all.first(cut), 0.0, Direction::Unknown});
    r.feed(BusChunk{all.subspan(cut), 0.0, Direction::Unknown});
    r.finish();
    ASSERT_EQ(sink.events.size(), 2u) << "cut " << cut;
    EXPECT_TRUE(sink.events[0].frame.check.ok);
    EXPECT_TRUE(sink.events[1].frame.check.ok);
  }
}

// Frames and noise runs with their times, as pvtap's own capture of them gives them back.
struct TimedSink : ReassemblerSink {
  struct Piece {
    bool frame;
    std::uint64_t offset;
    std::size_t size;
    double start;
    double end;
    bool check_ok;
  };
  void on_frame(const FrameEvent& e) override {
    pieces.push_back({true, e.offset, e.bytes.size(), e.start_time, e.end_time, e.check.ok});
  }
  void on_noise(const NoiseEvent& e) override {
    pieces.push_back({false, e.offset, e.bytes.size(), e.start_time, e.end_time, false});
  }
  std::vector<Piece> pieces;
};

TEST(StreamReassembler, DecidedPiecesKeepTheirBoundsAndTimes) {
  TimedSink sink;
  StreamReassembler r({}, sink);
  const std::vector<std::uint8_t> garbage = {0xFF, 0x00, 0xF0};
  // A damaged reply whose end nothing but its record pins, noise right behind it, and noise
  // that holds a good request (its run decided so: it stays noise), each timed to the bit.
  r.feed_decided(DecidedPiece{kBadEcho, 10.0000001, 10.0135, Direction::Unknown, false});
  r.feed_decided(DecidedPiece{garbage, 10.0136, 10.0167, Direction::Unknown, true});
  r.feed_decided(
      DecidedPiece{join({garbage, kGoodRequest}), 10.5, 10.51, Direction::Unknown, true});
  r.feed_decided(DecidedPiece{kGoodRequest, 11.25, 11.2583, Direction::Unknown, false});
  ASSERT_EQ(sink.pieces.size(), 4u) << "each piece is reported as it comes, whole";
  EXPECT_TRUE(sink.pieces[0].frame);
  EXPECT_FALSE(sink.pieces[0].check_ok);
  EXPECT_EQ(sink.pieces[0].start, 10.0000001);
  EXPECT_EQ(sink.pieces[0].end, 10.0135);
  EXPECT_FALSE(sink.pieces[1].frame);
  EXPECT_EQ(sink.pieces[1].offset, kBadEcho.size());
  EXPECT_EQ(sink.pieces[1].start, 10.0136);
  EXPECT_FALSE(sink.pieces[2].frame);
  EXPECT_EQ(sink.pieces[2].size, garbage.size() + kGoodRequest.size());
  EXPECT_EQ(sink.pieces[2].end, 10.51);
  EXPECT_TRUE(sink.pieces[3].frame);
  EXPECT_TRUE(sink.pieces[3].check_ok);
  EXPECT_EQ(sink.pieces[3].offset, kBadEcho.size() + 2 * garbage.size() + kGoodRequest.size());
  EXPECT_EQ(r.totals().bytes_in, r.totals().frame_bytes + r.totals().noise_bytes);
  EXPECT_EQ(r.totals().noise_runs, 2u);
}

TEST(StreamReassembler, BytesPendingBeforeADecidedPieceAreDecidedFirst) {
  TimedSink sink;
  StreamReassembler r({}, sink);
  r.feed(BusChunk{kBadEcho, 5.0, Direction::Unknown});
  EXPECT_TRUE(sink.pieces.empty());
  r.feed_decided(DecidedPiece{kGoodRequest, 6.0, 6.0083, Direction::Unknown, false});
  ASSERT_EQ(sink.pieces.size(), 2u);
  EXPECT_TRUE(sink.pieces[0].frame);
  EXPECT_FALSE(sink.pieces[0].check_ok);
  EXPECT_EQ(sink.pieces[1].offset, kBadEcho.size());
  EXPECT_EQ(r.pending_bytes(), 0u);
}

}  // namespace
}  // namespace pvtap
