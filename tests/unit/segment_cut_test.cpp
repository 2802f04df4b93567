// Cutting buffers into frames, noise and "need more" without timestamps (TCP reassembly).
#include "pvtap/segment_cut.h"

#include <gtest/gtest.h>

#include "hex_bytes.h"
#include "pvtap/checksums.h"

namespace pvtap {
namespace {

using test::hex_bytes;
using Kind = SegmentCut::Kind;

const auto kGoodRequest = hex_bytes("01 03 00 00 00 0A C5 CD");
const auto kBadEcho = hex_bytes("06 18 08 31 00 00 67 10 2A 09 3C 2A 86");
const auto kGoodDeviceReply = hex_bytes("09 11 08 22 00 00 6B 22 00 00 6B F2 77");
const auto kAsciiRequest = hex_bytes("05 30 31 52 30 30 30 34 30 34 30 31 64 62 04");

std::vector<std::uint8_t> join(std::initializer_list<std::vector<std::uint8_t>> parts) {
  std::vector<std::uint8_t> out;
  for (const auto& p : parts) out.insert(out.end(), p.begin(), p.end());
  return out;
}

std::vector<std::uint8_t> with_crc(std::vector<std::uint8_t> body) {
  const std::uint16_t crc = Crc16Modbus::compute(body);
  body.push_back(static_cast<std::uint8_t>(crc & 0xFF));
  body.push_back(static_cast<std::uint8_t>(crc >> 8));
  return body;
}

CutOptions from_master(bool more = true) {
  return CutOptions{RoleHint::Request, DialectSet::all(), more};
}
CutOptions from_slave(bool more = true) {
  return CutOptions{RoleHint::Response, DialectSet::all(), more};
}

TEST(SegmentCut, GoodFrameIsCutAtOnceWhateverFollows) {
  const auto bytes = join({kGoodRequest, hex_bytes("01")});
  const SegmentCut cut = cut_segment(bytes, from_master());
  EXPECT_EQ(cut.kind, Kind::Frame);
  EXPECT_EQ(cut.length, 8u);
  EXPECT_EQ(cut.dialect, Dialect::Gsl);
  EXPECT_EQ(cut.role, Role::Request);
  EXPECT_TRUE(cut.check.ok);
}

TEST(SegmentCut, FirstPieceOfOneByteAsksForMoreWithUnknownLength) {
  const SegmentCut cut = cut_segment(hex_bytes("01"), from_master());
  EXPECT_EQ(cut.kind, Kind::NeedMore);
  EXPECT_EQ(cut.length, 0u);
}

TEST(SegmentCut, HeaderThatFixesTheLengthAsksForExactlyTheRest) {
  const std::span<const std::uint8_t> request(kGoodRequest);
  const SegmentCut cut = cut_segment(request.first(6), from_master());
  EXPECT_EQ(cut.kind, Kind::NeedMore);
  EXPECT_EQ(cut.length, 8u);
}

TEST(SegmentCut, TruncatedFrameIsNoiseWhenNothingMoreCanCome) {
  const std::span<const std::uint8_t> request(kGoodRequest);
  const SegmentCut cut = cut_segment(request.first(6), from_master(false));
  EXPECT_EQ(cut.kind, Kind::Noise);
  EXPECT_EQ(cut.length, 6u);
}

TEST(SegmentCut, NoiseEndsWhereAFrameStarts) {
  const auto bytes = join({hex_bytes("00 07 00"), kGoodRequest});
  const SegmentCut cut = cut_segment(bytes, from_master());
  EXPECT_EQ(cut.kind, Kind::Noise);
  EXPECT_EQ(cut.length, 3u);
  const SegmentCut next = cut_segment(std::span(bytes).subspan(3), from_master());
  EXPECT_EQ(next.kind, Kind::Frame);
  EXPECT_EQ(next.length, 8u);
}

TEST(SegmentCut, BadFrameThatEndsTheBufferIsAFrameWithItsExpectedCheck) {
  const SegmentCut cut = cut_segment(kBadEcho, from_slave());
  EXPECT_EQ(cut.kind, Kind::Frame);
  EXPECT_EQ(cut.length, kBadEcho.size());
  EXPECT_EQ(cut.dialect, Dialect::Hybrid);
  EXPECT_FALSE(cut.check.ok);
  EXPECT_EQ(cut.check.expected, 0x8A2B);
}

TEST(SegmentCut, BadFrameFollowedByAGoodFrameIsAFrame) {
  const auto bytes = join({kBadEcho, kGoodDeviceReply});
  const SegmentCut cut = cut_segment(bytes, from_slave());
  EXPECT_EQ(cut.kind, Kind::Frame);
  EXPECT_EQ(cut.length, kBadEcho.size());
  EXPECT_FALSE(cut.check.ok);
}

TEST(SegmentCut, BadReadingWithAGoodFrameInsideIsNoise) {
  // "09 06" reads as a GSL write whose 8 bytes would swallow the good request after it.
  const auto bytes = join({hex_bytes("09 06"), kGoodRequest});
  const SegmentCut cut = cut_segment(bytes, from_master());
  EXPECT_EQ(cut.kind, Kind::Noise);
  EXPECT_EQ(cut.length, 2u);
}

TEST(SegmentCut, BadFrameFollowedByAPartialFrameWaitsForIt) {
  const std::span<const std::uint8_t> next(kGoodDeviceReply);
  const auto bytes = join({kBadEcho, {next.begin(), next.begin() + 4}});
  EXPECT_EQ(cut_segment(bytes, from_slave()).kind, Kind::NeedMore);
}

TEST(SegmentCut, PendingReadingIsNoiseWhenAGoodFrameStartsInsideIt) {
  // "01 03 20" announces 32 data bytes, but a complete good reply follows at once.
  const auto reply = with_crc(hex_bytes("01 03 02 00 01"));
  const auto bytes = join({hex_bytes("01 03 20"), reply});
  const SegmentCut cut = cut_segment(bytes, from_slave());
  EXPECT_EQ(cut.kind, Kind::Noise);
  EXPECT_EQ(cut.length, 3u);
}

TEST(SegmentCut, DamagedAsciiFrameEndsNoiseThanksToItsDelimiters) {
  auto damaged = kAsciiRequest;
  damaged[12] = '0';  // checksum digit
  const auto bytes = join({hex_bytes("7E 7E"), damaged});
  const SegmentCut noise = cut_segment(bytes, from_master());
  EXPECT_EQ(noise.kind, Kind::Noise);
  EXPECT_EQ(noise.length, 2u);
  const SegmentCut frame = cut_segment(std::span(bytes).subspan(2), from_master());
  EXPECT_EQ(frame.kind, Kind::Frame);
  EXPECT_EQ(frame.dialect, Dialect::Ascii);
  EXPECT_FALSE(frame.check.ok);
  EXPECT_EQ(frame.check.expected, 0x01DB);
}

TEST(SegmentCut, OnlyTheAllowedDialectsAreFound) {
  const CutOptions ascii_only{RoleHint::Unknown, DialectSet::only(Dialect::Ascii), false};
  const SegmentCut cut = cut_segment(kGoodRequest, ascii_only);
  EXPECT_EQ(cut.kind, Kind::Noise);
  EXPECT_EQ(cut.length, kGoodRequest.size());
}

TEST(SegmentCut, NoiseTakesItsLastByteAlongInsteadOfWaiting) {
  const SegmentCut cut = cut_segment(hex_bytes("00 07"), from_slave());
  EXPECT_EQ(cut.kind, Kind::Noise);
  EXPECT_EQ(cut.length, 2u);
}

TEST(SegmentCut, NoiseStopsBeforeAFrameThatRunsPastTheEnd) {
  const std::span<const std::uint8_t> request(kGoodRequest);
  const auto bytes = join({hex_bytes("00 00"), {request.begin(), request.begin() + 3}});
  const SegmentCut cut = cut_segment(bytes, from_master());
  EXPECT_EQ(cut.kind, Kind::Noise);
  EXPECT_EQ(cut.length, 2u);
}

TEST(SegmentCut, EmptyBufferIsEmptyNoise) {
  const SegmentCut cut = cut_segment({}, from_master());
  EXPECT_EQ(cut.kind, Kind::Noise);
  EXPECT_EQ(cut.length, 0u);
}

}  // namespace
}  // namespace pvtap
