#include "pvtap/codec/checksums.h"

#include <gtest/gtest.h>

#include <random>
#include <string_view>
#include <vector>

#include "hex_bytes.h"

namespace pvtap {
namespace {

std::uint16_t bitwise_crc(const std::vector<std::uint8_t>& bytes) {
  std::uint16_t crc = 0xFFFF;
  for (auto b : bytes) {
    crc ^= b;
    for (int i = 0; i < 8; ++i)
      crc = (crc & 1) ? static_cast<std::uint16_t>((crc >> 1) ^ 0xA001)
                      : static_cast<std::uint16_t>(crc >> 1);
  }
  return crc;
}

TEST(Crc16Modbus, CheckValueOf123456789) {
  constexpr std::string_view text = "123456789";
  const std::vector<std::uint8_t> bytes(text.begin(), text.end());
  EXPECT_EQ(Crc16Modbus::compute(bytes), 0x4B37);
}

TEST(Crc16Modbus, StandardModbusVector) {
  // 01 03 00 00 00 0A is sent with C5 CD (low byte first).
  EXPECT_EQ(Crc16Modbus::compute(test::hex_bytes("01 03 00 00 00 0A")), 0xCDC5);
}

TEST(Crc16Modbus, SlicedTablesAgreeWithBitwiseDefinitionForEveryLength) {
  std::mt19937 rng(7);
  for (std::size_t length = 0; length < 300; ++length) {
    std::vector<std::uint8_t> bytes(length);
    for (auto& b : bytes) b = static_cast<std::uint8_t>(rng());
    ASSERT_EQ(Crc16Modbus::compute(bytes), bitwise_crc(bytes)) << "length " << length;
  }
}

TEST(Crc16Modbus, UpdateInPiecesEqualsWhole) {
  const auto bytes = test::hex_bytes("09 11 08 22 00 00 6B 22 00 00 6B 55 66 77 88 99 AA");
  const auto whole = Crc16Modbus::compute(bytes);
  for (std::size_t cut = 0; cut <= bytes.size(); ++cut) {
    std::span<const std::uint8_t> all(bytes);
    auto crc = Crc16Modbus::update(Crc16Modbus::kInit, all.first(cut));
    EXPECT_EQ(Crc16Modbus::update(crc, all.subspan(cut)), whole);
  }
}

TEST(AsciiChecksum, SeedExampleRequest) {
  // station "01", 'R', address "0004", count "04" -> 0x01DB
  EXPECT_EQ(AsciiChecksum::compute(test::hex_bytes("30 31 52 30 30 30 34 30 34")), 0x01DB);
}

TEST(AsciiChecksum, TruncatesTo16Bits) {
  std::vector<std::uint8_t> bytes(300, 0xFF);  // 300 * 255 = 76500 = 0x12AD4
  EXPECT_EQ(AsciiChecksum::compute(bytes), 0x2AD4);
}

}  // namespace
}  // namespace pvtap
