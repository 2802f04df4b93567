// try_format: decode a stretch, frame its characters with the core's reassembler, count.
#include "pvtap/uart/format_trial.h"

#include <bitset>
#include <vector>

#include "pvtap/framing/stream_reassembler.h"

namespace pvtap {
namespace {

class GoodFrameCount final : public ReassemblerSink {
 public:
  void on_frame(const FrameEvent& frame) override {
    if (!frame.check.ok) return;
    ++count;
    if (frame.role == Role::Request) {
      ++requests;
    } else {
      ++responses;
    }
  }
  void on_noise(const NoiseEvent&) override {}
  std::uint64_t count = 0, requests = 0, responses = 0;
};

}  // namespace

FormatTrial try_format(const UartLine& line, std::span<const SampleRun> runs, DialectSet dialects) {
  FormatTrial trial;
  trial.format = line.format;
  UartDecoder decoder(line);
  std::vector<UartCharacter> chars;
  for (const SampleRun& r : runs) decoder.feed(r, chars);
  decoder.finish(chars);

  ReassemblerOptions options;
  options.dialects = dialects;
  options.baud = static_cast<std::uint32_t>(line.baud);
  options.bits_per_char = line.format.bits_per_char();
  options.timestamps = TimestampTrust::Trusted;
  GoodFrameCount frames;
  StreamReassembler reassembler(options, frames);
  std::bitset<256> seen;
  for (const UartCharacter& c : chars) {
    if (c.is_break) continue;
    ++trial.characters;
    trial.line_errors += (c.framing_error || c.parity_error) ? 1 : 0;
    const auto byte = static_cast<std::uint8_t>(c.value);
    seen.set(byte);
    reassembler.feed(BusChunk{std::span(&byte, 1), static_cast<double>(c.end) / line.sample_rate,
                              Direction::Unknown});
  }
  reassembler.finish();
  trial.good_frames = frames.count;
  trial.requests = frames.requests;
  trial.responses = frames.responses;
  trial.distinct_values = static_cast<unsigned>(seen.count());
  return trial;
}

}  // namespace pvtap
