// Stream reassembly throughput, fed in 64 KiB chunks as an offline audit reads a capture:
// random RTU frames of every kind (many of them 8 bytes), a logger's real polling cycle, and a
// noisy stream of all dialects, also in the 8-byte reads of a serial adapter on a slow line.
#include <benchmark/benchmark.h>

#include <vector>

#include "bus_script.h"
#include "pvtap/framing/stream_reassembler.h"

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

void run(benchmark::State& state, const std::vector<std::uint8_t>& stream,
         std::size_t chunk = 64 * 1024) {
  std::uint64_t frames = 0;
  for (auto _ : state) {
    CountingSink sink;
    pvtap::StreamReassembler r({}, sink);
    const std::span<const std::uint8_t> all(stream);
    for (std::size_t at = 0; at < all.size(); at += chunk) {
      const auto piece = all.subspan(at, std::min(chunk, all.size() - at));
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

// What a data logger really sends: each inverter polled for its documented blocks (Hybrid
// running data and settings, GSL information, alarms and analog values) and answering them.
std::vector<std::uint8_t> make_polling_stream(std::size_t target) {
  struct Poll {
    pvtap::Dialect dialect;
    std::uint8_t function;
    std::uint16_t start;
    std::uint16_t count;
  };
  static constexpr Poll kPolls[] = {
      {pvtap::Dialect::Hybrid, 0x12, 0x1000, 0x24}, {pvtap::Dialect::Hybrid, 0x16, 0x1024, 0x27},
      {pvtap::Dialect::Gsl, 0x03, 1000, 10},        {pvtap::Dialect::Gsl, 0x03, 1030, 4},
      {pvtap::Dialect::Gsl, 0x03, 1050, 51},
  };
  std::vector<std::uint8_t> stream;
  std::uint16_t value = 0;
  for (std::uint8_t station = 1; stream.size() < target; station = station % 16 + 1) {
    for (const Poll& p : kPolls) {
      const auto request =
          pvtap::test::read_request(p.dialect, station, p.function, p.start, p.count);
      pvtap::encode_frame(request, stream);
      auto reply = pvtap::test::frame_of(p.dialect, pvtap::Role::Response, station, p.function);
      for (unsigned i = 0; i < p.count; ++i) reply.words.push_back(value++);
      if (p.dialect == pvtap::Dialect::Hybrid) reply.device = pvtap::DeviceNumber{0x32, station};
      pvtap::encode_frame(reply, stream);
    }
  }
  return stream;
}

void BM_ReassemblePollingRtu(benchmark::State& state) {
  static const auto stream = make_polling_stream(32 << 20);
  run(state, stream);
}
BENCHMARK(BM_ReassemblePollingRtu)->Unit(benchmark::kMillisecond);

void BM_ReassembleNoisyMixed(benchmark::State& state) {
  static const auto stream = make_stream(pvtap::DialectSet::all(), 20, 15, 8 << 20);
  run(state, stream);
}
BENCHMARK(BM_ReassembleNoisyMixed)->Unit(benchmark::kMillisecond);

void BM_ReassembleNoisyMixedSmallReads(benchmark::State& state) {
  static const auto stream = make_stream(pvtap::DialectSet::all(), 20, 15, 1 << 20);
  run(state, stream, 8);
}
BENCHMARK(BM_ReassembleNoisyMixedSmallReads)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
