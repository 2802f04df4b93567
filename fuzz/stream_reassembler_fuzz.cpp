// Fuzz target stream_reassembler: the framing decision, through StreamReassembler, on a stream
// cut into chunks at fuzzer-chosen points with fuzzer-chosen timestamps and directions.
// Asserts the byte accounting of ReassemblerTotals after every step, that events cover the
// stream in order without gap or overlap, and that no frame is longer than its dialect allows.
#include <cstddef>
#include <cstdint>

#include "chunk_script.h"
#include "fuzz_input.h"
#include "pvtap/framing/stream_reassembler.h"

namespace {

using pvtap::fuzz::ChunkScript;
using pvtap::fuzz::ScriptStep;
using pvtap::fuzz::StepKind;

// CountingSink: adds up what the reassembler reports and checks each event as it comes.
class CountingSink : public pvtap::ReassemblerSink {
 public:
  explicit CountingSink(pvtap::DialectSet dialects) : dialects_(dialects) {}

  void on_frame(const pvtap::FrameEvent& f) override {
    PVTAP_FUZZ_CHECK(!f.bytes.empty());
    PVTAP_FUZZ_CHECK(dialects_.contains(f.dialect));
    PVTAP_FUZZ_CHECK(f.bytes.size() <= pvtap::fuzz::max_frame_length(f.dialect));
    advance(f.offset, f.bytes.size());
    frame_bytes += f.bytes.size();
    ++frames;
    if (!f.check.ok) ++bad_frames;
  }
  void on_noise(const pvtap::NoiseEvent& n) override {
    PVTAP_FUZZ_CHECK(!n.bytes.empty());
    advance(n.offset, n.bytes.size());
    noise_bytes += n.bytes.size();
  }

  std::uint64_t frame_bytes = 0;
  std::uint64_t noise_bytes = 0;
  std::uint64_t frames = 0;
  std::uint64_t bad_frames = 0;

 private:
  void advance(std::uint64_t offset, std::size_t length) {
    PVTAP_FUZZ_CHECK(offset == position_);
    position_ += length;
  }

  pvtap::DialectSet dialects_;
  std::uint64_t position_ = 0;
};

void check_accounting(const pvtap::StreamReassembler& r, const CountingSink& sink,
                      std::uint64_t fed) {
  const auto& t = r.totals();
  PVTAP_FUZZ_CHECK(t.bytes_in == fed);
  PVTAP_FUZZ_CHECK(t.bytes_in == t.frame_bytes + t.noise_bytes + r.pending_bytes());
  PVTAP_FUZZ_CHECK(t.frame_bytes == sink.frame_bytes);
  PVTAP_FUZZ_CHECK(t.noise_bytes == sink.noise_bytes);
  PVTAP_FUZZ_CHECK(t.frames == sink.frames);
  PVTAP_FUZZ_CHECK(t.bad_frames == sink.bad_frames);
  // Memory is bounded. The reassembler gives undecided bytes up as noise in runs of at most
  // 4 KiB (kMaxNoiseRun in stream_reassembler.cpp), so that much may wait besides one frame:
  // with untrusted timestamps 2,417 bytes were seen waiting with no event at all
  // (tests/corpus/stream_reassembler/pending-2417-undecided), more than the longest frame.
  constexpr std::size_t kMaxNoiseRun = 4096;
  PVTAP_FUZZ_CHECK(r.pending_bytes() <= kMaxNoiseRun + 2 * pvtap::kMaxFrameLength);
}

void apply(pvtap::StreamReassembler& r, const ScriptStep& step, std::uint64_t& fed) {
  switch (step.kind) {
    case StepKind::Chunk:
      r.feed(step.chunk);
      fed += step.chunk.bytes.size();
      break;
    case StepKind::Idle:
      r.idle(step.chunk.time);
      break;
    case StepKind::Discontinuity:
    case StepKind::DataLost:
      r.discontinuity();
      break;
    case StepKind::EndTurn:
      break;
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  pvtap::fuzz::FuzzInput in(data, size);
  const auto o = pvtap::fuzz::read_script_options(in);
  pvtap::ReassemblerOptions options;
  options.dialects = o.dialects;
  options.baud = o.baud;
  options.timestamps = o.trust;
  CountingSink sink(o.dialects);
  pvtap::StreamReassembler reassembler(options, sink);
  ChunkScript script(in);
  ScriptStep step;
  std::uint64_t fed = 0;
  while (script.next(step)) {
    apply(reassembler, step, fed);
    check_accounting(reassembler, sink, fed);
  }
  reassembler.finish();
  check_accounting(reassembler, sink, fed);
  PVTAP_FUZZ_CHECK(reassembler.pending_bytes() == 0);
  return 0;
}
