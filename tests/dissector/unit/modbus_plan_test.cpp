// The plan of plain Modbus frames: coil bits placed by their request, corrected places of the
// fields the core's layout leaves out, and the Info column's detail.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "hex_bytes.h"
#include "plan_support.h"
#include "pvtap/codec/checksums.h"

namespace pvtap::dissector::test {
namespace {

using pvtap::test::hex_bytes;

// A frame of station 20 with its body as on the wire, and its CRC.
std::vector<std::uint8_t> modbus(std::uint8_t function, const std::string& body) {
  const std::vector<std::uint8_t> data = hex_bytes(body);
  std::vector<std::uint8_t> bytes;
  bytes.push_back(20);
  bytes.push_back(function);
  for (const std::uint8_t b : data) bytes.push_back(b);
  const std::uint16_t crc = Crc16Modbus::compute(bytes);
  bytes.push_back(static_cast<std::uint8_t>(crc & 0xFF));
  bytes.push_back(static_cast<std::uint8_t>(crc >> 8));
  return bytes;
}

TEST(ModbusPlan, CoilsOfAReplyArePlacedByItsRequest) {
  Planner p;
  const auto request = modbus(0x01, "00 11 00 11");
  const auto reply = modbus(0x01, "03 CD 6B 01");
  FrameRecord q = request_record(request, Dialect::Modbus, 1);
  FrameRecord r = record_of(Dialect::Modbus, Role::Response, 2);
  r.placed_by = &q;
  const FramePlan plan = p.plan(reply, r);
  ASSERT_EQ(plan.modbus.bit_count, 17u);
  EXPECT_TRUE(plan.modbus.bits_placed);
  EXPECT_EQ(plan.modbus.bits[0].address, 17);
  EXPECT_TRUE(plan.modbus.bits[0].on);
  EXPECT_FALSE(plan.modbus.bits[1].on);
  EXPECT_EQ(plan.modbus.bits[16].address, 33);
  EXPECT_EQ(plan.modbus.bits[16].span.offset, 5);  // the third data byte
  EXPECT_STREQ(plan.summary, "read coils response, station 20: 17 coils from 17");
}

TEST(ModbusPlan, ReadWriteRequestWordsLieAfterTheWritePart) {
  Planner p;
  const auto bytes = modbus(0x17, "00 03 00 06 00 0E 00 03 06 00 FF 00 FE 00 FD");
  const FramePlan plan = p.plan(bytes, record_of(Dialect::Modbus, Role::Request, 1));
  EXPECT_EQ(plan.layout.byte_count.offset, 10);
  EXPECT_EQ(plan.layout.words.offset, 11);
  ASSERT_EQ(plan.value_count, 3u);
  EXPECT_EQ(plan.values[0].span.offset, 11);
}

TEST(ModbusPlan, ExceptionShowsTheModbusText) {
  Planner p;
  Frame f = make_frame(Dialect::Modbus, Role::Response, 20, 0x83);
  f.exception_code = 2;
  const FramePlan plan = p.plan(wire(f), record_of(Dialect::Modbus, Role::Response, 1));
  EXPECT_NE(std::string(plan.summary).find("illegal data address"), std::string::npos);
}

TEST(ModbusPlan, NoBitsFromAFrameWithABadCheck) {
  Planner p;
  auto reply = modbus(0x01, "01 05");
  FrameRecord r = record_of(Dialect::Modbus, Role::Response, 2);
  r.values_trusted = false;
  r.check_ok = false;
  const FramePlan plan = p.plan(reply, r);
  EXPECT_EQ(plan.modbus.bit_count, 0u);
  EXPECT_EQ(plan.modbus.detail, nullptr);
}

}  // namespace
}  // namespace pvtap::dissector::test
