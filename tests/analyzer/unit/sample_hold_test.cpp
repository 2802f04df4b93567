// SampleHold: a recording that fits is held whole and replayed as the file gave it; one that
// does not is given up, and a refused probe stops the reading.
#include "logic/input/sample_hold.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

namespace pvtap::analyzer {
namespace {

// Recorded: what a sink was given.
struct Recorded final : LogicSink {
  std::vector<std::string> names;
  double rate = 0;
  std::vector<std::vector<std::uint8_t>> chunks;
  void begin(const std::vector<LogicChannel>& channels, double sample_rate) override {
    for (const LogicChannel& c : channels) names.push_back(c.name);
    rate = sample_rate;
  }
  void samples(std::span<const std::uint8_t> data, unsigned) override {
    chunks.emplace_back(data.begin(), data.end());
  }
};

const std::vector<LogicChannel> kChannels = {{"RX", 0}, {"TX", 1}};

// Feeds `hold` three chunks of 4 samples while it wants more; how many it took.
int feed(SampleHold& hold) {
  hold.begin(kChannels, 1e6);
  int fed = 0;
  for (std::uint8_t c = 0; c < 3 && hold.wants_more(); ++c) {
    const std::vector<std::uint8_t> chunk(4, c);
    hold.samples(chunk, 1);
    ++fed;
  }
  return fed;
}

TEST(SampleHold, ARecordingThatFitsIsReplayedChunkByChunk) {
  LineProbe probe({});
  SampleHold hold(probe, 12);
  EXPECT_EQ(feed(hold), 3);
  const HeldSamples held = hold.take();
  ASSERT_TRUE(held.whole);
  Recorded out;
  held.replay(out);
  EXPECT_EQ(out.names, (std::vector<std::string>{"RX", "TX"}));
  EXPECT_EQ(out.rate, 1e6);
  ASSERT_EQ(out.chunks.size(), 3u);
  EXPECT_EQ(out.chunks[2], std::vector<std::uint8_t>(4, 2));
}

TEST(SampleHold, OneOverTheLimitIsGivenUp) {
  LineProbe probe({});
  SampleHold hold(probe, 11);
  feed(hold);
  const HeldSamples held = hold.take();
  EXPECT_FALSE(held.whole);
  EXPECT_TRUE(held.chunks.empty());
}

TEST(SampleHold, AChannelTheFileLacksStopsTheReading) {
  LineProbe probe({"DE"});
  SampleHold hold(probe, 1 << 20);
  EXPECT_EQ(feed(hold), 0);
  EXPECT_FALSE(hold.take().whole);
}

}  // namespace
}  // namespace pvtap::analyzer
