// EdgeScanner: runs per channel from interleaved samples, whatever the chunking and unit size.
#include "logic/input/edge_scanner.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

namespace pvtap::analyzer {
namespace {

struct Collected final : RunConsumer {
  std::vector<std::vector<SampleRun>> runs = std::vector<std::vector<SampleRun>>(2);
  void run(std::size_t slot, SampleRun r) override { runs.at(slot).push_back(r); }
};

bool same(const std::vector<SampleRun>& a, const std::vector<SampleRun>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (a[i].level != b[i].level || a[i].count != b[i].count) return false;
  }
  return true;
}

// Two channels on bits 2 and 5 beside a busy bit 0 that nobody asked for: channel A high 20,
// low 3, high 30; channel B low 11, high 42.
std::vector<std::uint8_t> one_byte_samples() {
  std::vector<std::uint8_t> s;
  for (int i = 0; i < 53; ++i) {
    const bool a = i < 20 || i >= 23;
    const bool b = i >= 11;
    s.push_back(static_cast<std::uint8_t>((a ? 0x04 : 0) | (b ? 0x20 : 0) | (i & 1)));
  }
  return s;
}

const std::vector<SampleRun> kA = {{true, 20}, {false, 3}, {true, 30}};
const std::vector<SampleRun> kB = {{false, 11}, {true, 42}};

TEST(EdgeScanner, OneByteSamplesInAnyChunks) {
  const auto samples = one_byte_samples();
  for (std::size_t chunk : {1u, 3u, 8u, 9u, 53u}) {
    EdgeScanner scanner({2, 5});
    Collected out;
    for (std::size_t i = 0; i < samples.size(); i += chunk) {
      const std::size_t n = std::min(chunk, samples.size() - i);
      scanner.scan(std::span(samples.data() + i, n), 1, out);
    }
    scanner.finish(out);
    EXPECT_TRUE(same(out.runs[0], kA)) << "chunk " << chunk;
    EXPECT_TRUE(same(out.runs[1], kB)) << "chunk " << chunk;
  }
}

TEST(EdgeScanner, TwoByteSamplesReadTheHighByte) {
  // The same channels on bits 10 and 13: sample bytes are little-endian.
  std::vector<std::uint8_t> samples;
  for (std::uint8_t s : one_byte_samples()) {
    samples.push_back(0xFF);  // the low byte's channels change nothing asked for
    samples.push_back(s);
  }
  EdgeScanner scanner({10, 13});
  Collected out;
  scanner.scan(samples, 2, out);
  scanner.finish(out);
  EXPECT_TRUE(same(out.runs[0], kA));
  EXPECT_TRUE(same(out.runs[1], kB));
}

TEST(EdgeScanner, QuietLineIsOneRun) {
  std::vector<std::uint8_t> samples(1 << 20, 0x04);
  EdgeScanner scanner({2});
  Collected out;
  scanner.scan(samples, 1, out);
  scanner.scan(samples, 1, out);
  scanner.finish(out);
  EXPECT_TRUE(same(out.runs[0], {{true, 2u << 20}}));
}

TEST(EdgeScanner, EdgesAtEveryPlaceOfTheWideComparisons) {
  // Edges just before, on and after the 8- and 32-sample strides, in chunks that cut them.
  const std::vector<std::size_t> edges = {1, 7, 8, 9, 31, 32, 33, 63, 64, 65, 95, 200, 201, 999};
  std::vector<std::uint8_t> samples(1000);
  std::vector<SampleRun> expected;
  bool level = true;
  std::size_t from = 0;
  for (std::size_t i = 0, e = 0; i < samples.size(); ++i) {
    if (e < edges.size() && i == edges[e]) {
      expected.push_back({level, i - from});
      level = !level;
      from = i;
      ++e;
    }
    samples[i] = static_cast<std::uint8_t>((level ? 0x08 : 0) | (i % 3 == 0 ? 0x01 : 0));
  }
  expected.push_back({level, samples.size() - from});
  for (std::size_t chunk : {1000u, 33u, 40u}) {
    EdgeScanner scanner({3});
    Collected out;
    for (std::size_t i = 0; i < samples.size(); i += chunk)
      scanner.scan(std::span(samples.data() + i, std::min(chunk, samples.size() - i)), 1, out);
    scanner.finish(out);
    EXPECT_TRUE(same(out.runs[0], expected)) << "chunk " << chunk;
  }
}

}  // namespace
}  // namespace pvtap::analyzer
