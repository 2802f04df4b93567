// BlockInference: the types of unmapped words from the values a capture shows.
#include "pvtap/registers/register_inference.h"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <vector>

namespace pvtap {
namespace {

std::vector<std::uint16_t> float_words(float f, bool low_first) {
  const auto bits = std::bit_cast<std::uint32_t>(f);
  const auto high = static_cast<std::uint16_t>(bits >> 16), low = static_cast<std::uint16_t>(bits);
  return low_first ? std::vector<std::uint16_t>{low, high} : std::vector<std::uint16_t>{high, low};
}

// A block of two phase voltages as float32 in one word order, sampled 40 times.
std::vector<InferredValue> voltages(bool low_first) {
  BlockInference b(4);
  for (int k = 0; k < 40; ++k) {
    std::vector<std::uint16_t> words = float_words(235.0f + 0.01f * float(k % 7), low_first);
    const std::vector<std::uint16_t> second = float_words(233.0f - 0.02f * float(k % 5), low_first);
    words.insert(words.end(), second.begin(), second.end());
    b.add(words);
  }
  return b.infer(0, 4);
}

TEST(RegisterInference, Float32InEitherWordOrderWithAPhaseVoltageHint) {
  for (const bool low_first : {false, true}) {
    const std::vector<InferredValue> v = voltages(low_first);
    ASSERT_EQ(v.size(), 2u);
    for (const InferredValue& x : v) {
      EXPECT_EQ(x.kind, InferredKind::Float32);
      EXPECT_EQ(x.order, low_first ? WordOrder::LowFirst : WordOrder::HighFirst);
      EXPECT_GT(x.confidence, 0.8);
      EXPECT_NE(x.hint.find("phase voltage"), std::string::npos) << x.hint;
    }
    EXPECT_NEAR(v[0].min, 235.0, 1e-3);
    EXPECT_NEAR(v[0].max, 235.06, 1e-3);
  }
}

TEST(RegisterInference, IntegersFlagsFillTextAndCounters) {
  BlockInference b(9);
  std::uint32_t energy = 0x0001FFF0;
  std::uint16_t messages = 0xFF00;
  for (int k = 0; k < 60; ++k) {
    const int current = static_cast<int>(std::lround(300 * std::sin(k / 6.0)));  // crosses 0
    const std::uint16_t flags = current > 0 ? 0x0009 : 0x0011;
    energy += 3;
    messages = static_cast<std::uint16_t>(messages + 100);
    b.add(std::vector<std::uint16_t>{
        static_cast<std::uint16_t>(static_cast<std::int16_t>(current)),                // s16
        static_cast<std::uint16_t>(energy >> 16), static_cast<std::uint16_t>(energy),  // u32
        flags,                                                                         // bits
        0xFFFF,                                                                        // unused
        messages,                                                                      // counter
        0x4142, 0x4344, 0x0000});                                                      // "ABCD"
  }
  const std::vector<InferredValue> v = b.infer(0, 9);
  ASSERT_EQ(v.size(), 6u);
  EXPECT_EQ(v[0].kind, InferredKind::S16);
  EXPECT_LT(v[0].min, 0);
  EXPECT_EQ(v[1].kind, InferredKind::U32);
  EXPECT_EQ(v[1].order, WordOrder::HighFirst);
  EXPECT_TRUE(v[1].counter);
  EXPECT_EQ(v[2].kind, InferredKind::Bits);
  EXPECT_EQ(v[3].kind, InferredKind::Unused);
  EXPECT_EQ(v[4].kind, InferredKind::U16);
  EXPECT_TRUE(v[4].counter);
  EXPECT_GT(v[4].wraps, 0u);
  EXPECT_EQ(v[5].kind, InferredKind::Text);
  EXPECT_EQ(v[5].text, "ABCD");
  EXPECT_EQ(v[5].words, 3);
  for (const InferredValue& x : v) EXPECT_FALSE(x.evidence.empty());
}

// A signed 32-bit value whose second word is only its sign; a reply of another length is not
// counted.
TEST(RegisterInference, SignExtensionWordMakesAnS32) {
  BlockInference b(2);
  for (int k = -20; k < 20; ++k) {
    const auto x = static_cast<std::uint32_t>(k * 37);
    b.add(std::vector<std::uint16_t>{static_cast<std::uint16_t>(x),
                                     static_cast<std::uint16_t>(x >> 16)});
  }
  b.add(std::vector<std::uint16_t>{1, 2, 3});
  EXPECT_EQ(b.samples(), 40u);
  const std::vector<InferredValue> v = b.infer(0, 2);
  ASSERT_EQ(v.size(), 1u);
  EXPECT_EQ(v[0].kind, InferredKind::S32);
  EXPECT_EQ(v[0].order, WordOrder::LowFirst);
  EXPECT_EQ(v[0].min, -20 * 37);
}

}  // namespace
}  // namespace pvtap
