// Byte ranges of the fields of every frame shape, checked against the reference's vectors.
#include "pvtap/codec/frame_layout.h"

#include <gtest/gtest.h>

#include "hex_bytes.h"
#include "pvtap/codec/frame_codec.h"

namespace pvtap {
namespace {

using test::hex_bytes;

struct Parsed {
  Frame frame;
  FrameLayout layout;
};

Parsed parse(std::string_view hex, Dialect d, Role r) {
  const auto bytes = hex_bytes(hex);
  const ParseOutcome out = parse_frame(bytes, d, r);
  EXPECT_TRUE(out) << out.diagnostics();
  if (!out) return {};
  return {out.value(), frame_layout(out.value(), bytes.size())};
}

void expect_span(FieldSpan s, unsigned offset, unsigned length) {
  EXPECT_EQ(s.offset, offset);
  EXPECT_EQ(s.length, length);
}

TEST(FrameLayout, HybridWriteEchoCarriesDeviceNumberRegisterAndValue) {
  const auto p = parse("06 18 08 31 00 00 67 10 2A 09 3C 2A 86", Dialect::Hybrid, Role::Response);
  expect_span(p.layout.station, 0, 1);
  expect_span(p.layout.function, 1, 1);
  expect_span(p.layout.byte_count, 2, 1);
  expect_span(p.layout.device_type, 3, 1);
  expect_span(p.layout.device_serial, 4, 3);
  expect_span(p.layout.start, 7, 2);
  expect_span(p.layout.words, 9, 2);
  expect_span(p.layout.check, 11, 2);
  EXPECT_FALSE(p.layout.count.present());
}

TEST(FrameLayout, HybridReadReplyWordsFollowTheDeviceNumber) {
  const auto p = parse("09 11 08 22 00 00 6B 22 00 00 6B F2 77", Dialect::Hybrid, Role::Response);
  expect_span(p.layout.words, 7, 4);
  expect_span(p.layout.word_span(1), 9, 2);
  EXPECT_FALSE(p.layout.word_span(2).present());
  EXPECT_FALSE(p.layout.start.present());
}

TEST(FrameLayout, HybridRestoreConfirmationHasStartAndCount) {
  const auto p = parse("06 1F 08 31 00 00 67 10 24 00 7B BD F1", Dialect::Hybrid, Role::Response);
  expect_span(p.layout.start, 7, 2);
  expect_span(p.layout.count, 9, 2);
  EXPECT_FALSE(p.layout.words.present());
}

TEST(FrameLayout, RtuRequests) {
  const auto read = parse("01 03 00 00 00 0A C5 CD", Dialect::Gsl, Role::Request);
  expect_span(read.layout.start, 2, 2);
  expect_span(read.layout.count, 4, 2);
  expect_span(read.layout.check, 6, 2);
  const auto write = parse("06 18 10 2A 09 3C 03 36", Dialect::Hybrid, Role::Request);
  expect_span(write.layout.start, 2, 2);
  expect_span(write.layout.words, 4, 2);
}

TEST(FrameLayout, GslWriteMultipleRequestCarriesItsByteCountAfterTheCount) {
  Frame f;
  f.dialect = Dialect::Gsl;
  f.station = 1;
  f.function = 0x10;
  f.start = 0x05DC;
  f.count = 2;
  f.byte_count = 4;
  f.words = {1, 2};
  const FrameLayout l = frame_layout(f, 13);
  expect_span(l.count, 4, 2);
  expect_span(l.byte_count, 6, 1);
  expect_span(l.words, 7, 4);
  expect_span(l.check, 11, 2);
}

TEST(FrameLayout, GslExceptionAndReadReply) {
  Frame ex;
  ex.dialect = Dialect::Gsl;
  ex.role = Role::Response;
  ex.function = 0x83;
  ex.exception_code = 2;
  const FrameLayout le = frame_layout(ex, 5);
  expect_span(le.exception_code, 2, 1);
  expect_span(le.check, 3, 2);
  Frame reply = ex;
  reply.function = 0x03;
  reply.exception_code.reset();
  reply.byte_count = 4;
  reply.words = {7, 8};
  const FrameLayout lr = frame_layout(reply, 9);
  expect_span(lr.byte_count, 2, 1);
  expect_span(lr.words, 3, 4);
}

TEST(FrameLayout, AsciiRequestAndReply) {
  const auto req =
      parse("05 30 31 52 30 30 30 34 30 34 30 31 64 62 04", Dialect::Ascii, Role::Request);
  expect_span(req.layout.start_delimiter, 0, 1);
  expect_span(req.layout.station, 1, 2);
  expect_span(req.layout.function, 3, 1);
  expect_span(req.layout.start, 4, 4);
  expect_span(req.layout.count, 8, 2);
  expect_span(req.layout.check, 10, 4);
  expect_span(req.layout.end_delimiter, 14, 1);

  Frame reply;
  reply.dialect = Dialect::Ascii;
  reply.role = Role::Response;
  reply.words = {266, 57};
  const FrameLayout l = frame_layout(reply, 13 + 8);
  expect_span(l.words, 8, 8);
  expect_span(l.word_span(1), 12, 4);
  expect_span(l.check, 16, 4);
  expect_span(l.end_delimiter, 20, 1);
}

// The plain Modbus frames whose fields do not follow the GSL order (CRCs are not checked here).
TEST(FrameLayout, ModbusDiagnosticsReadWriteAndFifoPutTheirWordsWhereTheyAre) {
  const auto diag = parse("11 08 00 00 A5 37 00 00", Dialect::Modbus, Role::Request);
  expect_span(diag.layout.words, 4, 2);
  const auto rw = parse("11 17 00 03 00 06 00 0E 00 03 06 00 FF 00 FF 00 FF 00 00", Dialect::Modbus,
                        Role::Request);
  expect_span(rw.layout.start, 2, 2);
  expect_span(rw.layout.count, 4, 2);
  expect_span(rw.layout.byte_count, 10, 1);
  expect_span(rw.layout.words, 11, 6);
  const auto fifo = parse("11 18 00 06 00 02 01 B8 12 84 00 00", Dialect::Modbus, Role::Response);
  expect_span(fifo.layout.byte_count, 2, 2);
  expect_span(fifo.layout.count, 4, 2);
  expect_span(fifo.layout.words, 6, 4);
  expect_span(fifo.layout.check, 10, 2);
}

}  // namespace
}  // namespace pvtap
