// The table of dialects: one record per dialect, in the enum's order, each complete, and the
// generic codec answers what the record answers.
#include "../../../protocols/src/dialects/dialect_module.h"

#include <gtest/gtest.h>

#include <cstddef>
#include <set>
#include <string_view>

#include "pvtap/codec/frame_codec.h"
#include "pvtap/codec/function_codes.h"

namespace pvtap::detail {
namespace {

Dialect nth(std::size_t i) {
  return static_cast<Dialect>(i);
}

TEST(DialectTable, EachDialectHasItsOwnCompleteRecord) {
  for (std::size_t i = 0; i < kDialectCount; ++i) {
    const DialectModule& m = dialect_module(nth(i));
    SCOPED_TRACE(to_string(nth(i)));
    EXPECT_EQ(m.dialect, nth(i));
    EXPECT_NE(m.parse, nullptr);
    EXPECT_NE(m.read_header, nullptr);
    EXPECT_NE(m.verify_check, nullptr);
    EXPECT_NE(m.check_wire_bytes, nullptr);
    EXPECT_NE(m.encode, nullptr);
    EXPECT_NE(m.function_name, nullptr);
    EXPECT_NE(m.exception_name, nullptr);
    EXPECT_NE(m.builtin_map_text, nullptr);
    EXPECT_NE(m.reply_kind, nullptr);
    EXPECT_NE(m.reply_is_echo, nullptr);
    EXPECT_NE(m.compare_reply_count, nullptr);
    // A field left out of a record's designated initializers is zero: neither is.
    EXPECT_GE(m.register_address_step, 1u);
    EXPECT_NE(m.answered_broadcast_station, 0) << "0 is every dialect's unanswered broadcast";
  }
}

// The session reads a reply again as the Modbus family's only where that can differ: an RTU
// frame of a dialect outside the family.
TEST(DialectTable, OnlyRtuDialectsOutsideTheModbusFamilyReadRepliesAgain) {
  for (const Dialect d : kAllDialects) {
    const DialectModule& m = dialect_module(d);
    if (!m.reply_may_be_modbus_family) continue;
    EXPECT_TRUE(m.rtu_framed) << to_string(d);
    EXPECT_FALSE(modbus_family(d)) << to_string(d);
  }
}

// A read of each dialect, written by the codec, read back by the record and by the codec.
TEST(DialectTable, TheCodecAndTheRecordReadAFrameAlike) {
  for (std::size_t i = 0; i < kDialectCount; ++i) {
    const Dialect d = nth(i);
    SCOPED_TRACE(to_string(d));
    Frame request;
    request.dialect = d;
    request.role = Role::Request;
    request.station = 7;
    request.function = d == Dialect::Ascii    ? fc::kAsciiRead
                       : d == Dialect::Hybrid ? fc::kHybridRunningData
                                              : fc::kGslReadInput;
    request.start = 0x0100;
    request.count = 4;
    const std::vector<std::uint8_t> wire = encode_frame(request);
    ASSERT_FALSE(wire.empty());

    Frame by_record;
    EXPECT_EQ(dialect_module(d).parse(wire, Role::Request, by_record), "");
    const ParseOutcome by_codec = parse_frame(wire, d, Role::Request);
    ASSERT_TRUE(by_codec.ok()) << by_codec.error_text();
    EXPECT_EQ(by_record.station, by_codec.value().station);
    EXPECT_EQ(by_record.start, by_codec.value().start);
    EXPECT_TRUE(verify_check(wire, d).ok);
    EXPECT_EQ(dialect_module(d).verify_check(wire).expected, verify_check(wire, d).expected);
    EXPECT_EQ(fc::function_name(d, request.function),
              dialect_module(d).function_name(request.function));
  }
}

// Plain Modbus devices bring their own map; the others ship one.
TEST(DialectTable, OnlyPlainModbusShipsWithoutABuiltInMap) {
  for (std::size_t i = 0; i < kDialectCount; ++i) {
    const Dialect d = nth(i);
    EXPECT_EQ(dialect_module(d).builtin_map_text().empty(), d == Dialect::Modbus) << to_string(d);
  }
}

// Each dialect is found again by the name to_string gives it, and has a title of its own.
TEST(DialectTable, NamesAndTitlesTellTheDialectsApart) {
  std::set<std::string_view> titles;
  for (const Dialect d : kAllDialects) {
    EXPECT_EQ(dialect_named(to_string(d)), d);
    EXPECT_FALSE(dialect_title(d).empty());
    EXPECT_TRUE(titles.insert(dialect_title(d)).second) << dialect_title(d);
    EXPECT_FALSE(check_name(d).empty());
  }
  EXPECT_EQ(dialect_named("rtu"), std::nullopt);
  EXPECT_EQ(check_name(Dialect::Ascii), "checksum");
}

}  // namespace
}  // namespace pvtap::detail
