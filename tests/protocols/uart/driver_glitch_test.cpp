// The driver glitch filter on characters placed by hand: glitch bytes at a driver's switching
// go aside, a frame's own 0x00 and 0xFF stay, and nothing is joined or split.
#include "pvtap/uart/driver_glitches.h"

#include <gtest/gtest.h>

#include <vector>

#include "pvtap/codec/checksums.h"

namespace pvtap {
namespace {

// 100 samples per bit, 8N1: a character is 1000 samples.
const UartLine kLine{960000, 9600, UartFormat{}};
constexpr std::uint64_t kChar = 1000;

std::vector<std::uint8_t> with_crc(std::vector<std::uint8_t> bytes) {
  const std::uint16_t crc = Crc16Modbus::compute(bytes);
  bytes.push_back(static_cast<std::uint8_t>(crc & 0xFF));
  bytes.push_back(static_cast<std::uint8_t>(crc >> 8));
  return bytes;
}

// Places characters back to back from `at`; returns where the last one ends.
std::uint64_t put(std::vector<UartCharacter>& line, std::uint64_t at,
                  const std::vector<std::uint8_t>& bytes) {
  for (std::uint8_t b : bytes) {
    line.push_back(UartCharacter{b, at, at + kChar});
    at += kChar;
  }
  return at;
}

struct Filtered {
  std::vector<std::uint8_t> bytes;
  std::vector<DriverGlitch> glitches;
};

Filtered run(const std::vector<UartCharacter>& line) {
  DriverGlitchFilter filter(kLine);
  std::vector<UartCharacter> out;
  Filtered f;
  for (const UartCharacter& c : line) filter.feed(c, out, f.glitches);
  filter.flush(out, f.glitches);
  for (const UartCharacter& c : out) f.bytes.push_back(static_cast<std::uint8_t>(c.value));
  return f;
}

TEST(DriverGlitchFilter, SwitchOnAndOffGlitchesGoAsideAndTheFrameStaysWhole) {
  const auto frame = with_crc({0x01, 0x03, 0x03, 0xE8, 0x00, 0x0A});
  std::vector<UartCharacter> line;
  // Switching on: a 0x00 with a framing error 1.2 characters before the frame.
  line.push_back(UartCharacter{0x00, 10'000, 11'000, true});
  const std::uint64_t end = put(line, 11'200, frame);
  // Switching off: a 0xFE 30 samples after the last stop bit.
  line.push_back(UartCharacter{0xFE, end + 30, end + 30 + kChar});
  const Filtered f = run(line);
  EXPECT_EQ(f.bytes, frame);
  ASSERT_EQ(f.glitches.size(), 2u);
  EXPECT_TRUE(f.glitches[0].switch_on);
  EXPECT_EQ(f.glitches[0].character.value, 0x00);
  EXPECT_FALSE(f.glitches[1].switch_on);
  EXPECT_EQ(f.glitches[1].character.value, 0xFE);
}

TEST(DriverGlitchFilter, ASwitchOffByteWithAParityErrorGoesAsideAfterADamagedFrame) {
  // No CRC can tell here: the frame is damaged with the byte and without it. On an 8E1 line
  // the 0xFF of a driver switching off has its parity bit wrong, and that says it.
  auto frame = with_crc({0x01, 0x03, 0x02, 0x12, 0x34});
  frame[3] ^= 0x40;
  std::vector<UartCharacter> line;
  const std::uint64_t end = put(line, 10'000, frame);
  line.push_back(UartCharacter{0xFF, end + 30, end + 30 + kChar, false, true});
  const Filtered f = run(line);
  EXPECT_EQ(f.bytes, frame);
  ASSERT_EQ(f.glitches.size(), 1u);
  EXPECT_FALSE(f.glitches[0].switch_on);
  // Read cleanly, the same byte stays: it may be the frame's own.
  line.back().parity_error = false;
  EXPECT_EQ(run(line).bytes.size(), frame.size() + 1);
}

TEST(DriverGlitchFilter, AFramesOwnZeroAndFfStay) {
  // A broadcast (station 0) whose CRC may end in anything: every byte is the frame's.
  std::vector<std::uint8_t> frame;
  for (std::uint8_t x = 0;; ++x) {
    frame = with_crc({0x00, 0x06, 0x00, x, 0x00, 0x01});
    if (frame.back() == 0xFF || frame.back() == 0xFE || frame.back() == 0x00) break;
  }
  std::vector<UartCharacter> line;
  put(line, 5'000, frame);
  const Filtered f = run(line);
  EXPECT_EQ(f.bytes, frame);
  EXPECT_TRUE(f.glitches.empty());
}

TEST(DriverGlitchFilter, ASuspectByteFarFromTheFrameIsNoGlitch) {
  const auto frame = with_crc({0x01, 0x03, 0x00, 0x00, 0x00, 0x02});
  std::vector<UartCharacter> line;
  // Two characters of silence (under t3.5, over about a character): not the driver switching.
  const std::uint64_t end = put(line, 5'000, frame);
  line.push_back(UartCharacter{0xFF, end + 2 * kChar, end + 3 * kChar});
  const Filtered f = run(line);
  EXPECT_EQ(f.bytes.size(), frame.size() + 1);
  EXPECT_TRUE(f.glitches.empty());
}

TEST(DriverGlitchFilter, RunsApartByThreeAndAHalfCharactersAreJudgedApart) {
  const auto request = with_crc({0x01, 0x03, 0x00, 0x00, 0x00, 0x02});
  const auto reply = with_crc({0x01, 0x03, 0x04, 0x00, 0x01, 0x00, 0x02});
  std::vector<UartCharacter> line;
  std::uint64_t end = put(line, 5'000, request);
  line.push_back(UartCharacter{0xFF, end + 40, end + 40 + kChar});
  end = put(line, end + 40 + kChar + 4 * kChar, reply);
  line.push_back(UartCharacter{0xFF, end + 60, end + 60 + kChar});
  const Filtered f = run(line);
  std::vector<std::uint8_t> both = request;
  both.insert(both.end(), reply.begin(), reply.end());
  EXPECT_EQ(f.bytes, both);
  ASSERT_EQ(f.glitches.size(), 2u);
  EXPECT_FALSE(f.glitches[0].switch_on);
  EXPECT_FALSE(f.glitches[1].switch_on);
}

}  // namespace
}  // namespace pvtap
