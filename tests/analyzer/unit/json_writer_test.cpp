// JsonWriter: commas, nesting, escaping and numbers as every JSON output writes them.
#include "formatting/json_writer.h"

#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <string>

namespace pvtap::analyzer {
namespace {

TEST(JsonWriter, CommasGoBetweenMembersAndElementsOnly) {
  std::string out;
  JsonWriter w(out);
  w.begin_object();
  w.field("a", 1u);
  w.key("b");
  w.begin_array();
  w.uint(2);
  w.begin_object();
  w.end_object();
  w.begin_array();
  w.end_array();
  w.null();
  w.end_array();
  w.key("c");
  w.begin_object();
  w.field("d", -3);
  w.end_object();
  w.field_bool("e", false);
  w.end_object();
  EXPECT_EQ(out, R"({"a":1,"b":[2,{},[],null],"c":{"d":-3},"e":false})");
}

// A member whose value is an object or an array is opened in one step, first or not.
TEST(JsonWriter, MembersOpenedWithTheirKey) {
  std::string out;
  JsonWriter w(out);
  w.begin_object();
  w.begin_array("a");
  w.uint(1);
  w.begin_object();
  w.begin_object("b");
  w.end_object();
  w.begin_array("c");
  w.end_array();
  w.end_object();
  w.end_array();
  w.begin_object("d");
  w.field_hex("e", std::array<std::uint8_t, 1>{0x0a});
  w.end_object();
  w.end_object();
  EXPECT_EQ(out, R"({"a":[1,{"b":{},"c":[]}],"d":{"e":"0a"}})");
}

TEST(JsonWriter, AppendsAfterWhatIsThere) {
  std::string out = "x";
  JsonWriter w(out);
  w.begin_array();
  w.end_array();
  EXPECT_EQ(out, "x[]");
}

TEST(JsonWriter, StringValuesAndRunTimeKeysAreEscaped) {
  std::string out;
  JsonWriter w(out);
  w.begin_object();
  w.field("name", "a\"b\\c\nd\x01");
  w.key_text("st\"ation");
  w.string("°C");
  w.field_plain("dialect", "gsl");
  w.end_object();
  EXPECT_EQ(out, R"({"name":"a\"b\\c\nd\u0001","st\"ation":"°C","dialect":"gsl"})");
}

TEST(JsonWriter, NumbersAsTheFastFormattersWriteThem) {
  std::string out;
  JsonWriter w(out);
  w.begin_array();
  w.uint(18446744073709551615u);
  w.integer(-9223372036854775807);
  w.fixed(52.3, 1);
  w.fixed(-0.04, 1);
  w.fixed(266, 0);
  w.fixed(0.007, 3);
  w.end_array();
  EXPECT_EQ(out, "[18446744073709551615,-9223372036854775807,52.3,0.0,266,0.007]");
}

TEST(JsonWriter, HexAndRawText) {
  std::string out;
  JsonWriter w(out);
  w.begin_object();
  const std::array<std::uint8_t, 3> bytes = {0x01, 0x03, 0xff};
  w.field_hex("raw", bytes);
  w.field_raw("value", "1e3");
  w.key("list");
  w.begin_array();
  w.raw("{\"kept\":1}");
  w.raw("2");
  w.end_array();
  w.field_null("none");
  w.end_object();
  EXPECT_EQ(out, R"({"raw":"0103ff","value":1e3,"list":[{"kept":1},2],"none":null})");
}

// Fixed parts of a line are written once, with the comma before them, and put into each line
// whole.
TEST(JsonWriter, MembersMadeApartJoinAnObject) {
  std::string head;
  JsonWriter h = JsonWriter::more_members(head);
  h.field_plain("dialect", "ascii");
  h.field_plain("role", "request");
  EXPECT_EQ(head, R"(,"dialect":"ascii","role":"request")");

  std::string out;
  JsonWriter w(out);
  w.begin_object();
  w.raw_members(head);
  w.field("station", 3u);
  w.end_object();
  w.buffer() += '\n';
  EXPECT_EQ(out, "{\"dialect\":\"ascii\",\"role\":\"request\",\"station\":3}\n");

  std::string first;
  JsonWriter f(first);
  f.begin_object();
  f.field("type", "frame");
  f.raw_members(head);
  f.end_object();
  EXPECT_EQ(first, R"({"type":"frame","dialect":"ascii","role":"request"})");
}

// A value object's register and name are kept per register; the value follows them.
TEST(JsonWriter, KeptTextEndingAtAKeyTakesTheValueNext) {
  std::string kept;
  JsonWriter k(kept);
  k.begin_object();
  k.field("register", "0x1006");
  k.key("value");
  EXPECT_EQ(kept, R"({"register":"0x1006","value":)");

  std::string out;
  JsonWriter w(out);
  w.begin_array();
  for (int i = 0; i < 2; ++i) {
    w.raw_object_start(kept);
    w.fixed(52.3, 1);
    w.field("unit", "V");
    w.end_object();
  }
  w.begin_object();
  w.raw_members(R"(,"station":)");
  w.uint(3);
  w.end_object();
  w.end_array();
  EXPECT_EQ(out, R"([{"register":"0x1006","value":52.3,"unit":"V"},)"
                 R"({"register":"0x1006","value":52.3,"unit":"V"},{"station":3}])");
}

TEST(JsonWriter, DeepNestingKeepsEachLevelsCommas) {
  std::string out;
  JsonWriter w(out);
  std::string expected;
  for (int i = 0; i < 60; ++i) {
    w.begin_array();
    w.uint(static_cast<std::uint64_t>(i));
    expected += '[' + std::to_string(i) + ',';
  }
  for (int i = 0; i < 60; ++i) {
    w.uint(7);
    w.end_array();
    expected += "7]";
    if (i + 1 < 60) expected += ',';
  }
  EXPECT_EQ(out, expected);
}

TEST(JsonWriter, LongestKeyFits) {
  std::string out;
  JsonWriter w(out);
  w.begin_object();
  w.field("k", 1u);
  w.field("b23456789012345678901234567890123456789012345678", 2u);  // 48 characters
  w.end_object();
  EXPECT_EQ(out, R"({"k":1,"b23456789012345678901234567890123456789012345678":2})");
}

}  // namespace
}  // namespace pvtap::analyzer
