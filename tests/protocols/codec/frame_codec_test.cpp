// Round trip of every frame kind of every dialect: encode, probe, parse gives the same frame.
#include "pvtap/codec/frame_codec.h"

#include <gtest/gtest.h>

#include "frame_builders.h"

#include "pvtap/codec/function_codes.h"
#include "pvtap/framing/framing_probe.h"

namespace pvtap {
namespace {

WordList ramp(std::size_t n, std::uint16_t from = 100) {
  WordList w;
  for (std::size_t i = 0; i < n; ++i) w.push_back(static_cast<std::uint16_t>(from + 7 * i));
  return w;
}

std::vector<Frame> every_kind() {
  std::vector<Frame> v;
  auto ascii_req = test::frame_of(Dialect::Ascii, Role::Request, 0x1F, 'R');
  ascii_req.start = 0x0060;
  ascii_req.count = 8;
  v.push_back(ascii_req);
  auto ascii_rep = test::frame_of(Dialect::Ascii, Role::Response, 0x1F, 'R');
  ascii_rep.start = 0x0060;
  ascii_rep.words = ramp(8, 0xFFF0);
  v.push_back(ascii_rep);
  for (int f : {0x11, 0x12, 0x16, 0x17, 0x1F}) {
    auto req = test::frame_of(Dialect::Hybrid, Role::Request, 6, f);
    req.start = 0x1000;
    req.count = 0x24;
    v.push_back(req);
  }
  for (int f : {0x11, 0x12, 0x16, 0x17}) {
    auto rep = test::frame_of(Dialect::Hybrid, Role::Response, 6, f);
    rep.byte_count = static_cast<std::uint8_t>(4 + 2 * 0x24);
    rep.device = DeviceNumber{0x32, 0xABCDEF};
    rep.words = ramp(0x24);
    v.push_back(rep);
  }
  auto write = test::frame_of(Dialect::Hybrid, Role::Request, 6, 0x18);
  write.start = 0x102A;
  write.words = {0x093C};
  v.push_back(write);
  auto echo = test::frame_of(Dialect::Hybrid, Role::Response, 6, 0x18);
  echo.byte_count = 8;
  echo.device = DeviceNumber{0x31, 103};
  echo.start = 0x102A;
  echo.words = {0x093C};
  v.push_back(echo);
  for (int f : {0x1F, 0xFF}) {
    auto rep = test::frame_of(Dialect::Hybrid, Role::Response, 6, f);
    rep.byte_count = 8;
    rep.device = DeviceNumber{0x31, 103};
    rep.start = f == 0xFF ? 0x1000 : 0x1024;
    rep.count = f == 0xFF ? 0x00FF : 0x007B;
    v.push_back(rep);
  }
  for (int f : {0x03, 0x04}) {
    auto req = test::frame_of(Dialect::Gsl, Role::Request, 247, f);
    req.start = 0x041A;
    req.count = 51;
    v.push_back(req);
    auto rep = test::frame_of(Dialect::Gsl, Role::Response, 247, f);
    rep.byte_count = 102;
    rep.words = ramp(51);
    v.push_back(rep);
  }
  auto w6 = test::frame_of(Dialect::Gsl, Role::Request, 1, 0x06);
  w6.start = 2010;
  w6.words = {0x5555};
  v.push_back(w6);
  auto w6_echo = w6;
  w6_echo.role = Role::Response;
  v.push_back(w6_echo);
  auto w16 = test::frame_of(Dialect::Gsl, Role::Request, 1, 0x10);
  w16.start = 1500;
  w16.count = 6;
  w16.byte_count = 12;
  w16.words = {13, 45, 0, 2026, 11, 22};
  v.push_back(w16);
  auto w16_rep = test::frame_of(Dialect::Gsl, Role::Response, 1, 0x10);
  w16_rep.start = 1500;
  w16_rep.count = 6;
  v.push_back(w16_rep);
  for (int f : {0x83, 0x84, 0x86, 0x90}) {
    auto ex = test::frame_of(Dialect::Gsl, Role::Response, 1, f);
    ex.exception_code = 0x02;
    v.push_back(ex);
  }
  return v;
}

TEST(FrameCodec, EveryKindRoundTrips) {
  for (const Frame& f : every_kind()) {
    SCOPED_TRACE(std::string(to_string(f.dialect)) + " fc " + std::to_string(f.function) + " " +
                 std::string(to_string(f.role)));
    const auto wire = encode_frame(f);
    ASSERT_FALSE(wire.empty());
    EXPECT_TRUE(verify_check(wire, f.dialect).ok);
    const auto back = parse_frame(wire, f.dialect, f.role);
    ASSERT_TRUE(back) << back.diagnostics();
    EXPECT_EQ(back.value(), f);
  }
}

TEST(FrameCodec, ProbeFindsEveryKindWithItsRole) {
  for (const Frame& f : every_kind()) {
    SCOPED_TRACE(std::string(to_string(f.dialect)) + " fc " + std::to_string(f.function));
    const auto wire = encode_frame(f);
    const RoleHint hint = f.role == Role::Request ? RoleHint::Request : RoleHint::Response;
    const auto hinted = probe_frame(wire, hint);
    ASSERT_EQ(hinted.status, ProbeResult::Status::Complete);
    EXPECT_EQ(hinted.length, wire.size());
    EXPECT_EQ(hinted.role, f.role);
    EXPECT_EQ(hinted.dialect, f.dialect);
    const auto unknown = probe_frame(wire);
    ASSERT_EQ(unknown.status, ProbeResult::Status::Complete);
    EXPECT_EQ(unknown.length, wire.size());
    EXPECT_TRUE(unknown.check.ok);
    // A GSL 0x06 echo is byte-identical to its request; only the order tells them apart.
    if (f.function != fc::kGslWriteSingle) {
      EXPECT_EQ(unknown.role, f.role);
    }
  }
}

TEST(FrameCodec, EncoderRejectsFieldsThatDoNotFitTheKind) {
  auto no_start = test::frame_of(Dialect::Gsl, Role::Request, 1, 0x03);
  no_start.count = 1;
  EXPECT_TRUE(encode_frame(no_start).empty());
  auto wrong_dialect = test::frame_of(Dialect::Gsl, Role::Request, 1, 0x12);
  wrong_dialect.start = 0x1000;
  wrong_dialect.count = 1;
  EXPECT_TRUE(encode_frame(wrong_dialect).empty());
  auto exception_request = test::frame_of(Dialect::Gsl, Role::Request, 1, 0x83);
  exception_request.exception_code = 1;
  EXPECT_TRUE(encode_frame(exception_request).empty());
}

TEST(FrameCodec, ParserRejectsLengthThatDisagreesWithByteCount) {
  auto rep = test::frame_of(Dialect::Gsl, Role::Response, 1, 0x03);
  rep.byte_count = 4;
  rep.words = {1, 2};
  auto wire = encode_frame(rep);
  wire.insert(wire.end() - 2, 0x00);
  EXPECT_FALSE(parse_frame(wire, Dialect::Gsl, Role::Response));
}

TEST(FrameCodec, ProbeRejectsImplausibleHeaders) {
  // Address 0, unknown function, GSL address above 247, zero-count read.
  EXPECT_EQ(probe_frame(std::vector<std::uint8_t>{0x00, 0x03, 0, 0, 0, 1, 0, 0}).status,
            ProbeResult::Status::NoFrame);
  EXPECT_EQ(probe_frame(std::vector<std::uint8_t>{0x01, 0x05, 0, 0, 0, 1, 0, 0}).status,
            ProbeResult::Status::NoFrame);
  EXPECT_EQ(probe_frame(std::vector<std::uint8_t>{0xF8, 0x03, 0, 0, 0, 1, 0, 0}).status,
            ProbeResult::Status::NoFrame);
  EXPECT_EQ(probe_frame(std::vector<std::uint8_t>{0x01, 0x03, 0, 0, 0, 0, 0, 0}, RoleHint::Request)
                .status,
            ProbeResult::Status::NoFrame);
}

TEST(FrameCodec, DialectSetExcludesOtherDialects) {
  auto req = test::frame_of(Dialect::Hybrid, Role::Request, 6, 0x12);
  req.start = 0x1000;
  req.count = 0x24;
  const auto wire = encode_frame(req);
  EXPECT_EQ(probe_frame(wire, RoleHint::Unknown, DialectSet::only(Dialect::Gsl)).status,
            ProbeResult::Status::NoFrame);
  EXPECT_EQ(probe_frame(wire, RoleHint::Unknown, DialectSet::only(Dialect::Hybrid)).status,
            ProbeResult::Status::Complete);
}

}  // namespace
}  // namespace pvtap
