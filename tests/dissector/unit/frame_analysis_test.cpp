// The per-frame plan: what the core makes of a frame's bytes and its record, before any
// Wireshark call.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "frame_builders.h"
#include "hex_bytes.h"
#include "plan_support.h"

namespace pvtap::dissector::test {
namespace {

using pvtap::test::hex_bytes;
using pvtap::test::read_request;

// IDs 1050..1056 of the GSL map (decimal IDs: wire 0x041A..): 230.0 V ... 60.01 Hz.
const std::vector<std::uint16_t> kGslWords = {2300, 2310, 2290, 100, 101, 102, 6001};
constexpr std::uint16_t kGslId1050 = 0x041A;

std::vector<std::uint8_t> gsl_reply(std::uint8_t station, const std::vector<std::uint16_t>& w) {
  Frame f = make_frame(Dialect::Gsl, Role::Response, station, fc::kGslReadHolding);
  f.byte_count = static_cast<std::uint8_t>(2 * w.size());
  for (std::uint16_t word : w) f.words.push_back(word);
  return wire(f);
}

std::vector<std::uint8_t> with_bad_check(std::vector<std::uint8_t> bytes) {
  bytes[bytes.size() - 2] ^= 0xFF;
  return bytes;
}

TEST(FramePlan, ReadRequestHeaderWithItsPlaces) {
  Planner p;
  const auto bytes = wire(read_request(Dialect::Gsl, 1, fc::kGslReadHolding, kGslId1050, 7));
  const FramePlan plan = p.plan(bytes, record_of(Dialect::Gsl, Role::Request, 1));
  ASSERT_TRUE(plan.parsed);
  EXPECT_EQ(plan.station, 1);
  EXPECT_EQ(plan.function, 0x03);
  EXPECT_EQ(plan.start, kGslId1050);
  EXPECT_STREQ(plan.start_text, "0x041A (ID 1050)");
  EXPECT_EQ(plan.count, 7);
  EXPECT_EQ(plan.layout.start.offset, 2);
  EXPECT_EQ(plan.layout.count.offset, 4);
  EXPECT_EQ(plan.layout.check.offset, 6);
  EXPECT_TRUE(plan.check.ok);
  EXPECT_EQ(plan.value_count, 0u);
  EXPECT_STREQ(plan.summary, "read holding registers request, station 1");
}

TEST(FramePlan, GslStartTextFollowsTheIdReading) {
  Planner p;
  p.decoder = RegisterDecoder({GslIdReading::Hex, PairRule::Binary});
  const auto hex_id = wire(read_request(Dialect::Gsl, 1, fc::kGslReadHolding, 0x1050, 1));
  EXPECT_STREQ(p.plan(hex_id, record_of(Dialect::Gsl, Role::Request, 1)).start_text,
               "0x1050 (ID 1050)");
  // A wire address with a hex digit above 9 has no written ID when IDs are read as hex.
  const auto no_id = wire(read_request(Dialect::Gsl, 1, fc::kGslReadHolding, kGslId1050, 1));
  EXPECT_STREQ(p.plan(no_id, record_of(Dialect::Gsl, Role::Request, 1)).start_text, "0x041A");
}

TEST(FramePlan, ReplyValuesArePlacedByTheRequestTheSessionChose) {
  Planner p;
  const auto request = wire(read_request(Dialect::Gsl, 1, fc::kGslReadHolding, kGslId1050, 7));
  FrameRecord asked = request_record(request, Dialect::Gsl, 1);
  FrameRecord reply = record_of(Dialect::Gsl, Role::Response, 2);
  reply.placed_by = &asked;
  const auto bytes = gsl_reply(1, kGslWords);
  const FramePlan plan = p.plan(bytes, reply);
  EXPECT_EQ(plan.decode_status, DecodeStatus::Decoded);
  EXPECT_EQ(plan.decode_note, nullptr);
  ASSERT_EQ(plan.value_count, 7u);
  const PlannedValue& first = plan.values[0];
  ASSERT_NE(first.def, nullptr);
  EXPECT_EQ(first.def->key, "grid_voltage_ab");
  EXPECT_EQ(first.span.offset, 3);
  EXPECT_EQ(first.span.length, 2);
  EXPECT_DOUBLE_EQ(first.number, 230.0);
  EXPECT_EQ(first.raw, 2300u);
  const PlannedValue& last = plan.values[6];
  EXPECT_EQ(last.def->key, "grid_frequency");
  EXPECT_EQ(last.span.offset, 15);
  EXPECT_DOUBLE_EQ(last.number, 60.01);
  EXPECT_STREQ(last.text, "60.01 Hz");
  EXPECT_STREQ(last.label, "grid frequency (1056)");
  EXPECT_STREQ(plan.summary, "read holding registers response, station 1");
}

TEST(FramePlan, ReplyWithoutItsRequestSaysWhyNoValues) {
  Planner p;
  const FramePlan plan =
      p.plan(gsl_reply(1, kGslWords), record_of(Dialect::Gsl, Role::Response, 2));
  EXPECT_EQ(plan.decode_status, DecodeStatus::StartUnknown);
  EXPECT_EQ(plan.value_count, 0u);
  ASSERT_NE(plan.decode_note, nullptr);
  EXPECT_NE(std::string(plan.decode_note), "");
  EXPECT_FALSE(plan.start_assumed);
}

TEST(FramePlan, ValuesOnlyFromATrustedFrameAndOnlyForATree) {
  Planner p;
  const auto request = wire(read_request(Dialect::Gsl, 1, fc::kGslReadHolding, kGslId1050, 7));
  FrameRecord asked = request_record(request, Dialect::Gsl, 1);
  FrameRecord reply = record_of(Dialect::Gsl, Role::Response, 2);
  reply.placed_by = &asked;
  reply.values_trusted = false;  // a bad check, as the session decided
  EXPECT_EQ(p.plan(gsl_reply(1, kGslWords), reply).value_count, 0u);
  reply.values_trusted = true;
  p.with_values = false;  // no tree is built for this packet
  const FramePlan plan = p.plan(gsl_reply(1, kGslWords), reply);
  EXPECT_EQ(plan.value_count, 0u);
  EXPECT_STREQ(plan.summary, "read holding registers response, station 1");
}

TEST(FramePlan, BadCheckInTheSummaryOnlyWhenVerified) {
  Planner p;
  const auto bytes =
      with_bad_check(wire(read_request(Dialect::Gsl, 2, fc::kGslReadHolding, kGslId1050, 2)));
  const FrameRecord record = record_of(Dialect::Gsl, Role::Request, 1);
  const FramePlan checked = p.plan(bytes, record);
  EXPECT_FALSE(checked.check.ok);
  EXPECT_NE(checked.check.found, checked.check.expected);
  EXPECT_STREQ(checked.summary, "read holding registers request, station 2 [bad CRC]");
  p.verify_check = false;
  const FramePlan unchecked = p.plan(bytes, record);
  EXPECT_FALSE(unchecked.check_verified);
  EXPECT_STREQ(unchecked.summary, "read holding registers request, station 2");
}

TEST(FramePlan, ExceptionReply) {
  Planner p;
  Frame f = make_frame(Dialect::Gsl, Role::Response, 1, 0x83);
  f.exception_code = 2;
  const FramePlan plan = p.plan(wire(f), record_of(Dialect::Gsl, Role::Response, 2));
  ASSERT_TRUE(plan.parsed);
  EXPECT_EQ(plan.exception_code, 2);
  EXPECT_TRUE(plan.layout.exception_code.present());
  EXPECT_STREQ(plan.summary,
               "read holding registers exception, station 1: address (ID) out of range");
}

TEST(FramePlan, MalformedFrameKeepsWhatTheBusDecidedItBy) {
  Planner p;
  // A request's bytes read as a reply: its byte count (4) does not fit its length.
  const auto bytes = wire(read_request(Dialect::Gsl, 5, fc::kGslReadHolding, 0x0400, 1));
  FrameRecord record = record_of(Dialect::Gsl, Role::Response, 3);
  record.station = 5;
  record.function = 0x03;
  const FramePlan plan = p.plan(bytes, record);
  EXPECT_FALSE(plan.parsed);
  ASSERT_NE(plan.parse_error, nullptr);
  EXPECT_EQ(std::string(plan.summary).rfind("malformed frame: ", 0), 0u) << plan.summary;
  EXPECT_EQ(plan.station, 5);
  EXPECT_EQ(plan.function, 0x03);
  EXPECT_TRUE(plan.layout.station.present());
  EXPECT_EQ(plan.layout.check.offset, bytes.size() - 2);
}

TEST(FramePlan, HybridReplyHasItsDeviceNumberAndAnAssumedStart) {
  Planner p;
  // PROTOCOLS.md section 5: device information reply of station 9, type 0x22, serial 107.
  const auto bytes = hex_bytes("09 11 08 22 00 00 6B 22 00 00 6B F2 77");
  const FramePlan plan = p.plan(bytes, record_of(Dialect::Hybrid, Role::Response, 2));
  ASSERT_TRUE(plan.parsed);
  EXPECT_EQ(plan.device_type, 0x22);
  EXPECT_EQ(plan.device_serial, 107u);
  EXPECT_EQ(plan.device_raw, 0x2200006Bu);
  ASSERT_NE(plan.device_text, nullptr);
  EXPECT_NE(std::string(plan.device_text), "");
  EXPECT_TRUE(plan.layout.device_type.present());
  EXPECT_TRUE(plan.start_assumed);
  EXPECT_NE(plan.decode_note, nullptr);
}

TEST(FramePlan, AsciiFramesSayChecksum) {
  Planner p;
  p.check_word = "checksum";
  // PROTOCOLS.md section 5: read 2 words from 0x0020 of station 1, last digit changed.
  auto bytes = hex_bytes("05 30 31 52 30 30 32 30 30 32 30 31 64 37 04");
  bytes[13] = '0';
  const FramePlan plan = p.plan(bytes, record_of(Dialect::Ascii, Role::Request, 1));
  EXPECT_STREQ(plan.start_text, "0x0020");
  EXPECT_STREQ(plan.summary, "read request, station 1 [bad checksum]");
}

TEST(FramePlan, WordsNoMapEntryCoversAreLabelledByAddress) {
  Planner p;
  const auto request = wire(read_request(Dialect::Gsl, 1, fc::kGslReadHolding, 0x0F00, 1));
  FrameRecord asked = request_record(request, Dialect::Gsl, 1);
  FrameRecord reply = record_of(Dialect::Gsl, Role::Response, 2);
  reply.placed_by = &asked;
  const FramePlan plan = p.plan(gsl_reply(1, {0x1234}), reply);
  ASSERT_EQ(plan.value_count, 1u);
  EXPECT_EQ(plan.values[0].def, nullptr);
  EXPECT_EQ(plan.values[0].raw, 0x1234u);
  EXPECT_EQ(std::string(plan.values[0].label).rfind("word at ", 0), 0u) << plan.values[0].label;
}

}  // namespace
}  // namespace pvtap::dissector::test
