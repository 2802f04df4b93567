// Every worked example of PROTOCOLS.md section 5, with the verdict the reference gives.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "hex_bytes.h"
#include "pvtap/codec/frame_codec.h"
#include "pvtap/framing/framing_probe.h"

namespace pvtap {
namespace {

struct Vector {
  const char* wire;
  Dialect dialect;
  Role role;
  bool good;
  const char* expected_check;  // wire bytes of the correct check when bad
};

const Vector kVectors[] = {
    {"05 30 31 52 30 30 30 34 30 34 30 31 64 62 04", Dialect::Ascii, Role::Request, true, ""},
    {"05 30 31 52 30 30 32 30 30 32 30 31 64 37 04", Dialect::Ascii, Role::Request, true, ""},
    {"05 30 31 52 30 30 35 30 30 37 30 31 64 66 04", Dialect::Ascii, Role::Request, true, ""},
    {"05 30 31 52 30 30 36 30 30 38 30 31 65 31 04", Dialect::Ascii, Role::Request, true, ""},
    {"05 30 31 52 30 31 65 30 30 33 30 32 30 63 04", Dialect::Ascii, Role::Request, true, ""},
    {"FF 11 10 60 00 02 6D 08", Dialect::Hybrid, Role::Request, true, ""},
    {"06 11 08 31 00 00 67 31 00 00 67 93 3A", Dialect::Hybrid, Role::Response, false, "97 FA"},
    {"09 11 08 22 00 00 6B 22 00 00 6B F2 77", Dialect::Hybrid, Role::Response, true, ""},
    {"06 18 10 2A 09 3C 03 36", Dialect::Hybrid, Role::Request, true, ""},
    {"06 18 08 31 00 00 67 10 2A 09 3C 2A 86", Dialect::Hybrid, Role::Response, false, "2B 8A"},
    {"06 1F 10 24 00 7B 91 57", Dialect::Hybrid, Role::Request, true, ""},
    {"06 1F 08 31 00 00 67 10 24 00 7B BD F1", Dialect::Hybrid, Role::Response, true, ""},
    {"06 FF 08 31 00 00 67 10 00 00 FF F8 C3", Dialect::Hybrid, Role::Response, false, "F9 CF"},
    {"01 03 00 00 00 0A C5 CD", Dialect::Gsl, Role::Request, true, ""},
};

class ReferenceVector : public ::testing::TestWithParam<Vector> {};

void expect_verdict(const Vector& v, const ProbeResult& r, std::size_t size) {
  ASSERT_EQ(r.status, ProbeResult::Status::Complete) << v.wire;
  EXPECT_EQ(r.length, size) << v.wire;
  EXPECT_EQ(r.dialect, v.dialect) << v.wire;
  EXPECT_EQ(r.role, v.role) << v.wire;
  EXPECT_EQ(r.check.ok, v.good) << v.wire;
  if (!v.good) {
    EXPECT_EQ(test::hex_text(check_wire_bytes(v.dialect, r.check.expected)), v.expected_check);
  }
}

TEST_P(ReferenceVector, ProbeWithoutRoleGivesTheReferenceVerdict) {
  const Vector& v = GetParam();
  const auto bytes = test::hex_bytes(v.wire);
  expect_verdict(v, probe_frame(bytes), bytes.size());
}

TEST_P(ReferenceVector, ProbeWithRoleGivesTheReferenceVerdict) {
  const Vector& v = GetParam();
  const auto bytes = test::hex_bytes(v.wire);
  const RoleHint hint = v.role == Role::Request ? RoleHint::Request : RoleHint::Response;
  expect_verdict(v, probe_frame(bytes, hint, DialectSet::only(v.dialect)), bytes.size());
}

TEST_P(ReferenceVector, EveryShorterPrefixAsksForMore) {
  const Vector& v = GetParam();
  const auto bytes = test::hex_bytes(v.wire);
  const RoleHint hint = v.role == Role::Request ? RoleHint::Request : RoleHint::Response;
  for (std::size_t n = 0; n < bytes.size(); ++n) {
    const auto r = probe_frame(std::span(bytes).first(n), hint);
    ASSERT_EQ(r.status, ProbeResult::Status::NeedMore) << v.wire << " prefix " << n;
    EXPECT_GE(r.more, 1u);
    EXPECT_LE(n + r.more, bytes.size()) << "asked past the frame end";
  }
}

TEST_P(ReferenceVector, ParsesAndReEncodesWithACorrectCheck) {
  const Vector& v = GetParam();
  const auto bytes = test::hex_bytes(v.wire);
  const auto parsed = parse_frame(bytes, v.dialect, v.role);
  ASSERT_TRUE(parsed) << v.wire << ": " << parsed.diagnostics();
  auto encoded = encode_frame(parsed.value());
  ASSERT_EQ(encoded.size(), bytes.size());
  // Only the check differs, and only where the reference says it is bad.
  const std::size_t check_len = v.dialect == Dialect::Ascii ? 5 : 2;
  EXPECT_TRUE(
      std::equal(bytes.begin(), bytes.end() - static_cast<long>(check_len), encoded.begin()));
  EXPECT_EQ(encoded == bytes, v.good);
  EXPECT_TRUE(verify_check(encoded, v.dialect).ok);
}

std::string vector_name(const ::testing::TestParamInfo<Vector>& info) {
  std::string name = std::string(to_string(info.param.dialect)) + "_" +
                     std::string(to_string(info.param.role)) + "_" + std::to_string(info.index);
  return name;
}

INSTANTIATE_TEST_SUITE_P(Section5, ReferenceVector, ::testing::ValuesIn(kVectors), vector_name);

TEST(ReferenceVectorFields, HybridDeviceInfoReplyCarriesInverter103) {
  const auto f = parse_frame(test::hex_bytes("06 11 08 31 00 00 67 31 00 00 67 93 3A"),
                             Dialect::Hybrid, Role::Response);
  ASSERT_TRUE(f);
  EXPECT_EQ(f->station, 6);
  EXPECT_EQ(f->byte_count, 8);
  ASSERT_TRUE(f->device);
  EXPECT_EQ(f->device->type_code, 0x31);
  EXPECT_EQ(f->device->serial, 103u);
  EXPECT_EQ(f->words, (WordList{0x3100, 0x0067}));
}

TEST(ReferenceVectorFields, HybridWriteAndEcho) {
  const auto req =
      parse_frame(test::hex_bytes("06 18 10 2A 09 3C 03 36"), Dialect::Hybrid, Role::Request);
  ASSERT_TRUE(req);
  EXPECT_EQ(req->start, 0x102A);
  EXPECT_EQ(req->words, (WordList{0x093C}));
  const auto echo = parse_frame(test::hex_bytes("06 18 08 31 00 00 67 10 2A 09 3C 2A 86"),
                                Dialect::Hybrid, Role::Response);
  ASSERT_TRUE(echo);
  EXPECT_EQ(echo->start, 0x102A);
  EXPECT_EQ(echo->words, (WordList{0x093C}));
  EXPECT_EQ(echo->device->serial, 103u);
}

TEST(ReferenceVectorFields, HybridErrorReply) {
  const auto f = parse_frame(test::hex_bytes("06 FF 08 31 00 00 67 10 00 00 FF F8 C3"),
                             Dialect::Hybrid, Role::Response);
  ASSERT_TRUE(f);
  EXPECT_EQ(f->start, 0x1000);
  EXPECT_EQ(f->count, 0x00FF);
}

TEST(ReferenceVectorFields, AsciiRequestFields) {
  const auto f = parse_frame(test::hex_bytes("05 30 31 52 30 31 65 30 30 33 30 32 30 63 04"),
                             Dialect::Ascii, Role::Request);
  ASSERT_TRUE(f);
  EXPECT_EQ(f->station, 1);
  EXPECT_EQ(f->start, 0x01E0);
  EXPECT_EQ(f->count, 3);
}

// The seed gives only the data words of the replies; build them with the framing rules.
TEST(ReferenceVectorFields, AsciiRepliesFromSeedWordsRoundTrip) {
  const std::vector<std::pair<std::uint16_t, WordList>> replies = {
      {0x0004, {0x0008, 0x40A2, 0x0021, 0x0000}},
      {0x0020, {266, 57}},
      {0x0050, {217, 0, 0, 65, 0, 0, 601}},
      {0x0060, {2724, 57, 230, 2518, 2980, 998, 11340, 0}},
      {0x01E0, {0x1030, 0x0510, 0x0001}},
  };
  for (const auto& [start, words] : replies) {
    Frame f;
    f.dialect = Dialect::Ascii;
    f.role = Role::Response;
    f.station = 1;
    f.function = 'R';
    f.start = start;
    f.words = words;
    const auto wire = encode_frame(f);
    ASSERT_EQ(wire.size(), 13 + 4 * words.size());
    EXPECT_EQ(wire.front(), 0x06);
    EXPECT_EQ(wire.back(), 0x04);
    const auto probe = probe_frame(wire);
    EXPECT_EQ(probe.status, ProbeResult::Status::Complete);
    EXPECT_EQ(probe.length, wire.size());
    EXPECT_TRUE(probe.check.ok);
    const auto back = parse_frame(wire, Dialect::Ascii, Role::Response);
    ASSERT_TRUE(back);
    EXPECT_EQ(back.value(), f);
  }
}

TEST(ReferenceVectorFields, AsciiChecksumAcceptsUppercaseHex) {
  // Same request as the first vector with "DB" instead of "db".
  const auto bytes = test::hex_bytes("05 30 31 52 30 30 30 34 30 34 30 31 44 42 04");
  EXPECT_TRUE(verify_check(bytes, Dialect::Ascii).ok);
}

TEST(ReferenceVectorFields, AsciiNonHexFieldIsMalformed) {
  auto bytes = test::hex_bytes("05 30 31 52 30 30 30 34 30 34 30 31 64 62 04");
  bytes[5] = 'g';
  EXPECT_FALSE(parse_frame(bytes, Dialect::Ascii, Role::Request));
  EXPECT_EQ(probe_frame(bytes).status, ProbeResult::Status::NoFrame);
}

}  // namespace
}  // namespace pvtap
