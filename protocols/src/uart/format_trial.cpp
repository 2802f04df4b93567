// try_format: decode a stretch, frame its characters with the core's reassembler, count.
#include "pvtap/uart/format_trial.h"

#include <algorithm>
#include <bitset>
#include <vector>

#include "pvtap/framing/stream_reassembler.h"

namespace pvtap {
namespace {

class GoodFrameCount final : public ReassemblerSink {
 public:
  // `errors`: per byte fed, whether its character had a line error.
  explicit GoodFrameCount(const std::vector<bool>& errors) : errors_(errors) {}

  void on_frame(const FrameEvent& frame) override {
    if (!frame.check.ok) return;
    ++count;
    if (frame.role == Role::Request) {
      ++requests;
    } else {
      ++responses;
    }
    const std::uint64_t end =
        std::min<std::uint64_t>(frame.offset + frame.bytes.size(), errors_.size());
    for (std::uint64_t i = frame.offset; i < end; ++i) line_errors += errors_[i] ? 1u : 0u;
  }
  void on_noise(const NoiseEvent&) override {}
  std::uint64_t count = 0, requests = 0, responses = 0, line_errors = 0;

 private:
  const std::vector<bool>& errors_;
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
  std::vector<bool> errors;
  errors.reserve(chars.size());
  GoodFrameCount frames(errors);
  StreamReassembler reassembler(options, frames);
  std::bitset<256> seen;
  for (const UartCharacter& c : chars) {
    if (c.is_break) continue;
    ++trial.characters;
    const bool error = c.framing_error || c.parity_error;
    trial.line_errors += error ? 1 : 0;
    errors.push_back(error);
    const auto byte = static_cast<std::uint8_t>(c.value);
    seen.set(byte);
    reassembler.feed(BusChunk{std::span(&byte, 1), static_cast<double>(c.end) / line.sample_rate,
                              Direction::Unknown});
  }
  reassembler.finish();
  trial.good_frames = frames.count;
  trial.requests = frames.requests;
  trial.responses = frames.responses;
  trial.frame_line_errors = frames.line_errors;
  trial.distinct_values = static_cast<unsigned>(seen.count());
  return trial;
}

}  // namespace pvtap
