#include "pvtap/carriers/solarman_v5_frame.h"

#include <gtest/gtest.h>

#include "hex_bytes.h"
#include "pvtap/codec/checksums.h"

namespace pvtap::solarman_v5 {
namespace {

using test::hex_bytes;

// A request as pysolarmanv5's protocol notes lay it out: header (length 0x17, control
// 0x4510, sequence 2C 00, logger serial 2712345678 little endian), frame type 2, sensor type
// 0, three zero times, the RTU frame 01 03 00 00 00 0A C5 CD; the checksum 0xF0 was summed
// by hand from the length to the payload's end (the start byte is not in the sum).
const char* kWorkedRequest =
    "A5 17 00 10 45 2C 00 4E 1C AB A1 02 00 00 00 00 00 00 00 00 00 00 00 00 00 00 "
    "01 03 00 00 00 0A C5 CD F0 15";

TEST(SolarmanV5Frame, WorkedRequestParses) {
  const auto bytes = hex_bytes(kWorkedRequest);
  const Frame f = parse_frame(bytes);
  EXPECT_EQ(f.header.length, 0x17);
  EXPECT_EQ(f.header.control, control::kRequest);
  EXPECT_EQ(f.header.sequence, 0x002C);
  EXPECT_EQ(f.header.serial, 2712345678u);
  EXPECT_EQ(f.kind, FrameKind::Request);
  EXPECT_EQ(f.checksum, 0xF0);
  EXPECT_TRUE(f.checksum_ok());
  EXPECT_EQ(f.frame_type, 2);
  EXPECT_EQ(test::hex_text({f.rtu().begin(), f.rtu().end()}), "01 03 00 00 00 0A C5 CD");
  EXPECT_EQ(f.quirk_bytes, 0u);
  EXPECT_EQ(f.carrier_bytes(), bytes.size() - 8);
}

TEST(SolarmanV5Frame, EncodingReproducesTheWorkedRequest) {
  const auto rtu = hex_bytes("01 03 00 00 00 0A C5 CD");
  const auto bytes =
      encode_frame(Header{0, control::kRequest, 0x002C, 2712345678u}, request_payload(rtu));
  EXPECT_EQ(test::hex_text(bytes), kWorkedRequest);
}

TEST(SolarmanV5Frame, ChecksumLeavesOutTheStartByte) {
  auto bytes = hex_bytes(kWorkedRequest);
  bytes[0] = 0x00;  // not summed: the checksum still holds
  EXPECT_EQ(checksum_of(bytes), 0xF0);
  bytes[1] = 0x18;  // summed
  EXPECT_EQ(checksum_of(bytes), 0xF1);
}

TEST(SolarmanV5Frame, ResponseWithTheTwoExtraZerosIsTheQuirk) {
  const auto rtu = hex_bytes("01 03 02 00 2A 39 9B");
  const auto bytes =
      encode_frame(Header{0, control::kResponse, 0x012C, 7}, response_payload(rtu, true));
  const Frame f = parse_frame(bytes);
  EXPECT_EQ(f.kind, FrameKind::Response);
  EXPECT_EQ(f.status, 1);
  EXPECT_EQ(f.quirk_bytes, kQuirkSize);
  EXPECT_EQ(test::hex_text({f.rtu().begin(), f.rtu().end()}), "01 03 02 00 2A 39 9B");
  EXPECT_EQ(f.carrier_bytes() + f.rtu_length + f.quirk_bytes, bytes.size());
}

TEST(SolarmanV5Frame, AReplyDamagedOnTheLineKeepsItsQuirkApart) {
  // 01 03 02 00 2A 39 9B with a data byte hit: no CRC holds, its byte count says 7 bytes.
  const auto rtu = hex_bytes("01 03 02 10 2A 39 9B");
  const Frame f =
      parse_frame(encode_frame(Header{0, control::kResponse, 1, 7}, response_payload(rtu, true)));
  EXPECT_EQ(f.quirk_bytes, kQuirkSize);
  EXPECT_EQ(f.rtu_length, rtu.size());
}

TEST(SolarmanV5Frame, AReplyWhoseCountWasHitKeepsItsQuirkApart) {
  // The byte count hit (0x02 -> 0x18): no reading ends at either length; the zeros are the
  // quirk, not a CRC of 00 00.
  const auto rtu = hex_bytes("01 03 18 00 2A 39 9B");
  const Frame f =
      parse_frame(encode_frame(Header{0, control::kResponse, 1, 7}, response_payload(rtu, true)));
  EXPECT_EQ(f.quirk_bytes, kQuirkSize);
}

TEST(SolarmanV5Frame, ADamagedReplyWhoseStructureEndsWithTheZerosKeepsThem) {
  // A byte count of 4: seven bytes of data and CRC follow, the last two of them zero.
  const auto rtu = hex_bytes("01 03 04 00 2A 39 9B 00 00");
  const Frame f =
      parse_frame(encode_frame(Header{0, control::kResponse, 1, 7}, response_payload(rtu, false)));
  EXPECT_EQ(f.quirk_bytes, 0u);
  EXPECT_EQ(f.rtu_length, rtu.size());
}

TEST(SolarmanV5Frame, AReplyWhoseOwnCrcIsZeroKeepsItByItsByteCount) {
  // Found in a long capture: a reply whose CRC is 00 00, so that its bytes before the CRC
  // hold a CRC of their own. Its byte count says the zeros are its own.
  std::vector<std::uint8_t> rtu = hex_bytes("01 03 04 00 00 00 00");
  for (std::uint32_t v = 0; v <= 0xFFFF; ++v) {
    rtu[5] = static_cast<std::uint8_t>(v >> 8);
    rtu[6] = static_cast<std::uint8_t>(v & 0xFF);
    if (Crc16Modbus::compute(rtu) == 0) break;
  }
  ASSERT_EQ(Crc16Modbus::compute(rtu), 0);  // data whose CRC holds inside the data
  rtu.push_back(0);
  rtu.push_back(0);
  ASSERT_EQ(Crc16Modbus::compute(rtu), 0);  // and the CRC of all of it is 00 00
  const Frame f =
      parse_frame(encode_frame(Header{0, control::kResponse, 1, 7}, response_payload(rtu, false)));
  EXPECT_EQ(f.quirk_bytes, 0u);
  EXPECT_EQ(f.rtu_length, rtu.size());
}

TEST(SolarmanV5Frame, ZerosThatAreTheRtuFramesOwnAreNoQuirk) {
  // A reply whose last data word is zero: the CRC covers it, so nothing is stripped.
  const auto rtu = hex_bytes("01 03 02 00 00 B8 44");
  const Frame f =
      parse_frame(encode_frame(Header{0, control::kResponse, 1, 7}, response_payload(rtu, false)));
  EXPECT_EQ(f.quirk_bytes, 0u);
  EXPECT_EQ(f.rtu_length, rtu.size());
}

TEST(SolarmanV5Frame, StickFramesAndTheirRepliesAreKnown) {
  EXPECT_EQ(kind_of(control::kHeartbeat), FrameKind::StickFrame);
  EXPECT_EQ(kind_of(control::kDataReport), FrameKind::StickFrame);
  EXPECT_EQ(kind_of(0x1710), FrameKind::StickReply);
  EXPECT_EQ(kind_of(0x1210), FrameKind::StickReply);
  EXPECT_EQ(kind_of(0x4610), FrameKind::Other);
  // A heartbeat as the notes show one: payload one zero byte.
  const Frame hb = parse_frame(hex_bytes("A5 01 00 10 47 05 01 4E 1C AB A1 00 14 15"));
  EXPECT_EQ(hb.kind, FrameKind::StickFrame);
  EXPECT_TRUE(hb.checksum_ok());
  EXPECT_EQ(hb.rtu_length, 0u);
  EXPECT_EQ(hb.carrier_bytes(), 14u);
}

TEST(SolarmanV5Frame, APayloadShorterThanItsFixedFieldsIsALengthFinding) {
  const auto bytes = encode_frame(Header{0, control::kResponse, 1, 7}, hex_bytes("02 01 00 00"));
  const Frame f = parse_frame(bytes);
  EXPECT_TRUE(f.payload_short);
  EXPECT_EQ(f.rtu_length, 0u);
}

}  // namespace
}  // namespace pvtap::solarman_v5
