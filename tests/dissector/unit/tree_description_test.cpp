// The tree description: the items, their places, values, labels and expert infos that the
// plugin adds to Wireshark's tree for a frame or a run of noise.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "fields/register_field_type.h"
#include "frame_builders.h"
#include "hex_bytes.h"
#include "plan_support.h"
#include "pvtap/registers/register_format.h"

namespace pvtap::dissector::test {
namespace {

using pvtap::test::hex_bytes;
using pvtap::test::read_request;
using Lines = std::vector<std::string>;

constexpr std::uint16_t kGslId1050 = 0x041A;

std::vector<std::uint8_t> gsl_reply(std::uint8_t station, const std::vector<std::uint16_t>& w) {
  Frame f = make_frame(Dialect::Gsl, Role::Response, station, fc::kGslReadHolding);
  f.byte_count = static_cast<std::uint8_t>(2 * w.size());
  for (std::uint16_t word : w) f.words.push_back(word);
  return wire(f);
}

// The check item of an RTU frame: its CRC, which goes low byte first.
std::string check_line(const std::vector<std::uint8_t>& bytes) {
  const std::size_t at = bytes.size() - 2;
  const unsigned crc = bytes[at] | unsigned{bytes[at + 1]} << 8;
  return "1 Check [" + std::to_string(at) + "+2] = " + std::to_string(crc);
}

// Describes a frame as the plugin does: plan first, then the description of plan and record.
Lines described(Planner& p, const std::vector<std::uint8_t>& bytes, const FrameRecord& record,
                bool visited = true) {
  const FramePlan plan = p.plan(bytes, record);
  return lines_of(describe_frame(plan, record, p.description(bytes.size(), visited)));
}

// The items of a description from the first that starts with `prefix` on.
Lines from(const Lines& lines, const std::string& prefix) {
  for (auto it = lines.begin(); it != lines.end(); ++it) {
    if (it->rfind(prefix, 0) == 0) return Lines(it, lines.end());
  }
  return {};
}

TEST(TreeDescription, RequestInWireOrder) {
  Planner p;
  const auto bytes = wire(read_request(Dialect::Gsl, 1, fc::kGslReadHolding, kGslId1050, 7));
  FrameRecord record = record_of(Dialect::Gsl, Role::Request, 1);
  FrameRecord reply = record_of(Dialect::Gsl, Role::Response, 2);
  record.response = &reply;
  EXPECT_EQ(described(p, bytes, record),
            (Lines{"0 Protocol [0+8] +\", read holding registers request, station 1\" {frame}",
                   "1 Dialect = 2 (generated)", "1 Role = 0 (generated)", "1 Station [0+1] = 1",
                   "1 Function [1+1] = 3", "1 Start [2+2] = 1050 \"0x041A (ID 1050)\"",
                   "1 Count [4+2] = 7", check_line(bytes), "1 CheckStatus = 1 (generated)",
                   "1 ResponseIn = 2 (generated)"}));
}

TEST(TreeDescription, BadCheckShowsTheExpectedValueAndAnExpertInfo) {
  Planner p;
  auto bytes = wire(read_request(Dialect::Gsl, 2, fc::kGslReadHolding, kGslId1050, 2));
  bytes[6] = 0x34;
  bytes[7] = 0x12;
  const FramePlan plan = p.plan(bytes, record_of(Dialect::Gsl, Role::Request, 1));
  const Lines lines = lines_of(describe_frame(plan, record_of(Dialect::Gsl, Role::Request, 1),
                                              p.description(bytes.size(), false)));
  char expected[64];
  std::snprintf(expected, sizeof expected, "Bad CRC 0x1234, expected 0x%04X",
                static_cast<unsigned>(plan.check.expected));
  EXPECT_EQ(from(lines, "1 Check"),
            (Lines{"1 Check [6+2] = 4660", "1 CheckStatus = 0 (generated)",
                   "1 CheckExpected = " + std::to_string(plan.check.expected) + " (generated)",
                   "  ! BadCheck on #7: " + std::string(expected)}));
  EXPECT_EQ(lines[0],
            "0 Protocol [0+8] +\", read holding registers request, station 2 [bad CRC]\""
            " {frame}");
}

TEST(TreeDescription, UnverifiedCheckHasNoVerdict) {
  Planner p;
  p.verify_check = false;
  auto bytes = wire(read_request(Dialect::Gsl, 2, fc::kGslReadHolding, kGslId1050, 2));
  bytes[6] ^= 0xFF;
  const Lines lines = described(p, bytes, record_of(Dialect::Gsl, Role::Request, 1), false);
  EXPECT_EQ(from(lines, "1 CheckStatus"), (Lines{"1 CheckStatus = 2 (generated)"}));
}

TEST(TreeDescription, ReplyValuesWithTheirLabelsAndTheLinkToTheRequest) {
  Planner p;
  const auto request = wire(read_request(Dialect::Gsl, 1, fc::kGslReadHolding, 1055, 2));
  FrameRecord asked = request_record(request, Dialect::Gsl, 4);
  FrameRecord reply = record_of(Dialect::Gsl, Role::Response, 5);
  reply.placed_by = &asked;
  reply.request = &asked;
  reply.has_latency = true;
  reply.latency = 0.04;
  const auto bytes = gsl_reply(1, {102, 6001});
  const Lines lines = from(described(p, bytes, reply), "1 RegisterValue");
  EXPECT_EQ(lines,
            (Lines{"1 RegisterValue output_current_c [3+2] = 10.2 label \"output current phase C "
                   "(1055): 10.2 A\"",
                   "1 RegisterValue grid_frequency [5+2] = 60.01 label \"grid frequency (1056): "
                   "60.01 Hz\"",
                   check_line(bytes), "1 CheckStatus = 1 (generated)",
                   "1 RequestIn = 4 (generated)", "1 ResponseTime = 0 s 40000000 ns (generated)"}));
}

TEST(TreeDescription, ResponseTimeWithoutALatencyIsTheTimeBetweenThePackets) {
  Planner p;
  FrameRecord asked = record_of(Dialect::Gsl, Role::Request, 4);
  asked.time = {10, 900000000};
  FrameRecord reply = record_of(Dialect::Gsl, Role::Response, 6);
  reply.time = {11, 100000000};
  reply.request = &asked;
  reply.duplicate = true;
  reply.values_trusted = false;
  const Lines lines = described(p, gsl_reply(1, {1}), reply);
  EXPECT_EQ(
      from(lines, "1 ResponseTime"),
      (Lines{"1 ResponseTime = 0 s 200000000 ns (generated)",
             "1 ! Duplicate [0+0]: Duplicate reply: the station answered its request again"}));
  // Before its request (as nstime_delta: both parts of one sign).
  reply.time = {9, 950000000};
  EXPECT_EQ(from(described(p, gsl_reply(1, {1}), reply), "1 ResponseTime")[0],
            "1 ResponseTime = 0 s -950000000 ns (generated)");
  reply.time = {8, 950000000};
  EXPECT_EQ(from(described(p, gsl_reply(1, {1}), reply), "1 ResponseTime")[0],
            "1 ResponseTime = -1 s -950000000 ns (generated)");
}

// The verdict is the announcement's (describe_timeout); a later pass links the request to it.
TEST(TreeDescription, AnUnansweredRequestLinksToItsAnnouncementOnALaterPass) {
  Planner p;
  const auto bytes = wire(read_request(Dialect::Gsl, 3, fc::kGslReadHolding, kGslId1050, 2));
  FrameRecord record = record_of(Dialect::Gsl, Role::Request, 7);
  record.timed_out = true;
  record.timeout_reason = TimeoutReason::NextRequestFirst;
  FrameRecord next = record_of(Dialect::Gsl, Role::Request, 9);
  record.next_request = &next;
  record.announced_in = 9;
  EXPECT_EQ(from(described(p, bytes, record, false), "1 TimeoutIn"), Lines{});
  EXPECT_EQ(
      from(described(p, bytes, record, true), "1 TimeoutIn"),
      (Lines{"1 TimeoutIn = 9 label \"No reply: the master sent its next request to the station "
             "first (frame 9); announced in frame 9\" (generated)"}));
  EXPECT_EQ(from(described(p, bytes, record, true), "1 !"), Lines{})
      << "the verdict is the announcement's: one pass and two show it once";
  record.announced_in = 0;  // not announced (the capture ended first)
  EXPECT_EQ(from(described(p, bytes, record, true), "1 TimeoutIn"), Lines{});
}

TEST(TreeDescription, ATimeoutAnnouncementSaysWhichTimeoutJudgedIt) {
  Planner p;
  p.reply_timeout_ms = 2500;
  FrameRecord record = record_of(Dialect::Gsl, Role::Request, 7);
  record.station = 3;
  record.function = fc::kGslReadHolding;
  record.timed_out = true;
  record.timeout_reason = TimeoutReason::NoReply;
  EXPECT_EQ(lines_of(describe_timeout(record, p.description(0, false))),
            (Lines{"0 Protocol +\", no reply to the request in frame 7\" {frame}",
                   "1 Station = 3 (generated)", "1 UnansweredRequest = 7 (generated)",
                   "  ! Unanswered on #2: Request in frame 7 never answered: no reply within the "
                   "reply timeout (2500 ms)"}));
}

// A write's echo is its normal reply: read as a request and corrected, it is not noted.
TEST(TreeDescription, NormalEchoIsNotNoted) {
  Planner p;
  Frame f = make_frame(Dialect::Gsl, Role::Response, 1, fc::kGslWriteSingle);
  f.start = 1250;
  f.words.push_back(525);
  FrameRecord echo = record_of(Dialect::Gsl, Role::Response, 8);
  echo.function = fc::kGslWriteSingle;
  echo.role_corrected = true;
  EXPECT_EQ(from(described(p, wire(f), echo), "1 !"), Lines{});
}

TEST(TreeDescription, SequenceExpertInfosOfReplies) {
  Planner p;
  FrameRecord reply = record_of(Dialect::Gsl, Role::Response, 8);
  reply.values_trusted = false;
  reply.role_corrected = true;
  reply.unsolicited = true;
  FrameRecord timed_out = record_of(Dialect::Gsl, Role::Request, 3);
  reply.late_for = &timed_out;
  reply.count_mismatch = true;
  reply.count_expected = 76;
  reply.count_found = 68;
  const Lines lines = from(described(p, gsl_reply(1, {1}), reply), "1 !");
  EXPECT_EQ(lines, (Lines{"1 ! RoleCorrected [0+0]: (summary)", "1 ! Unsolicited [0+0]: (summary)",
                          "1 ! LateReply [0+0]: Reply after its request in frame 3 timed out",
                          "1 ExpectedCount = 76 (generated)",
                          "  ! CountMismatch on #11: The request asked for 76 bytes, the reply "
                          "carries 68"}));
}

TEST(TreeDescription, CountedReplyShowsByteCountAndDeviceBeforeTheRest) {
  Planner p;
  // PROTOCOLS.md section 5: device information reply of station 9, without its request.
  const auto bytes = hex_bytes("09 11 08 22 00 00 6B 22 00 00 6B F2 77");
  EXPECT_EQ(described(p, bytes, record_of(Dialect::Hybrid, Role::Response, 2)),
            (Lines{"0 Protocol [0+13] +\", device information response, station 9\" {frame}",
                   "1 Dialect = 1 (generated)", "1 Role = 1 (generated)", "1 Station [0+1] = 9",
                   "1 Function [1+1] = 17", "1 ByteCount [2+1] = 8",
                   "1 Device [3+4] = 570425451 \"22 PWM controller, serial 107\" {device}",
                   "2 DeviceType [3+1] = 34", "2 DeviceSerial [4+3] = 107",
                   "1 RegisterValue device_number [7+4] = 570425451 label \"device number "
                   "(0x1060): 22 PWM controller, serial 107\"",
                   "1 ! StartAssumed [7+4]: decoded; no matching request, so the start address "
                   "is the seed's default for this function code (assumed)",
                   check_line(bytes), "1 CheckStatus = 1 (generated)"}));
}

TEST(TreeDescription, ExceptionReplyRaisesAnExpertInfoOnItsCode) {
  Planner p;
  Frame f = make_frame(Dialect::Gsl, Role::Response, 1, 0x83);
  f.exception_code = 2;
  const Lines lines = described(p, wire(f), record_of(Dialect::Gsl, Role::Response, 2));
  EXPECT_EQ(from(lines, "1 ExceptionCode"),
            (Lines{"1 ExceptionCode [2+1] = 2 \"address (ID) out of range (2)\"",
                   "  ! Exception on #5: Exception reply: address (ID) out of range (code 2)",
                   check_line(wire(f)), "1 CheckStatus = 1 (generated)"}));
}

TEST(TreeDescription, HybridErrorReplyShowsItsFixedBodyAndRaisesAnException) {
  Planner p;
  // PROTOCOLS.md section 2: the error reply of station 6 (device 0x31, serial 103), whose
  // fixed body 0x1000 0x00FF is not a start and a count.
  const auto bytes = hex_bytes("06 FF 08 31 00 00 67 10 00 00 FF F9 CF");
  const Lines lines = described(p, bytes, record_of(Dialect::Hybrid, Role::Response, 2));
  const Lines body = from(lines, "1 ErrorBody");
  ASSERT_GE(body.size(), 2u) << ::testing::PrintToString(lines);
  EXPECT_EQ(body[0], "1 ErrorBody [7+4] = 268435711");
  EXPECT_EQ(body[1].rfind("  ! Exception on #", 0), 0u) << body[1];
  EXPECT_NE(body[1].find("Error reply: the inverter rejected the request (body 0x1000 0x00FF)"),
            std::string::npos)
      << body[1];
  for (const std::string& line : lines) {
    EXPECT_NE(line.rfind("1 Start ", 0), 0u) << line;
    EXPECT_NE(line.rfind("1 Count ", 0), 0u) << line;
  }
}

TEST(TreeDescription, MalformedFrameShowsItsHeaderAndCheck) {
  Planner p;
  const auto bytes = wire(read_request(Dialect::Gsl, 5, fc::kGslReadHolding, 0x0400, 1));
  FrameRecord record = record_of(Dialect::Gsl, Role::Response, 3);
  record.station = 5;
  record.function = 0x03;
  const FramePlan plan = p.plan(bytes, record);
  const Lines lines = lines_of(describe_frame(plan, record, p.description(bytes.size())));
  ASSERT_EQ(lines.size(), 9u) << ::testing::PrintToString(lines);
  EXPECT_EQ(lines[3], "  ! Malformed on #0: Malformed frame: " + std::string(plan.parse_error));
  EXPECT_EQ(lines[4], "1 Station [0+1] = 5");
  EXPECT_EQ(lines[5], "1 Function [1+1] = 3");
  EXPECT_EQ(lines[6], "1 Undecoded [2+4] +\" (4 bytes, not decoded: the frame did not parse)\"");
  EXPECT_EQ(lines[7], check_line(bytes));
  EXPECT_EQ(lines[8], "1 CheckStatus = 1 (generated)");
}

TEST(TreeDescription, ABadCheckReplyShowsItsDataAsNotDecoded) {
  Planner p;
  auto bytes = gsl_reply(1, {0x0102, 0x0304});
  bytes.back() ^= 0xFF;
  FrameRecord reply = record_of(Dialect::Gsl, Role::Response, 2);
  reply.check_ok = false;
  reply.values_trusted = false;
  const Lines lines = described(p, bytes, reply);
  const Lines tail = from(lines, "1 Undecoded");
  ASSERT_EQ(tail.size(), 5u) << ::testing::PrintToString(lines);
  EXPECT_EQ(tail[0], "1 Undecoded [3+4] +\" (4 bytes, not decoded: the CRC failed)\"");
  EXPECT_EQ(tail[1], check_line(bytes)) << "the data comes before the check, as on the wire";
  EXPECT_EQ(tail[4].rfind("  ! BadCheck", 0), 0u) << ::testing::PrintToString(lines);
}

TEST(TreeDescription, BitsRegisterOpensASubtreeOfItsNamedFlags) {
  Planner p;
  p.check_word = "checksum";
  // ASCII: inverter operation and fault (0x0006) with bit 14 "inverter running" set, and
  // bit 2, which has no name.
  Frame f = make_frame(Dialect::Ascii, Role::Response, 1, fc::kAsciiRead);
  f.start = 0x0006;
  f.words = {0x4004};
  const auto request = wire(read_request(Dialect::Ascii, 1, fc::kAsciiRead, 0x0006, 1));
  FrameRecord asked = request_record(request, Dialect::Ascii, 1);
  FrameRecord record = record_of(Dialect::Ascii, Role::Response, 2);
  record.placed_by = &asked;
  // One flag per named bit (0, 1, 3, 5, 7, 8, 14), each over the whole word; the unnamed
  // bit is worth a note on the value's item (item 6).
  EXPECT_EQ(from(described(p, wire(f), record), "1 RegisterValue"),
            (Lines{"1 RegisterValue inverter_status [8+4] = 16388 label \"inverter operation and "
                   "fault (0x0006): bit 2, inverter running\" {flags}",
                   "2 RegisterFlag inverter_status [8+4] = bit 0 of 16388",
                   "2 RegisterFlag inverter_status [8+4] = bit 1 of 16388",
                   "2 RegisterFlag inverter_status [8+4] = bit 3 of 16388",
                   "2 RegisterFlag inverter_status [8+4] = bit 5 of 16388",
                   "2 RegisterFlag inverter_status [8+4] = bit 7 of 16388",
                   "2 RegisterFlag inverter_status [8+4] = bit 8 of 16388",
                   "2 RegisterFlag inverter_status [8+4] = bit 14 of 16388",
                   "  ! ValueNote on #6: inverter operation and fault (0x0006): " +
                       std::string(pvtap::describe(ValueWarning::UnnamedBitSet)),
                   "1 Check [12+4] = 577", "1 CheckStatus = 1 (generated)"}));
}

TEST(TreeDescription, UnmappedWordsSayTheyAreNotInTheMap) {
  Planner p;
  const auto request = wire(read_request(Dialect::Gsl, 1, fc::kGslReadHolding, 0x0F00, 1));
  FrameRecord asked = request_record(request, Dialect::Gsl, 1);
  FrameRecord reply = record_of(Dialect::Gsl, Role::Response, 2);
  reply.placed_by = &asked;
  const FramePlan plan = p.plan(gsl_reply(1, {0x1234}), reply);
  const Lines lines = from(lines_of(describe_frame(plan, reply, p.description(7))), "1 Word");
  ASSERT_FALSE(lines.empty());
  EXPECT_EQ(lines[0], "1 Word [3+2] = 4660 label \"" + std::string(plan.values[0].label) + ": " +
                          plan.values[0].text + " (not in the register map)\"");
}

TEST(TreeDescription, WordsWithoutAStartGetANoteOverAllOfThem) {
  Planner p;
  const Lines lines =
      described(p, gsl_reply(1, {1, 2, 3}), record_of(Dialect::Gsl, Role::Response, 2));
  const Lines notes = from(lines, "1 ! StartUnknown");
  ASSERT_EQ(notes.size(), 3u) << ::testing::PrintToString(lines);
  EXPECT_EQ(notes[0].rfind("1 ! StartUnknown [3+6]: ", 0), 0u) << notes[0];
}

TEST(TreeDescription, NoiseRun) {
  HeapArena heap;
  const DescriptionContext ctx{heap.arena(), 3, true, "CRC"};
  EXPECT_EQ(lines_of(describe_noise(std::nullopt, ctx)),
            (Lines{"0 Protocol [0+3] +\", noise (3 bytes)\" {noise}", "1 Noise [0+3]",
                   "  ! Noise on #1: (summary)"}));
}

TEST(TreeDescription, NoiseThatIsAFrameOfAnUnknownFunction) {
  HeapArena heap;
  const DescriptionContext ctx{heap.arena(), 8, true, "CRC"};
  EXPECT_EQ(lines_of(describe_noise(UnknownFunctionFrame{0x11, 0x01}, ctx)),
            (Lines{"0 Protocol [0+8] +\", noise (8 bytes)\" {noise}", "1 Noise [0+8]",
                   "1 Station [0+1] = 17", "1 UnknownFunction [1+1] = 1",
                   "  ! UnknownFunction on #3: Frame with a good CRC and the unknown function "
                   "code 0x01"}));
}

TEST(TreeDescription, EveryItemIsPlainDataInTheArena) {
  static_assert(std::is_trivially_destructible_v<TreeItem>);
  static_assert(std::is_trivially_copyable_v<TreeDescription>);
  HeapArena heap;
  const TreeDescription d = describe_noise(std::nullopt, {heap.arena(), 1, true, "CRC"});
  EXPECT_EQ(d.count, 3u);
  EXPECT_NE(d.items, nullptr);
}

TEST(RegisterFieldType, FollowsTheKindOfTheEntry) {
  RegisterDef def;
  def.kind = RegisterKind::Number;
  EXPECT_EQ(register_field_type(def), RegisterFieldType::Double);
  def.kind = RegisterKind::BcdYearMonth;
  EXPECT_EQ(register_field_type(def), RegisterFieldType::String);
  def.kind = RegisterKind::Raw;
  EXPECT_EQ(register_field_type(def), RegisterFieldType::Uint16);
  def.words = 2;
  EXPECT_EQ(register_field_type(def), RegisterFieldType::Uint32);
  def.kind = RegisterKind::Enum;
  EXPECT_EQ(register_field_type(def), RegisterFieldType::Uint32);
}

}  // namespace
}  // namespace pvtap::dissector::test
