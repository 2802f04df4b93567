// The UART decoder on runs synthesised from known bytes: formats, inversion, line errors.
#include "pvtap/uart/uart_decoder.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "uart_runs.h"

namespace pvtap {
namespace {

using test::decode_runs;
using test::UartRuns;

// 4 MS/s at 9600 baud, as the flow-meter sessions: 416.67 samples per bit.
constexpr double kRate = 4e6;
constexpr double kBaud = 9600;
const std::vector<std::uint8_t> kBytes = {0x00, 0x01, 0x55, 0xAA, 0x7F, 0x80, 0xF7, 0xFF};

UartLine line_of(UartFormat format) {
  return UartLine{kRate, kBaud, format};
}

std::vector<std::uint8_t> values(const std::vector<UartCharacter>& chars) {
  std::vector<std::uint8_t> out;
  for (const UartCharacter& c : chars) out.push_back(static_cast<std::uint8_t>(c.value));
  return out;
}

void expect_clean_round_trip(UartFormat format, double gap_bits) {
  UartRuns line(kRate / kBaud, format);
  line.idle(20).bytes(kBytes, gap_bits).idle(20);
  const auto chars = decode_runs(line_of(format), line.runs());
  EXPECT_EQ(values(chars), kBytes) << format_name(format);
  for (const UartCharacter& c : chars) {
    EXPECT_FALSE(c.framing_error || c.parity_error || c.is_break) << format_name(format);
  }
}

TEST(UartDecoder, EightNoneOneBackToBack) {
  expect_clean_round_trip(UartFormat{8, Parity::None, 1, false}, 0);
}

TEST(UartDecoder, EightEvenOne) {
  expect_clean_round_trip(UartFormat{8, Parity::Even, 1, false}, 0);
}

TEST(UartDecoder, EightOddOne) {
  expect_clean_round_trip(UartFormat{8, Parity::Odd, 1, false}, 0.5);
}

TEST(UartDecoder, EightNoneTwo) {
  expect_clean_round_trip(UartFormat{8, Parity::None, 2, false}, 0);
}

TEST(UartDecoder, InvertedLineIdlesLow) {
  const UartFormat format{8, Parity::None, 1, true};
  UartRuns line(kRate / kBaud, format);
  line.idle(5).bytes(kBytes, 1);
  EXPECT_FALSE(line.runs().front().level);  // the synthesised line really idles low
  expect_clean_round_trip(format, 1);
}

TEST(UartDecoder, TimesAtSamplePrecision) {
  const UartFormat format{8, Parity::None, 1, false};
  UartRuns line(kRate / kBaud, format);
  line.idle(7);
  const std::uint64_t first = line.now();
  line.byte(0x41).idle(3.25);
  const std::uint64_t second = line.now();
  line.byte(0x42).idle(4);
  const auto chars = decode_runs(line_of(format), line.runs());
  ASSERT_EQ(chars.size(), 2u);
  EXPECT_EQ(chars[0].start, first);
  EXPECT_EQ(chars[1].start, second);
  // The end is the start plus ten bits, to the nearest sample.
  EXPECT_EQ(chars[0].end, first + static_cast<std::uint64_t>(std::llround(10 * kRate / kBaud)));
}

TEST(UartDecoder, ParityErrorIsFlaggedAndTheValueKept) {
  const UartFormat format{8, Parity::Even, 1, false};
  UartRuns line(kRate / kBaud, format);
  line.idle(10).byte(0x31).byte(0x32, true).byte(0x33).idle(10);
  const auto chars = decode_runs(line_of(format), line.runs());
  ASSERT_EQ(chars.size(), 3u);
  EXPECT_EQ(values(chars), (std::vector<std::uint8_t>{0x31, 0x32, 0x33}));
  EXPECT_FALSE(chars[0].parity_error);
  EXPECT_TRUE(chars[1].parity_error);
  EXPECT_FALSE(chars[2].parity_error);
}

TEST(UartDecoder, FramingErrorThenTheLineResynchronises) {
  const UartFormat format{8, Parity::None, 1, false};
  UartRuns line(kRate / kBaud, format);
  line.idle(10).byte(0x81, false, true).idle(2).byte(0x5A).idle(10);
  const auto chars = decode_runs(line_of(format), line.runs());
  ASSERT_EQ(chars.size(), 2u);
  EXPECT_EQ(chars[0].value, 0x81);
  EXPECT_TRUE(chars[0].framing_error);
  EXPECT_FALSE(chars[0].is_break);
  EXPECT_EQ(chars[1].value, 0x5A);
  EXPECT_FALSE(chars[1].framing_error);
}

TEST(UartDecoder, ZeroWithAFramingErrorIsNoBreak) {
  // A driver switching on can leave one character time of space: a 0x00 with a framing error.
  const UartFormat format{8, Parity::None, 1, false};
  UartRuns line(kRate / kBaud, format);
  line.idle(10).hold(false, 10).idle(5).byte(0x11).idle(5);
  const auto chars = decode_runs(line_of(format), line.runs());
  ASSERT_EQ(chars.size(), 2u);
  EXPECT_EQ(chars[0].value, 0x00);
  EXPECT_TRUE(chars[0].framing_error);
  EXPECT_FALSE(chars[0].is_break);
  EXPECT_EQ(chars[1].value, 0x11);
}

TEST(UartDecoder, BreakHoldsTheLineLongerThanACharacter) {
  const UartFormat format{8, Parity::None, 1, false};
  UartRuns line(kRate / kBaud, format);
  line.idle(10);
  const std::uint64_t from = line.now();
  line.hold(false, 40);
  const std::uint64_t to = line.now();
  line.idle(5).byte(0x22).idle(5);
  const auto chars = decode_runs(line_of(format), line.runs());
  ASSERT_EQ(chars.size(), 2u);
  EXPECT_TRUE(chars[0].is_break);
  EXPECT_FALSE(chars[0].framing_error);
  EXPECT_EQ(chars[0].start, from);
  EXPECT_EQ(chars[0].end, to);
  EXPECT_EQ(chars[1].value, 0x22);
  EXPECT_FALSE(chars[1].is_break);
}

TEST(UartDecoder, BreakAtTheEndOfSamplesIsGivenOutByFinish) {
  const UartFormat format{8, Parity::None, 1, false};
  UartRuns line(kRate / kBaud, format);
  line.idle(10).hold(false, 30);
  const auto chars = decode_runs(line_of(format), line.runs());
  ASSERT_EQ(chars.size(), 1u);
  EXPECT_TRUE(chars[0].is_break);
}

TEST(UartDecoder, GlitchShorterThanHalfABitOpensNoCharacter) {
  const UartFormat format{8, Parity::None, 1, false};
  UartRuns line(kRate / kBaud, format);
  line.idle(10).hold(false, 0.4).idle(3).byte(0x66).idle(5);
  const std::vector<SampleRun> runs = line.runs();
  UartDecoder decoder(line_of(format));
  std::vector<UartCharacter> chars;
  for (const SampleRun& r : runs) decoder.feed(r, chars);
  decoder.finish(chars);
  ASSERT_EQ(chars.size(), 1u);
  EXPECT_EQ(chars[0].value, 0x66);
  EXPECT_EQ(decoder.false_starts(), 1u);
}

TEST(UartDecoder, IdleCostsOneRunWhateverItsLength) {
  const UartFormat format{8, Parity::None, 1, false};
  UartDecoder decoder(line_of(format));
  std::vector<UartCharacter> chars;
  decoder.feed(SampleRun{true, 1ull << 40}, chars);
  EXPECT_EQ(decoder.position(), 1ull << 40);
  EXPECT_TRUE(chars.empty());
}

TEST(UartDecoder, RunsSplitAnywhereDecodeTheSame) {
  const UartFormat format{8, Parity::Even, 1, false};
  UartRuns line(kRate / kBaud, format);
  line.idle(10).bytes(kBytes, 0).idle(10);
  std::vector<SampleRun> split;
  for (const SampleRun& r : line.runs()) {
    // A logic analyzer's chunks cut runs where they like: every run here arrives in pieces.
    for (std::uint64_t left = r.count; left > 0;) {
      const std::uint64_t piece = std::min<std::uint64_t>(left, 97);
      split.push_back(SampleRun{r.level, piece});
      left -= piece;
    }
  }
  EXPECT_EQ(values(decode_runs(line_of(format), split)), kBytes);
}

}  // namespace
}  // namespace pvtap
