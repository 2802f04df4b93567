// Which noise is filed with the ASCII dialect: a damaged ASCII frame, not RTU bytes.
#include "pvtap/codec/noise_resemblance.h"

#include <gtest/gtest.h>

#include "hex_bytes.h"

namespace pvtap {
namespace {

using test::hex_bytes;

TEST(NoiseResemblance, ADamagedAsciiRequestResemblesAscii) {
  // ENQ " 3R000404" ... EOT with one damaged byte (0x20 for the station's first digit).
  EXPECT_TRUE(resembles_ascii_frame(hex_bytes("05 20 33 52 30 30 30 34 30 34 30 31 64 64 04")));
  EXPECT_TRUE(resembles_ascii_frame(hex_bytes("06 30 31 52 30 30 DC 30 38 30 31 65 33 04")))
      << "one byte that no ASCII frame carries is damage, not a different dialect";
}

TEST(NoiseResemblance, RtuBytesAndLineNoiseDoNot) {
  EXPECT_FALSE(resembles_ascii_frame(hex_bytes("EA C0 B0 EA C9 E3 A4 D7 E0 E8")));
  EXPECT_FALSE(resembles_ascii_frame(hex_bytes("05 03 10 00 00 24 C4 1A")))
      << "an RTU frame to station 5 starts with 0x05 too";
  EXPECT_FALSE(resembles_ascii_frame(hex_bytes("05")));
  EXPECT_FALSE(resembles_ascii_frame({}));
}

}  // namespace
}  // namespace pvtap
