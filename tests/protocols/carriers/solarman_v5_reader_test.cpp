#include "pvtap/carriers/solarman_v5_reader.h"

#include <gtest/gtest.h>

#include <vector>

#include "hex_bytes.h"
#include "pvtap/carriers/solarman_v5_structure.h"

namespace pvtap::solarman_v5 {
namespace {

using test::hex_bytes;

std::vector<std::uint8_t> request(std::uint16_t sequence) {
  return encode_frame(Header{0, control::kRequest, sequence, 2712345678u},
                      request_payload(hex_bytes("01 03 04 1A 00 02 E4 FC")));
}

std::vector<std::uint8_t> response(std::uint16_t sequence, bool quirk) {
  return encode_frame(Header{0, control::kResponse, sequence, 2712345678u},
                      response_payload(hex_bytes("01 03 04 00 01 00 02 2A 32"), quirk));
}

std::vector<std::uint8_t> heartbeat() {
  return hex_bytes("A5 01 00 10 47 05 01 4E 1C AB A1 00 14 15");
}

std::vector<std::uint8_t> join(std::initializer_list<std::vector<std::uint8_t>> parts) {
  std::vector<std::uint8_t> out;
  for (const auto& p : parts) out.insert(out.end(), p.begin(), p.end());
  return out;
}

// Event: what the tests keep of an event once the reader moved on.
struct Seen {
  Event::Kind kind;
  std::uint64_t offset;
  std::size_t size;
  std::size_t rtu;
  std::size_t quirk;
  bool checksum_ok;
  Broken broken;
};

struct Recorder {
  SolarmanV5Reader reader;
  std::vector<Seen> seen;
  void keep(std::span<const Event> events) {
    for (const Event& e : events) {
      seen.push_back(Seen{e.kind, e.offset, e.bytes.size(), e.frame.rtu_length, e.frame.quirk_bytes,
                          e.frame.checksum_ok(), e.broken});
    }
  }
  void feed(std::span<const std::uint8_t> b) { keep(reader.feed(b)); }
  void finish() { keep(reader.finish()); }
  // Every byte fed is in one count once the stream is finished.
  void expect_accounted() const {
    const Totals& t = reader.totals();
    EXPECT_EQ(reader.pending(), 0u);
    EXPECT_EQ(t.bytes_in,
              t.carrier_bytes + t.rtu_bytes + t.quirk_bytes + t.broken_bytes + t.noise_bytes);
  }
};

TEST(SolarmanV5Reader, FramesSplitAtEveryByteComeOutWhole) {
  const auto stream = join({request(1), response(1, true), heartbeat(), request(2)});
  Recorder r;
  for (std::uint8_t b : stream) r.feed(std::span<const std::uint8_t>(&b, 1));
  r.finish();
  ASSERT_EQ(r.seen.size(), 4u);
  for (const Seen& s : r.seen) EXPECT_EQ(s.kind, Event::Kind::Frame);
  EXPECT_EQ(r.seen[1].offset, request(1).size());
  EXPECT_EQ(r.seen[1].rtu, 9u);
  EXPECT_EQ(r.seen[1].quirk, 2u);
  EXPECT_EQ(r.seen[2].rtu, 0u);
  const Totals& t = r.reader.totals();
  EXPECT_EQ(t.frames, 4u);
  EXPECT_EQ(t.rtu_frames, 3u);
  EXPECT_EQ(t.quirk_bytes, 2u);
  EXPECT_EQ(t.heartbeats, 1u);
  EXPECT_EQ(t.stick_frames, 1u);
  EXPECT_EQ(t.rtu_bytes, 8u + 9u + 8u);
  EXPECT_EQ(t.noise_bytes, 0u);
  r.expect_accounted();
}

TEST(SolarmanV5Reader, TheSticksOwnFramesAreCountedApartFromTheAnswersToThem) {
  const auto answer = encode_frame(Header{0, 0x1710, 0x0105, 2712345678u}, hex_bytes("00"));
  const auto report =
      encode_frame(Header{0, control::kDataReport, 0x0106, 2712345678u}, hex_bytes("01 02 03 04"));
  Recorder r;
  r.feed(join({heartbeat(), answer, report}));
  const Totals& t = r.reader.totals();
  EXPECT_EQ(t.stick_frames, 2u);
  EXPECT_EQ(t.heartbeats, 1u);
  EXPECT_EQ(t.data_reports, 1u);
  EXPECT_EQ(t.stick_answers, 1u);
  EXPECT_EQ(t.rtu_frames, 0u);
  EXPECT_EQ(t.carrier_bytes, t.bytes_in);
}

TEST(SolarmanV5Reader, SeveralFramesInOneSegment) {
  Recorder r;
  r.feed(join({request(1), request(2), request(3)}));
  EXPECT_EQ(r.seen.size(), 3u);
  EXPECT_EQ(r.reader.pending(), 0u);
}

TEST(SolarmanV5Reader, ABadChecksumIsStillAFrameWithItsVerdict) {
  auto bad = request(2);
  bad[bad.size() - 2] ^= 0x01;
  Recorder r;
  r.feed(join({request(1), bad, request(3)}));
  r.finish();
  ASSERT_EQ(r.seen.size(), 3u);
  EXPECT_EQ(r.seen[1].kind, Event::Kind::Frame);
  EXPECT_FALSE(r.seen[1].checksum_ok);
  EXPECT_EQ(r.reader.totals().checksum_failures, 1u);
  r.expect_accounted();
}

TEST(SolarmanV5Reader, ATruncatedFrameIsFoundAndTheNextFrameRead) {
  const auto cut = request(2);
  const std::vector<std::uint8_t> first(cut.begin(), cut.begin() + 20);
  Recorder r;
  r.feed(join({request(1), first, request(3), response(3, false)}));
  r.finish();
  ASSERT_EQ(r.seen.size(), 4u);
  EXPECT_EQ(r.seen[1].kind, Event::Kind::Broken);
  EXPECT_EQ(r.seen[1].size, 20u);
  EXPECT_EQ(r.seen[2].kind, Event::Kind::Frame);
  EXPECT_EQ(r.seen[2].offset, request(1).size() + 20);
  EXPECT_EQ(r.reader.totals().broken_bytes, 20u);
  EXPECT_EQ(r.reader.totals().noise_bytes, 0u);
  r.expect_accounted();
}

TEST(SolarmanV5Reader, AFrameCutByTheEndOfTheStreamIsTruncated) {
  const auto whole = request(1);
  Recorder r;
  r.feed(std::span<const std::uint8_t>(whole).first(30));
  EXPECT_TRUE(r.seen.empty());
  r.finish();
  ASSERT_EQ(r.seen.size(), 1u);
  EXPECT_EQ(r.seen[0].kind, Event::Kind::Broken);
  EXPECT_EQ(r.seen[0].broken, Broken::Truncated);
  EXPECT_EQ(r.reader.totals().truncated, 1u);
  r.expect_accounted();
}

TEST(SolarmanV5Reader, ALengthThatOverrunsIsAFindingWithItsBytes) {
  auto lying = request(2);
  lying[1] = 0x40;  // claims 64 payload bytes; the frame has 23
  Recorder r;
  r.feed(join({lying, request(3), request(4), request(5)}));
  r.finish();
  ASSERT_GE(r.seen.size(), 1u);
  EXPECT_EQ(r.seen[0].kind, Event::Kind::Broken);
  EXPECT_EQ(r.seen[0].broken, Broken::LengthMismatch);
  EXPECT_EQ(r.seen[0].size, lying.size());
  EXPECT_EQ(r.seen.size(), 4u);
  EXPECT_EQ(r.reader.totals().length_mismatches, 1u);
  r.expect_accounted();
}

TEST(SolarmanV5Reader, OtherBytesAreNoiseAndAStrayStartByteResyncs) {
  Recorder r;
  r.feed(join({hex_bytes("48 54 54 50 A5 20 31"), request(1)}));
  r.finish();
  ASSERT_EQ(r.seen.size(), 3u);
  EXPECT_EQ(r.seen[0].kind, Event::Kind::Noise);
  EXPECT_EQ(r.seen[1].kind, Event::Kind::Noise);
  EXPECT_EQ(r.seen[2].kind, Event::Kind::Frame);
  EXPECT_EQ(r.reader.totals().noise_bytes, 7u);
  r.expect_accounted();
}

TEST(SolarmanV5Reader, ADiscontinuityDecidesThePendingBytes) {
  const auto whole = request(1);
  Recorder r;
  r.feed(std::span<const std::uint8_t>(whole).first(12));
  r.keep(r.reader.discontinuity());
  r.feed(request(2));
  ASSERT_EQ(r.seen.size(), 2u);
  EXPECT_EQ(r.seen[0].kind, Event::Kind::Broken);
  EXPECT_EQ(r.seen[1].kind, Event::Kind::Frame);
}

TEST(SolarmanV5Structure, RecognizesAWholeFirstFrameOnly) {
  const auto frame = request(1);
  EXPECT_EQ(recognize(frame), Recognition::Yes);
  EXPECT_EQ(recognize(std::span<const std::uint8_t>(frame).first(20)), Recognition::NeedMore);
  auto bad = frame;
  bad[bad.size() - 2] ^= 0x01;
  EXPECT_EQ(recognize(bad), Recognition::No);
  // A Modbus/TCP request: transaction id 0xA5.. would start like V5; its protocol id and
  // length make no V5 frame.
  EXPECT_EQ(recognize(hex_bytes("A5 01 00 00 00 06 01 03 00 00 00 0A")), Recognition::No);
  EXPECT_EQ(recognize(hex_bytes("01 03 00 00 00 0A C5 CD")), Recognition::No);
}

}  // namespace
}  // namespace pvtap::solarman_v5
