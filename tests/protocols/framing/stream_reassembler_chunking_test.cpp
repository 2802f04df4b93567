// Chunking does not change what the reassembler finds: the same noisy stream of all dialects,
// fed whole, in large chunks (decided in place after a pending tail) and in small ones
// (buffered), gives the same frames and noise runs at the same offsets.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "bus_script.h"
#include "pvtap/framing/stream_reassembler.h"

namespace pvtap {
namespace {

// Records every event as one line of text: kind, offset, bytes, and for frames the reading.
class RecordingSink : public ReassemblerSink {
 public:
  void on_frame(const FrameEvent& e) override {
    events.push_back("frame " + std::to_string(e.offset) + " " + hex(e.bytes) + " " +
                     std::to_string(static_cast<int>(e.dialect)) + " " +
                     std::to_string(static_cast<int>(e.role)) + (e.check.ok ? " ok" : " bad"));
  }
  void on_noise(const NoiseEvent& e) override {
    events.push_back("noise " + std::to_string(e.offset) + " " + hex(e.bytes));
  }
  std::vector<std::string> events;

 private:
  static std::string hex(std::span<const std::uint8_t> bytes) {
    static constexpr char kDigits[] = "0123456789abcdef";
    std::string s;
    for (const std::uint8_t b : bytes) {
      s += kDigits[b >> 4];
      s += kDigits[b & 0xF];
    }
    return s;
  }
};

std::vector<std::uint8_t> noisy_stream(std::size_t target) {
  test::RandomFrames gen(77, DialectSet::all());
  test::ScriptOptions options{400, 20, 15, DialectSet::all()};
  std::vector<std::uint8_t> stream;
  while (stream.size() < target) {
    const auto part = test::concatenate(test::make_script(gen, options));
    stream.insert(stream.end(), part.begin(), part.end());
  }
  return stream;
}

// Feeds the stream in chunks whose sizes repeat `sizes`.
std::vector<std::string> events_of(const std::vector<std::uint8_t>& stream,
                                   const std::vector<std::size_t>& sizes) {
  RecordingSink sink;
  StreamReassembler r({}, sink);
  const std::span<const std::uint8_t> all(stream);
  std::size_t at = 0;
  for (std::size_t i = 0; at < all.size(); ++i) {
    const std::size_t n = std::min(sizes[i % sizes.size()], all.size() - at);
    r.feed(BusChunk{all.subspan(at, n), 0.0, Direction::Unknown});
    at += n;
  }
  r.finish();
  EXPECT_EQ(r.totals().bytes_in, stream.size());
  EXPECT_EQ(r.totals().frame_bytes + r.totals().noise_bytes, stream.size());
  return sink.events;
}

TEST(StreamReassemblerChunking, SameEventsWhateverTheChunkSizes) {
  const auto stream = noisy_stream(600 * 1024);
  const auto whole = events_of(stream, {stream.size()});
  ASSERT_GT(whole.size(), 1000u);
  EXPECT_EQ(events_of(stream, {64 * 1024}), whole);
  EXPECT_EQ(events_of(stream, {3001, 2069, 2070, 9000}), whole);
  EXPECT_EQ(events_of(stream, {1, 7, 64, 300, 5, 2}), whole);
  // A byte at a time: each decision at a pinned start goes on with the repair scan where the
  // previous one waited (frame_decision.h, RepairScan).
  EXPECT_EQ(events_of(stream, {1}), whole);
}

// A real bus: a Huawei inverter polling a battery and a meter, logged by others (../shared/real,
// raw/: 999 whole frames and 10,733 bytes their sniffer skipped while resynchronising). Its
// noise puts many starts after a frame that no reading fits, so the repair scan waits and goes
// on with every read.
TEST(StreamReassemblerChunking, ARealBusGivesTheSameEventsWhateverTheReads) {
  const std::string path =
      std::string(PVTAP_REAL_RECORDINGS) + "/raw/huawei_sun2000_luna_dtsu_9600_8N1.bin";
  std::ifstream in(path, std::ios::binary);
  if (!in) GTEST_SKIP() << path << " is missing";
  const std::vector<std::uint8_t> stream{std::istreambuf_iterator<char>(in),
                                         std::istreambuf_iterator<char>()};
  const auto whole = events_of(stream, {stream.size()});
  ASSERT_GT(whole.size(), 999u);
  EXPECT_EQ(events_of(stream, {1}), whole);
  EXPECT_EQ(events_of(stream, {8}), whole);
  EXPECT_EQ(events_of(stream, {1, 7, 64, 300, 5, 2}), whole);
}

}  // namespace
}  // namespace pvtap
