// What a dissector shows of each call's bytes (SegmentedBus), and the property that, for any
// byte stream and any split into segments, it cuts exactly as the stream reassembler does.
#include "pvtap/session/segmented_bus.h"

#include <gtest/gtest.h>

#include "bus_script.h"
#include "hex_bytes.h"
#include "pvtap/codec/checksums.h"
#include "pvtap/registers/register_decoder.h"

namespace pvtap {
namespace {

using test::hex_bytes;

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

// The options the plugin gives a gateway conversation (bus_track.cpp).
BusSessionOptions gateway_options(DialectSet dialects = DialectSet::all()) {
  BusSessionOptions o;
  o.reassembler.dialects = dialects;
  o.reassembler.timestamps = TimestampTrust::Untrusted;
  o.reassembler.boundary_gap = 0.05;
  o.reassembler.segment_ends_pin = true;
  o.decode_values = false;
  return o;
}

// Piece: a frame or noise run as the dissector would show it.
struct Piece {
  std::uint64_t offset;
  std::size_t length;
  bool frame;
  bool ok;
  bool operator==(const Piece&) const = default;
};

class Shown : public BusSessionSink {
 public:
  explicit Shown(BusSessionOptions o = gateway_options()) : bus(o, decoder, *this) {}
  void on_frame(const SessionFrame& f) override { checks[f.id] = f.check.ok; }

  // One call, as Wireshark's TCP hands it over; returns the pieces it shows.
  std::vector<Piece> call(Direction d, std::uint64_t from, const std::vector<std::uint8_t>& bytes,
                          double time = 0.0, bool can_wait = true) {
    last = bus.show(d, from, bytes, time, can_wait);
    std::vector<Piece> out;
    for (const BusPiece& p : bus.pieces(d, last.from, last.shown_to)) {
      out.push_back({p.offset, p.length, p.frame, p.frame && checks[p.frame_id]});
    }
    return out;
  }

  RegisterDecoder decoder;
  SegmentedBus bus;
  SegmentedBus::CallSpan last;
  std::map<std::uint64_t, bool> checks;
};

constexpr Direction kMaster = Direction::ToSlave;
constexpr Direction kSlave = Direction::FromSlave;

TEST(SegmentedBus, GoodFrameIsShownAtOnceAndWhatFollowsWaits) {
  Shown s;
  const auto pieces = s.call(kMaster, 0, join({kGoodRequest, hex_bytes("01")}));
  ASSERT_EQ(pieces, (std::vector<Piece>{{0, 8, true, true}}));
  EXPECT_EQ(s.last.shown_to, 8u) << "the byte after it may start the next request";
}

TEST(SegmentedBus, AFrameSplitOverSegmentsIsShownWhenItsLastPieceCame) {
  Shown s;
  const std::span<const std::uint8_t> request(kGoodRequest);
  EXPECT_TRUE(s.call(kMaster, 0, {request.begin(), request.begin() + 6}).empty());
  EXPECT_EQ(s.last.shown_to, 0u);
  // TCP hands the held-back bytes again with the next segment.
  const auto pieces = s.call(kMaster, 0, kGoodRequest);
  EXPECT_EQ(pieces, (std::vector<Piece>{{0, 8, true, true}}));
}

TEST(SegmentedBus, ACallSaysHowMuchOfItWasHandedBefore) {
  Shown s;
  const std::span<const std::uint8_t> request(kGoodRequest);
  s.call(kMaster, 0, {request.begin(), request.begin() + 6});
  EXPECT_EQ(s.last.handed_to, 0u) << "nothing was handed before the first call";
  s.call(kMaster, 0, kGoodRequest);
  EXPECT_EQ(s.last.handed_to, 6u) << "the six bytes held back came again";
  s.call(kMaster, 8, kGoodRequest);
  EXPECT_EQ(s.last.handed_to, 8u) << "a call after the bytes handed so far: none handed again";
}

TEST(SegmentedBus, TruncatedFrameIsNoiseWhenNothingMoreCanCome) {
  Shown s;
  const std::span<const std::uint8_t> request(kGoodRequest);
  const auto pieces = s.call(kMaster, 0, {request.begin(), request.begin() + 6}, 0.0, false);
  EXPECT_EQ(pieces, (std::vector<Piece>{{0, 6, false, false}}));
}

TEST(SegmentedBus, NoiseEndsWhereAFrameStarts) {
  Shown s;
  const auto pieces = s.call(kMaster, 0, join({hex_bytes("00 07 00"), kGoodRequest}));
  EXPECT_EQ(pieces, (std::vector<Piece>{{0, 3, false, false}, {3, 8, true, true}}));
}

TEST(SegmentedBus, BadFrameThatEndsTheSegmentIsShownWithIt) {
  Shown s;
  s.call(kSlave, 0, kGoodDeviceReply);
  const auto pieces = s.call(kSlave, kGoodDeviceReply.size(), kBadEcho);
  EXPECT_EQ(pieces, (std::vector<Piece>{{kGoodDeviceReply.size(), kBadEcho.size(), true, false}}));
}

TEST(SegmentedBus, BadFrameFollowedByAGoodFrameIsAFrame) {
  Shown s;
  const auto pieces = s.call(kSlave, 0, join({kBadEcho, kGoodDeviceReply}));
  EXPECT_EQ(pieces, (std::vector<Piece>{{0, 13, true, false}, {13, 13, true, true}}));
}

TEST(SegmentedBus, BadReadingWithAGoodFrameInsideIsNoise) {
  Shown s;
  s.call(kMaster, 0, kGoodRequest);
  // "09 06" reads as a GSL write whose 8 bytes would swallow the good request after it.
  const auto pieces = s.call(kMaster, 8, join({hex_bytes("09 06"), kGoodRequest}));
  EXPECT_EQ(pieces, (std::vector<Piece>{{8, 2, false, false}, {10, 8, true, true}}));
}

// Changed from the old cut_segment, which called a pending reading noise as soon as a good
// frame started inside it: a long reply's data holds a chance good CRC often enough (about
// one 200-byte reply in 160) that this would cut real replies. The reading waits until its
// bytes have come, as in pvtap audit; then the good frame inside it shows it was noise.
TEST(SegmentedBus, PendingReadingIsNoiseOnceAGoodFrameInsideItIsComplete) {
  Shown s;
  s.call(kSlave, 0, kGoodDeviceReply);
  // "01 03 20" announces 32 data bytes, but a complete good reply follows at once.
  const auto reply = with_crc(hex_bytes("01 03 02 00 01"));
  const auto first = join({hex_bytes("01 03 20"), reply});
  EXPECT_TRUE(s.call(kSlave, 13, first).empty());
  const auto rest = join({first, kGoodDeviceReply, kGoodDeviceReply, kGoodDeviceReply});
  const auto pieces = s.call(kSlave, 13, rest);
  ASSERT_GE(pieces.size(), 2u);
  EXPECT_EQ(pieces[0], (Piece{13, 3, false, false}));
  EXPECT_EQ(pieces[1], (Piece{16, 7, true, true}));
}

TEST(SegmentedBus, DamagedAsciiFrameEndsNoiseThanksToItsDelimiters) {
  Shown s;
  auto damaged = kAsciiRequest;
  damaged[12] = '0';  // checksum digit
  const auto pieces = s.call(kMaster, 0, join({hex_bytes("7E 7E"), damaged}));
  EXPECT_EQ(pieces, (std::vector<Piece>{{0, 2, false, false}, {2, 15, true, false}}));
}

TEST(SegmentedBus, OnlyTheAllowedDialectsAreFound) {
  Shown s(gateway_options(DialectSet::only(Dialect::Ascii)));
  const auto pieces = s.call(kMaster, 0, kGoodRequest, 0.0, false);
  EXPECT_EQ(pieces, (std::vector<Piece>{{0, 8, false, false}}));
}

// Changed from the old cut_segment, which took a lone last byte into the noise: a byte that
// may start a frame waits for the next segment, as in pvtap audit.
TEST(SegmentedBus, ALastByteThatMayStartAFrameWaitsForTheNextSegment) {
  Shown s;
  s.call(kSlave, 0, kGoodDeviceReply);
  EXPECT_TRUE(s.call(kSlave, 13, hex_bytes("00 07")).empty());
  EXPECT_EQ(s.last.shown_to, 13u);
}

// Two damaged requests in a row, a second of silence apart while the master waits: no good
// frame pins the first one's end, the silence between the segments does.
TEST(SegmentedBus, ASilenceLongerThanTheGatewayGapPinsADamagedFrame) {
  BusSessionOptions o = gateway_options();
  o.reassembler.segment_ends_pin = false;  // the gap alone
  Shown s(o);
  s.call(kMaster, 0, kGoodRequest, 1.0);
  auto damaged = kGoodRequest;
  damaged[4] = 0x06;  // the count's high byte: 0x060A registers
  EXPECT_TRUE(s.call(kMaster, 8, damaged, 1.5).empty());
  auto again = kGoodRequest;
  again[5] = 0x0B;  // the retry, damaged in its low byte
  const auto pieces = s.call(kMaster, 8, join({damaged, again}), 2.5);
  EXPECT_EQ(pieces, (std::vector<Piece>{{8, 8, true, false}}));
  // 30 ms apart (less than the gap), nothing is proven: the retry still waits.
  EXPECT_EQ(s.last.shown_to, 16u);
  Shown close(o);
  close.call(kMaster, 0, kGoodRequest, 1.0);
  close.call(kMaster, 8, damaged, 1.5);
  EXPECT_TRUE(close.call(kMaster, 8, join({damaged, again}), 1.5 + 0.030).empty());
}

TEST(SegmentedBus, LostBytesBreakTheStream) {
  Shown s;
  s.call(kMaster, 0, kGoodRequest);
  const std::span<const std::uint8_t> request(kGoodRequest);
  EXPECT_TRUE(s.call(kMaster, 8, {request.begin(), request.begin() + 4}).empty());
  // Four bytes never arrive; the next segment starts after them.
  const auto pieces = s.call(kMaster, 16, kGoodRequest);
  ASSERT_EQ(pieces.size(), 1u);
  EXPECT_EQ(pieces[0], (Piece{16, 8, true, true}));
  const auto before = s.bus.pieces(kMaster, 8, 16);
  ASSERT_EQ(before.size(), 1u);
  EXPECT_FALSE(before[0].frame) << "the bytes before the loss are noise, not a frame";
}

// The property: for any byte stream and any split into segments, what the dissector shows,
// call by call as TCP hands the held-back bytes over again, is exactly what the stream
// reassembler reports for the same segments; and, with segment ends proving nothing, for the
// stream in one piece.
class ReassemblerEvents : public ReassemblerSink {
 public:
  void on_frame(const FrameEvent& e) override {
    pieces.push_back({e.offset, e.bytes.size(), true, e.check.ok});
  }
  void on_noise(const NoiseEvent& e) override {
    pieces.push_back({e.offset, e.bytes.size(), false, false});
  }
  std::vector<Piece> pieces;
};

std::vector<std::size_t> random_cuts(test::RandomFrames& gen, std::size_t size) {
  std::vector<std::size_t> cuts;
  for (std::size_t at = 0; at < size;) {
    at += gen.pick(1, 40);
    cuts.push_back(at < size ? at : size);
  }
  return cuts;
}

// The dissector: each call is the held-back tail plus the next segment; the last call may not
// wait (the connection closed). Returns every piece shown, in order.
std::vector<Piece> dissector_cuts(const std::vector<std::uint8_t>& stream,
                                  const std::vector<std::size_t>& cuts, BusSessionOptions o) {
  Shown s(o);
  std::vector<Piece> shown;
  std::uint64_t from = 0;
  for (std::size_t i = 0; i < cuts.size(); ++i) {
    const std::vector<std::uint8_t> tvb(stream.begin() + static_cast<std::ptrdiff_t>(from),
                                        stream.begin() + static_cast<std::ptrdiff_t>(cuts[i]));
    const bool last = i + 1 == cuts.size();
    for (const Piece& p : s.call(kSlave, from, tvb, 0.0, !last)) shown.push_back(p);
    from = s.last.shown_to;
  }
  return shown;
}

std::vector<Piece> reassembler_events(const std::vector<std::uint8_t>& stream,
                                      const std::vector<std::size_t>& cuts, ReassemblerOptions o) {
  ReassemblerEvents sink;
  StreamReassembler r(o, sink);
  std::size_t at = 0;
  for (std::size_t cut : cuts) {
    r.feed(BusChunk{std::span(stream).subspan(at, cut - at), 0.0, Direction::FromSlave});
    at = cut;
  }
  r.finish();
  return sink.pieces;
}

void check_property(DialectSet dialects, std::uint32_t first_seed, std::uint32_t cases) {
  std::size_t frames = 0;
  for (std::uint32_t seed = first_seed; seed < first_seed + cases; ++seed) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    test::RandomFrames gen(seed, dialects);
    const auto stream = test::concatenate(test::make_script(gen, {20, 20, 15, dialects}));
    const auto cuts = random_cuts(gen, stream.size());
    BusSessionOptions o = gateway_options(dialects);
    const auto shown = dissector_cuts(stream, cuts, o);
    ASSERT_EQ(shown, reassembler_events(stream, cuts, o.reassembler)) << "same segments";
    o.reassembler.segment_ends_pin = false;
    ASSERT_EQ(dissector_cuts(stream, cuts, o),
              reassembler_events(stream, {stream.size()}, o.reassembler))
        << "any split, against the stream in one piece";
    for (const Piece& p : shown) frames += p.frame;
  }
  EXPECT_GT(frames, std::size_t{cases} * 5) << "the streams must hold frames";
}

TEST(SegmentedBusProperty, DissectorCutsAreTheReassemblersEventsAllDialects) {
  check_property(DialectSet::all(), 1, 1500);
}

TEST(SegmentedBusProperty, DissectorCutsAreTheReassemblersEventsEachDialect) {
  check_property(DialectSet::only(Dialect::Ascii), 3000, 500);
  check_property(DialectSet::only(Dialect::Hybrid), 4000, 500);
  check_property(DialectSet::only(Dialect::Gsl), 5000, 500);
}

}  // namespace
}  // namespace pvtap
