// CRC-16/MODBUS and the ASCII sum over buffers of frame-like and bulk sizes.
#include <benchmark/benchmark.h>

#include <random>
#include <vector>

#include "pvtap/codec/checksums.h"

namespace {

std::vector<std::uint8_t> random_bytes(std::size_t n) {
  std::mt19937 rng(42);
  std::vector<std::uint8_t> v(n);
  for (auto& b : v) b = static_cast<std::uint8_t>(rng());
  return v;
}

void BM_Crc16Modbus(benchmark::State& state) {
  const auto bytes = random_bytes(static_cast<std::size_t>(state.range(0)));
  for (auto _ : state) benchmark::DoNotOptimize(pvtap::Crc16Modbus::compute(bytes));
  state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations()) * state.range(0));
}
BENCHMARK(BM_Crc16Modbus)->Arg(6)->Arg(77)->Arg(256)->Arg(1 << 16);

void BM_AsciiChecksum(benchmark::State& state) {
  const auto bytes = random_bytes(static_cast<std::size_t>(state.range(0)));
  for (auto _ : state) benchmark::DoNotOptimize(pvtap::AsciiChecksum::compute(bytes));
  state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations()) * state.range(0));
}
BENCHMARK(BM_AsciiChecksum)->Arg(13)->Arg(1 << 16);

}  // namespace

BENCHMARK_MAIN();
