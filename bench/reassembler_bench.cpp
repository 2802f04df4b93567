// Stream reassembly throughput: a long clean RTU stream and a noisy mixed-dialect stream,
// fed in 64 KiB chunks as an offline audit reads a capture.
#include <benchmark/benchmark.h>

#include <vector>

#include "bus_script.h"
#include "pvtap/stream_reassembler.h"

namespace {

class CountingSink : public pvtap::ReassemblerSink {
 public:
  void on_frame(const pvtap::FrameEvent& e) override { frames += e.check.ok ? 1 : 0; }
  void on_noise(const pvtap::NoiseEvent& e) override { noise += e.bytes.size(); }
  std::uint64_t frames = 0;
  std::uint64_t noise = 0;
};

std::vector<std::uint8_t> make_stream(pvtap::DialectSet dialects, unsigned noise_percent,
                                      unsigned corrupt_percent, std::size_t target) {
  pvtap::test::RandomFrames gen(2026, dialects);
  pvtap::test::ScriptOptions options{1000, noise_percent, corrupt_percent, dialects};
  std::vector<std::uint8_t> stream;
  while (stream.size() < target) {
    const auto part = pvtap::test::concatenate(pvtap::test::make_script(gen, options));
    stream.insert(stream.end(), part.begin(), part.end());
  }
  return stream;
}

void run(benchmark::State& state, const std::vector<std::uint8_t>& stream) {
  constexpr std::size_t kChunk = 64 * 1024;
  std::uint64_t frames = 0;
  for (auto _ : state) {
    CountingSink sink;
    pvtap::StreamReassembler r({}, sink);
    const std::span<const std::uint8_t> all(stream);
    for (std::size_t at = 0; at < all.size(); at += kChunk) {
      const auto piece = all.subspan(at, std::min(kChunk, all.size() - at));
      r.feed(pvtap::BusChunk{piece, 0.0, pvtap::Direction::Unknown});
    }
    r.finish();
    frames = sink.frames;
    benchmark::DoNotOptimize(sink.noise);
  }
  const auto iterations = static_cast<std::uint64_t>(state.iterations());
  state.SetBytesProcessed(static_cast<std::int64_t>(iterations * stream.size()));
  state.counters["frames"] = static_cast<double>(frames);
  state.counters["frames/s"] =
      benchmark::Counter(static_cast<double>(frames * iterations), benchmark::Counter::kIsRate);
}

void BM_ReassembleCleanRtu(benchmark::State& state) {
  static const auto stream = make_stream(
      pvtap::DialectSet::only(pvtap::Dialect::Hybrid).with(pvtap::Dialect::Gsl), 0, 0, 32 << 20);
  run(state, stream);
}
BENCHMARK(BM_ReassembleCleanRtu)->Unit(benchmark::kMillisecond);

void BM_ReassembleNoisyMixed(benchmark::State& state) {
  static const auto stream = make_stream(pvtap::DialectSet::all(), 20, 15, 8 << 20);
  run(state, stream);
}
BENCHMARK(BM_ReassembleNoisyMixed)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
