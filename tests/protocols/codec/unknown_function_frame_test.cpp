// RTU-shaped noise with a good CRC and a function code no dialect defines.
#include "pvtap/codec/unknown_function_frame.h"

#include <gtest/gtest.h>

#include "hex_bytes.h"
#include "pvtap/codec/checksums.h"

namespace pvtap {
namespace {

using test::hex_bytes;

std::vector<std::uint8_t> with_crc(std::vector<std::uint8_t> body) {
  const std::uint16_t crc = Crc16Modbus::compute(body);
  body.push_back(static_cast<std::uint8_t>(crc & 0xFF));
  body.push_back(static_cast<std::uint8_t>(crc >> 8));
  return body;
}

TEST(UnknownFunctionFrame, UserDefinedFunctionFrameIsRecognized) {
  const auto found = unknown_function_frame(with_crc(hex_bytes("11 41 00 13 00 25")));
  ASSERT_TRUE(found.has_value());
  EXPECT_EQ(found->station, 0x11);
  EXPECT_EQ(found->function, 0x41);
}

TEST(UnknownFunctionFrame, KnownFunctionCodesAreNotUnknown) {
  EXPECT_FALSE(unknown_function_frame(hex_bytes("01 03 00 00 00 0A C5 CD")));
  EXPECT_FALSE(unknown_function_frame(with_crc(hex_bytes("06 12 10 00 00 24"))));
  // Read coils has a length rule of its own since the modbus dialect.
  EXPECT_FALSE(unknown_function_frame(with_crc(hex_bytes("11 01 00 13 00 25"))));
}

TEST(UnknownFunctionFrame, BadCrcOrImpossibleStationIsNoise) {
  auto frame = with_crc(hex_bytes("11 41 00 13 00 25"));
  frame.back() ^= 0x01;
  EXPECT_FALSE(unknown_function_frame(frame));
  EXPECT_FALSE(unknown_function_frame(with_crc(hex_bytes("00 41 00 13 00 25"))));
  EXPECT_FALSE(unknown_function_frame(with_crc(hex_bytes("F8 41 00 13 00 25"))));
  EXPECT_FALSE(unknown_function_frame(hex_bytes("11 41 00")));
}

}  // namespace
}  // namespace pvtap
