// The passive baud search fed what a UART at each setting it asks for reads from a Modbus
// line: every standard rate, parity told from the 8N1 framing errors and confirmed, a line
// that changes rate, and lines that never settle it.
#include "pvtap/uart/baud_search.h"

#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "pvtap/codec/checksums.h"
#include "uart_receiver.h"

namespace pvtap {
namespace {

using test::line_bytes;
using test::received;

std::vector<std::uint8_t> with_crc(std::vector<std::uint8_t> body) {
  const std::uint16_t crc = Crc16Modbus::compute(body);
  body.push_back(static_cast<std::uint8_t>(crc & 0xFF));
  body.push_back(static_cast<std::uint8_t>(crc >> 8));
  return body;
}

LineSetting setting(std::uint32_t baud, Parity parity, unsigned stop_bits = 1) {
  LineSetting s;
  s.baud = baud;
  s.format.parity = parity;
  s.format.stop_bits = stop_bits;
  return s;
}

// One transmission at `time`: the search reads it at its current setting.
void transmit(BaudSearch& search, const std::vector<std::uint8_t>& frame, const LineSetting& line,
              double time) {
  const auto bytes = line_bytes(received(frame, line, search.setting()));
  search.feed(bytes, time);
}

// A master polling station 17 once a second, the meter answering 40 ms later; returns the
// seconds of traffic the search took to settle, or -1 when it did not within `seconds`.
int poll_until_settled(BaudSearch& search, const LineSetting& line, int seconds = 60,
                       int from = 0) {
  for (int t = from; t < from + seconds; ++t) {
    const auto request = with_crc({0x11, 0x03, 0x00, 0x6B, 0x00, 0x03});
    const auto reply =
        with_crc({0x11, 0x03, 0x06, 0x02, 0x2B, static_cast<std::uint8_t>(t), 0x64, 0x00, 0x7F});
    transmit(search, request, line, t);
    transmit(search, reply, line, t + 0.04);
    search.tick(t + 0.5);
    if (search.settled()) return t - from;
  }
  return -1;
}

void expect_found(const LineSetting& line, unsigned stop_bits_read = 1) {
  BaudSearch search;
  const int took = poll_until_settled(search, line);
  ASSERT_GE(took, 0) << line.baud << " " << format_name(line.format) << " never settled";
  // Passive detection has to settle within half a minute of traffic.
  EXPECT_LE(took, 30);
  EXPECT_EQ(search.setting().baud, line.baud);
  EXPECT_EQ(search.setting().format.parity, line.format.parity);
  // A receiver reads two stop bits as one stop bit and idle line: it cannot tell them apart.
  EXPECT_EQ(search.setting().format.stop_bits, stop_bits_read);
}

TEST(BaudSearch, FindsEveryStandardRateOfAn8N1Line) {
  for (const std::uint32_t baud : BaudSearch::rates()) {
    SCOPED_TRACE(baud);
    expect_found(setting(baud, Parity::None));
  }
}

TEST(BaudSearch, FindsEvenParityFromTheFramingErrorsAt8N1) {
  expect_found(setting(9600, Parity::Even));
  expect_found(setting(19200, Parity::Even));
  expect_found(setting(2400, Parity::Even));
}

TEST(BaudSearch, FindsOddParityFromTheFramingErrorsAt8N1) {
  expect_found(setting(9600, Parity::Odd));
  expect_found(setting(57600, Parity::Odd));
}

TEST(BaudSearch, ReadsTwoStopBitsAsOne) {
  expect_found(setting(4800, Parity::None, 2), 1);
}

TEST(BaudSearch, AParityLineIsFirstReadAt8N1ThenConfirmedWithItsParity) {
  BaudSearch search;
  ASSERT_GE(poll_until_settled(search, setting(19200, Parity::Even)), 0);
  // 9600 8N1, 19200 8N1, then 19200 8E1 to confirm.
  EXPECT_EQ(search.settings_tried(), 3u);
}

TEST(BaudSearch, SearchesAgainWhenTheLineChangesRate) {
  BaudSearch search;
  ASSERT_GE(poll_until_settled(search, setting(9600, Parity::None)), 0);
  EXPECT_EQ(search.searches_again(), 0u);
  // Still settled on the first poll at the new rate: it takes a few to notice.
  EXPECT_EQ(poll_until_settled(search, setting(38400, Parity::Odd), 1, 100), 0);
  EXPECT_EQ(search.searches_again(), 0u);
  for (int t = 101; t < 150 && search.searches_again() == 0; ++t) {
    poll_until_settled(search, setting(38400, Parity::Odd), 1, t);
  }
  const int took = poll_until_settled(search, setting(38400, Parity::Odd), 60, 150);
  ASSERT_GE(took, 0);
  EXPECT_EQ(search.searches_again(), 1u);
  EXPECT_EQ(search.setting().baud, 38400u);
  EXPECT_EQ(search.setting().format.parity, Parity::Odd);
}

TEST(BaudSearch, StaysSettledOnAGoodLine) {
  BaudSearch search;
  ASSERT_GE(poll_until_settled(search, setting(4800, Parity::None)), 0);
  const std::uint64_t tried = search.settings_tried();
  EXPECT_EQ(poll_until_settled(search, setting(4800, Parity::None), 200, 100), 0);
  EXPECT_TRUE(search.settled());
  EXPECT_EQ(search.settings_tried(), tried);
}

TEST(BaudSearch, NoiseNeverSettles) {
  BaudSearch search;
  std::mt19937 random(24);
  for (int t = 0; t < 120; ++t) {
    std::vector<LineByte> noise(20);
    for (LineByte& b : noise) {
      b.value = static_cast<std::uint8_t>(random());
      b.error = random() % 3 == 0;
    }
    search.feed(noise, t);
    ASSERT_FALSE(search.settled()) << "at " << t << " s";
  }
  // It kept cycling through the rates.
  EXPECT_GT(search.settings_tried(), BaudSearch::rates().size());
}

TEST(BaudSearch, AQuietLineKeepsItsSetting) {
  BaudSearch search;
  for (int t = 0; t < 100; ++t) EXPECT_FALSE(search.tick(t));
  EXPECT_EQ(search.settings_tried(), 1u);
}

TEST(ParityEvidence, TellsEvenFromOdd) {
  ParityEvidence even;
  ParityEvidence odd;
  for (unsigned v = 0; v < 256; ++v) {
    const bool even_ones = std::popcount(v) % 2 == 0;
    // Even parity: the parity bit is 0 (read as a space stop bit) when the ones are even.
    even.add(static_cast<std::uint8_t>(v), even_ones);
    odd.add(static_cast<std::uint8_t>(v), !even_ones);
  }
  EXPECT_EQ(even.verdict(), Parity::Even);
  EXPECT_EQ(odd.verdict(), Parity::Odd);
}

TEST(ParityEvidence, ErrorsThatFollowNoParityTellNothing) {
  ParityEvidence e;
  for (unsigned v = 0; v < 256; ++v) e.add(static_cast<std::uint8_t>(v), v % 2 == 0);
  EXPECT_EQ(e.verdict(), std::nullopt);
  ParityEvidence clean;
  for (unsigned v = 0; v < 256; ++v) clean.add(static_cast<std::uint8_t>(v), false);
  EXPECT_EQ(clean.verdict(), std::nullopt);
}

}  // namespace
}  // namespace pvtap
