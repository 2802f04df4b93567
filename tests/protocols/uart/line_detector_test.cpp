// Line settings found from synthesised samples of a Modbus conversation: rate (exact, 1.5 %
// and 3 % off), idle level, parity and stop bits; and what is not a UART.
#include "pvtap/uart/line_detector.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "pvtap/codec/checksums.h"
#include "uart_runs.h"

namespace pvtap {
namespace {

using test::UartRuns;

constexpr double kRate = 4e6;

std::vector<std::uint8_t> with_crc(std::vector<std::uint8_t> body) {
  const std::uint16_t crc = Crc16Modbus::compute(body);
  body.push_back(static_cast<std::uint8_t>(crc & 0xFF));
  body.push_back(static_cast<std::uint8_t>(crc >> 8));
  return body;
}

// A master reading two registers from station 247 and its reply, `polls` times over.
std::vector<SampleRun> conversation(double baud, UartFormat format, int polls = 6,
                                    double gap_bits = 0) {
  const auto request = with_crc({0xF7, 0x03, 0x00, 0x10, 0x00, 0x02});
  UartRuns line(kRate / baud, format);
  line.idle(50);
  for (int i = 0; i < polls; ++i) {
    const auto reply = with_crc({0xF7, 0x03, 0x04, 0x12, static_cast<std::uint8_t>(i), 0x00,
                                 static_cast<std::uint8_t>(0x80 | i)});
    line.bytes(request, gap_bits).idle(60).bytes(reply, gap_bits).idle(200);
  }
  return line.runs();
}

DetectedLine detect(const std::vector<SampleRun>& runs) {
  LineDetector detector;
  for (const SampleRun& r : runs) detector.add(r);
  const std::optional<DetectedLine> d = detector.decide(kRate);
  EXPECT_TRUE(d.has_value());
  return d.value_or(DetectedLine{});
}

void expect_format(const DetectedLine& d, UartFormat format) {
  EXPECT_EQ(format_name(d.line.format), format_name(format));
  EXPECT_EQ(d.line.format.inverted, format.inverted);
  EXPECT_TRUE(d.has_traffic);
  EXPECT_EQ(d.trial.good_frames, 12u);
  EXPECT_EQ(d.trial.line_errors, 0u);
}

TEST(LineDetector, ModbusDefaultEightNoneTwoAt9600) {
  const UartFormat format{8, Parity::None, 2, false};
  const DetectedLine d = detect(conversation(9600, format));
  EXPECT_EQ(d.baud.baud, 9600u);
  EXPECT_TRUE(d.baud.snapped);
  EXPECT_NEAR(d.baud.measured, 9600, 9600 * 0.002);
  expect_format(d, format);
}

TEST(LineDetector, EvenParityAt19200) {
  const UartFormat format{8, Parity::Even, 1, false};
  const DetectedLine d = detect(conversation(19200, format));
  EXPECT_EQ(d.baud.baud, 19200u);
  expect_format(d, format);
}

TEST(LineDetector, OddParityAt4800) {
  const UartFormat format{8, Parity::Odd, 1, false};
  const DetectedLine d = detect(conversation(4800, format));
  EXPECT_EQ(d.baud.baud, 4800u);
  expect_format(d, format);
}

TEST(LineDetector, OneStopBitBackToBackIsNotReadAsTwo) {
  const UartFormat format{8, Parity::None, 1, false};
  const DetectedLine d = detect(conversation(9600, format));
  expect_format(d, format);
}

TEST(LineDetector, LineIdlingLowIsInverted) {
  const UartFormat format{8, Parity::Even, 1, true};
  const DetectedLine d = detect(conversation(38400, format));
  EXPECT_EQ(d.baud.baud, 38400u);
  expect_format(d, format);
}

TEST(LineDetector, ClockOnePointFivePercentFastSnapsTo9600) {
  const UartFormat format{8, Parity::None, 2, false};
  const DetectedLine d = detect(conversation(9600 * 1.015, format));
  EXPECT_EQ(d.baud.baud, 9600u);
  EXPECT_TRUE(d.baud.snapped);
  EXPECT_NEAR(d.baud.deviation, 0.015, 0.002);
  EXPECT_NEAR(d.baud.measured, 9744, 15);
  expect_format(d, format);
}

TEST(LineDetector, ClockThreePercentSlowKeepsTheMeasuredRate) {
  const UartFormat format{8, Parity::Even, 1, false};
  const DetectedLine d = detect(conversation(9600 * 0.97, format));
  EXPECT_FALSE(d.baud.snapped);
  EXPECT_NEAR(d.baud.deviation, -0.03, 0.002);
  EXPECT_NEAR(d.baud.baud, 9312, 15);
  // Decoded at the measured rate, every frame still checks.
  expect_format(d, format);
}

// Every edge moved by up to `percent` of a bit, as slow transceivers and long lines do: the
// same runs, each boundary shifted by a fixed pseudo-random amount.
std::vector<SampleRun> jittered(std::vector<SampleRun> runs, double bit, double percent) {
  std::uint32_t seed = 12345;
  double previous_shift = 0;
  for (std::size_t i = 0; i + 1 < runs.size(); ++i) {
    seed = seed * 1103515245u + 12345u;
    const double unit = static_cast<double>((seed >> 8) & 0xFFFF) / 65535.0 * 2 - 1;
    const double shift = std::round(unit * percent / 100 * bit);
    runs[i].count =
        static_cast<std::uint64_t>(static_cast<double>(runs[i].count) + shift - previous_shift);
    previous_shift = shift;
  }
  return runs;
}

TEST(LineDetector, EdgesJitteringEightPercentOfABitKeepTheRate) {
  // The shortest common pulse is then the short end of the bits: refined once, its bands
  // around 3, 4 and 5 bits took only the short pulses, and 9600 read as 10088.
  for (const UartFormat format :
       {UartFormat{8, Parity::None, 2, false}, UartFormat{8, Parity::Even, 1, false}}) {
    for (const double baud : {9600.0, 19200.0, 115200.0}) {
      const DetectedLine d = detect(jittered(conversation(baud, format), kRate / baud, 8));
      EXPECT_EQ(d.baud.baud, static_cast<std::uint32_t>(baud)) << baud;
      EXPECT_NEAR(d.baud.deviation, 0, 0.01) << baud;
      expect_format(d, format);
    }
  }
}

// Each talker's driver switching on (space for a whole character, stop bits included, then
// mark for a bit) before its frame and off after it (the line falling for one bit).
std::vector<SampleRun> glitching_conversation(double baud, UartFormat format) {
  const auto request = with_crc({0xF7, 0x03, 0x00, 0x10, 0x00, 0x02});
  UartRuns line(kRate / baud, format);
  line.idle(50);
  const auto frame = [&](std::span<const std::uint8_t> bytes) {
    line.hold(false, 11).idle(1.0).bytes(bytes).idle(0.3).hold(false, 1).idle(60);
  };
  for (int i = 0; i < 6; ++i) {
    const auto reply = with_crc({0xF7, 0x03, 0x04, 0x12, static_cast<std::uint8_t>(i), 0x00,
                                 static_cast<std::uint8_t>(0x80 | i)});
    frame(request);
    frame(reply);
    line.idle(140);
  }
  return line.runs();
}

TEST(LineDetector, DriverGlitchesBetweenFramesDoNotChooseTheFormat) {
  // The glitches read with more line errors in 8N2 than in 8N1; the frames read clean in both,
  // and 8N2 is what Modbus RTU asks for without parity.
  const UartFormat format{8, Parity::None, 2, false};
  const DetectedLine d = detect(glitching_conversation(9600, format));
  EXPECT_EQ(format_name(d.line.format), format_name(format));
  EXPECT_EQ(d.trial.good_frames, 12u);
  EXPECT_EQ(d.trial.frame_line_errors, 0u);
  EXPECT_GT(d.trial.line_errors, 0u);
}

// A bus line without failsafe bias, probed on A/B: in space wherever no driver holds it. Each
// driver lifts it before its frame with a short pulse (mark for an eighth of a bit, a dip to space
// of `dip` bits, then mark for `lead` bits) and drops it when released, `release` bits after
// its last stop bit: to a receiver, a start bit that never ends.
std::vector<SampleRun> unbiased_conversation(double baud, UartFormat format, double dip,
                                             std::span<const double> leads) {
  const auto request = with_crc({0xF7, 0x03, 0x00, 0x10, 0x00, 0x02});
  UartRuns line(kRate / baud, format);
  line.hold(false, 50);
  std::size_t turn = 0;
  const auto frame = [&](std::span<const std::uint8_t> bytes) {
    const double lead = leads[turn++ % leads.size()];
    line.idle(0.12).hold(false, dip).idle(lead).bytes(bytes).idle(0.2).hold(false, 60);
  };
  for (int i = 0; i < 6; ++i) {
    const auto reply = with_crc({0xF7, 0x03, 0x04, 0x12, static_cast<std::uint8_t>(i), 0x00,
                                 static_cast<std::uint8_t>(0x80 | i)});
    frame(request);
    frame(reply);
    line.hold(false, 140);
  }
  return line.runs();
}

TEST(LineDetector, BusLineRestingInSpaceIsReadAtThePolarityItsFramesCheckIn) {
  // Most samples are in space: the idle level alone said inverted, and no frame checked.
  const double leads[] = {1.0};
  for (const bool inverted : {false, true}) {
    const UartFormat format{8, Parity::None, 2, inverted};
    const DetectedLine d = detect(unbiased_conversation(9600, format, 0.15, leads));
    EXPECT_EQ(d.baud.baud, 9600u) << inverted;
    EXPECT_EQ(d.line.format.inverted, inverted);
    EXPECT_TRUE(d.has_traffic);
    EXPECT_EQ(d.trial.good_frames, 12u) << inverted;
  }
}

TEST(LineDetector, SwitchOnPulsesAtEveryTurnAreNoBit) {
  // Two pulses of one width at every turn, an eighth and a sixth of a bit: 2 % of the pulses and
  // more, as common as a bit by that share alone, and far rarer than the bits.
  const double leads[] = {1.0};
  const UartFormat format{8, Parity::None, 1, false};
  const DetectedLine d = detect(unbiased_conversation(19200, format, 0.16, leads));
  EXPECT_EQ(d.baud.baud, 19200u);
  EXPECT_NEAR(d.baud.deviation, 0, 0.005);
  EXPECT_EQ(d.trial.good_frames, 12u);
}

TEST(LineDetector, DriversLeadingByPartsOfABitKeepTheRate) {
  // Jittering edges and leads of 0.45 to 1.5 bits before the first start bit crowd the short
  // end of the bits: the first width was a fifth of a bit short, four rounds of refining left
  // 9600 at 10085, and no frame checked.
  const double leads[] = {0.45, 0.8, 1.3, 0.6, 1.5, 0.95, 0.5, 1.1, 0.7, 1.4, 0.55, 0.85};
  const UartFormat format{8, Parity::None, 2, false};
  const double baud = 9600 * 0.99;
  const DetectedLine d =
      detect(jittered(unbiased_conversation(baud, format, 0.3, leads), kRate / baud, 5));
  EXPECT_EQ(d.baud.baud, 9600u);
  EXPECT_NEAR(d.baud.deviation, -0.01, 0.003);
  EXPECT_EQ(d.trial.good_frames, 12u);
}

TEST(LineDetector, IdleLineHasNoBit) {
  LineDetector detector;
  detector.add(SampleRun{true, 1'000'000});
  EXPECT_FALSE(detector.decide(kRate).has_value());
}

TEST(LineDetector, SquareWaveIsNoUartTraffic) {
  // A clock: every pulse one width, high and low alike. It reads as clean 0x55 characters in
  // 8N1 (a square wave is exactly that), one value over and over, and no frame checks.
  LineDetector detector;
  for (int i = 0; i < 2000; ++i) {
    detector.add(SampleRun{true, 37});
    detector.add(SampleRun{false, 37});
  }
  const std::optional<DetectedLine> d = detector.decide(kRate);
  ASSERT_TRUE(d.has_value());
  EXPECT_EQ(d->trial.good_frames, 0u);
  EXPECT_FALSE(d->has_traffic);
}

TEST(LineDetector, TooFewSamplesPerBitAreReported) {
  // 115200 baud at 400 kS/s: 3.5 samples per bit, below what a reader can trust.
  const UartFormat format{8, Parity::None, 1, false};
  UartRuns line(400e3 / 115200, format);
  line.idle(50).bytes(with_crc({0x01, 0x03, 0x00, 0x00, 0x00, 0x0A}), 0).idle(50);
  LineDetector detector;
  for (const SampleRun& r : line.runs()) detector.add(r);
  const std::optional<DetectedLine> d = detector.decide(400e3);
  ASSERT_TRUE(d.has_value());
  EXPECT_LT(d->samples_per_bit(), 4.0);
}

TEST(LineDetector, SnapKeepsRatesFarFromAStandardOne) {
  const BaudEstimate e = snap_baud(10000);
  EXPECT_FALSE(e.snapped);
  EXPECT_EQ(e.baud, 10000u);
  EXPECT_NEAR(e.deviation, 10000.0 / 9600 - 1, 1e-9);
  EXPECT_TRUE(snap_baud(115200 * 0.985).snapped);
}

}  // namespace
}  // namespace pvtap
