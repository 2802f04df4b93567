// USB-chunked serial captures: one read can hold the last bytes of a reply, the silence after
// it and the first bytes of the next request, stamped only when the read returned.
#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "bus_script.h"
#include "hex_bytes.h"
#include "pvtap/codec/checksums.h"
#include "pvtap/framing/stream_reassembler.h"

namespace pvtap {
namespace {

using test::hex_bytes;

// A GSL reply to a read of 23 registers (51 bytes) with one data byte damaged: its header
// and byte count still say where it ends.
std::vector<std::uint8_t> damaged_reply() {
  std::vector<std::uint8_t> reply{0x01, 0x03, 46};
  for (unsigned i = 0; i < 46; ++i) reply.push_back(static_cast<std::uint8_t>(i % 2 ? i : 1));
  const std::uint16_t crc = Crc16Modbus::compute(reply);
  reply.push_back(static_cast<std::uint8_t>(crc & 0xFF));
  reply.push_back(static_cast<std::uint8_t>(crc >> 8));
  reply[20] ^= 0x10;
  return reply;
}

const auto kRequest = hex_bytes("01 03 04 1A 00 17 25 33");      // 23 registers from 1050
const auto kNextRequest = hex_bytes("02 03 04 1A 00 04 64 CD");  // the next station's poll

// Bytes 0-7 the request, 8-58 the damaged reply, 59-66 the next request.
std::vector<std::uint8_t> request_reply_request() {
  std::vector<std::uint8_t> stream = kRequest;
  const auto reply = damaged_reply();
  stream.insert(stream.end(), reply.begin(), reply.end());
  stream.insert(stream.end(), kNextRequest.begin(), kNextRequest.end());
  return stream;
}

// As pvtap audit reads a USER0 capture of a serial adapter: batched stamps, the adapter's
// default boundary gap.
ReassemblerOptions usb_capture() {
  ReassemblerOptions o;
  o.timestamps = TimestampTrust::Untrusted;
  return o;
}

struct Read {
  std::size_t from, to;  // bytes of the stream
  double time;           // when the sniffer's read returned
};

std::vector<test::CapturedEvent> reassembled(const std::vector<std::uint8_t>& stream,
                                             const std::vector<Read>& reads) {
  test::CapturingSink sink;
  StreamReassembler r(usb_capture(), sink);
  const std::span<const std::uint8_t> all(stream);
  for (const Read& read : reads) {
    r.feed(BusChunk{all.subspan(read.from, read.to - read.from), read.time, Direction::Unknown});
  }
  r.finish();
  return sink.events;
}

// Request, damaged reply, and 11 ms after it the next request. The adapter hands the reply
// over in 16 ms pieces; the piece that holds the reply's last 3 bytes, the 11 ms silence and
// the next request's first 3 bytes is read 9 ms late. Counted back from that stamp as if its
// 6 bytes had been sent back to back, the piece seems to follow a silence longer than the
// boundary gap: a silence the stamps place before the piece, that is inside the reply, though
// it may lie anywhere up to the piece's last byte (here after the reply).
TEST(StreamReassemblerUsbReads, ASilenceReadTogetherWithTheNextRequestDoesNotCutTheReply) {
  const auto stream = request_reply_request();
  const auto events = reassembled(
      stream,
      {{0, 8, 0.02623}, {8, 32, 0.05710}, {32, 56, 0.08122}, {56, 62, 0.10739}, {62, 67, 0.13000}});
  ASSERT_EQ(events.size(), 3u);
  for (const auto& e : events) EXPECT_TRUE(e.is_frame);
  EXPECT_EQ(events[0].bytes, kRequest);
  EXPECT_EQ(events[1].bytes, damaged_reply());
  EXPECT_FALSE(events[1].frame.check.ok);
  EXPECT_EQ(events[1].frame.role, Role::Response);
  EXPECT_EQ(events[2].bytes, kNextRequest);
}

// The reply's last byte handed over alone and read 7 ms late, the next request in the read
// after it: that byte seems to follow a silence longer than the boundary gap.
TEST(StreamReassemblerUsbReads, ALateReadOfTheReplysLastByteDoesNotCutTheReply) {
  const auto stream = request_reply_request();
  const auto events = reassembled(
      stream,
      {{0, 8, 0.02623}, {8, 32, 0.05710}, {32, 58, 0.08418}, {58, 59, 0.10862}, {59, 67, 0.11330}});
  ASSERT_EQ(events.size(), 3u);
  EXPECT_TRUE(events[1].is_frame);
  EXPECT_EQ(events[1].bytes, damaged_reply());
  EXPECT_FALSE(events[1].frame.check.ok);
}

// Where only timing pins the reading's end (a long silence, then noise), a silence that the
// timestamps prove inside it still rules it out, batched or not.
TEST(StreamReassemblerUsbReads, WhereOnlyTimingPinsItsEndASilenceInsideStillRulesTheReadingOut) {
  auto stream = request_reply_request();
  stream.resize(59);  // the request and the reply
  stream.insert(stream.end(), {0xFF, 0xFF, 0xFF});
  const auto events = reassembled(
      stream,
      {{0, 8, 0.02623}, {8, 32, 0.05710}, {32, 56, 0.12122}, {56, 59, 0.12436}, {59, 62, 0.30000}});
  ASSERT_FALSE(events.empty());
  EXPECT_TRUE(std::none_of(events.begin(), events.end(), [](const test::CapturedEvent& e) {
    return e.is_frame && e.bytes.size() == 51;
  }));
  // The same reads with no silence inside the reply: the silence after it pins its end.
  const auto whole = reassembled(
      stream,
      {{0, 8, 0.02623}, {8, 32, 0.05710}, {32, 56, 0.08210}, {56, 59, 0.08524}, {59, 62, 0.30000}});
  ASSERT_EQ(whole.size(), 3u);
  EXPECT_EQ(whole[1].bytes, damaged_reply());
  EXPECT_FALSE(whole[2].is_frame);
}

}  // namespace
}  // namespace pvtap
