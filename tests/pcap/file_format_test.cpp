// file_format_of: a file's format from its first bytes.
#include "pvtap/pcap/file_format.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <string_view>
#include <vector>

namespace pvtap {
namespace {

FileFormat of(std::string_view text) {
  const std::vector<std::uint8_t> bytes(text.begin(), text.end());
  return file_format_of(bytes);
}

TEST(FileFormat, CapturesInEitherByteOrderAndPrecision) {
  EXPECT_EQ(of("\xd4\xc3\xb2\xa1\x02\x00"), FileFormat::Pcap);
  EXPECT_EQ(of("\xa1\xb2\xc3\xd4\x00\x02"), FileFormat::Pcap);
  EXPECT_EQ(of("\x4d\x3c\xb2\xa1\x02\x00"), FileFormat::Pcap);
  EXPECT_EQ(of("\xa1\xb2\x3c\x4d\x00\x02"), FileFormat::Pcap);
  EXPECT_EQ(of("\x0a\x0d\x0d\x0a\x1c\x00"), FileFormat::Pcapng);
}

TEST(FileFormat, ASigrokSessionIsAZipAndAVcdOpensWithAKeyword) {
  EXPECT_EQ(of("PK\x03\x04\x14\x00"), FileFormat::Zip);
  EXPECT_EQ(of("$date today $end"), FileFormat::Vcd);
  EXPECT_EQ(of("\n  $timescale 1 us"), FileFormat::Vcd);
}

TEST(FileFormat, OtherTextAndBinaryAreNeither) {
  EXPECT_EQ(of("logic,logic,logic\n"), FileFormat::Text);
  EXPECT_EQ(of("<html>"), FileFormat::Text);
  EXPECT_EQ(of("\x01\x03\x00\x00\x00\x0a\xc5\xcd"), FileFormat::Unknown);
  EXPECT_EQ(of(""), FileFormat::Unknown);
  EXPECT_EQ(file_format_of(std::string("/nonexistent/pvtap-file")), FileFormat::Unreadable);
}

}  // namespace
}  // namespace pvtap
