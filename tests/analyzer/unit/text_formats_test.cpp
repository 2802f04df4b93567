// Number, hex, JSON and CSV text as the output formats write it.
#include "formatting/csv_text.h"
#include "formatting/json_text.h"
#include "formatting/number_text.h"

#include <gtest/gtest.h>

#include <array>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <utility>
#include <vector>

namespace pvtap::analyzer {
namespace {

std::string fixed(double v, int decimals) {
  std::string out;
  append_fixed(out, v, decimals);
  return out;
}

std::string reference_fixed(double v, int decimals) {
  std::array<char, 64> buf{};
  const auto r =
      std::to_chars(buf.data(), buf.data() + buf.size(), v, std::chars_format::fixed, decimals);
  return std::string(buf.data(), r.ptr);
}

TEST(TextAppend, FixedPointAsRegistersScaleIt) {
  EXPECT_EQ(fixed(523 * 0.1, 1), "52.3");
  EXPECT_EQ(fixed(5001 * 0.01, 2), "50.01");
  EXPECT_EQ(fixed(7 * 0.001, 3), "0.007");
  EXPECT_EQ(fixed(-12.5, 1), "-12.5");
  EXPECT_EQ(fixed(-0.04, 1), "0.0");  // no "-0.0"
  EXPECT_EQ(fixed(266, 0), "266");
  EXPECT_EQ(fixed(1e20, 1), "100000000000000000000.0");
  EXPECT_EQ(fixed(NAN, 2), "0.00");
}

// Integers are written two digits at a time: every digit count, each edge of a pair, and the
// extremes must read as std::to_string writes them.
TEST(TextAppend, IntegersAgreeWithToString) {
  std::vector<std::uint64_t> values = {
      0, 1, 9, 10, 11, 99, 100, 101, 999, 1000, std::numeric_limits<std::uint64_t>::max()};
  for (std::uint64_t p = 10; p < 1000000000000000000u; p *= 10) {
    for (const std::uint64_t v : {p - 1, p, p + 1, 7 * p + 3}) values.push_back(v);
  }
  for (const std::uint64_t v : values) {
    std::string out = "x";  // appended after what is there
    append_uint(out, v);
    ASSERT_EQ(out.substr(1), std::to_string(v));
    ASSERT_EQ(out[0], 'x');
    if (v > static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max())) continue;
    const auto s = static_cast<std::int64_t>(v);
    std::string neg;
    append_int(neg, -s);
    ASSERT_EQ(neg, std::to_string(-s));
  }
  std::string lowest;
  append_int(lowest, std::numeric_limits<std::int64_t>::min());
  EXPECT_EQ(lowest, std::to_string(std::numeric_limits<std::int64_t>::min()));
}

// Capture timestamps (1e9 seconds and more with 6 decimals) are scaled exactly, so the digits
// are the ones to_chars prints from the binary value, ties and all.
TEST(TextAppend, FixedPointAgreesWithToCharsOnTimestamps) {
  std::uint64_t state = 2026;
  const auto next = [&] {
    state = state * 6364136223846793005u + 1442695040888963407u;
    return state >> 11;
  };
  for (int i = 0; i < 200000; ++i) {
    const double seconds = 1e9 + static_cast<double>(next() % 4000000000u);
    const double v = seconds + static_cast<double>(next() % 1000000000u) * 1e-9;
    ASSERT_EQ(fixed(v, 6), reference_fixed(v, 6)) << v;
    ASSERT_EQ(fixed(v, 9), reference_fixed(v, 9)) << v;
    const double tie = seconds + static_cast<double>(next() % 64) / 128.0;  // exact halves
    ASSERT_EQ(fixed(tie, 6), reference_fixed(tie, 6)) << tie;
    ASSERT_EQ(fixed(tie * 1e6, 0), reference_fixed(tie * 1e6, 0)) << tie;
  }
  EXPECT_EQ(fixed(1700000000.0078125, 6), "1700000000.007812");  // a tie: to the even digit
  EXPECT_EQ(fixed(1700000000.0234375, 6), "1700000000.023438");
  EXPECT_EQ(fixed(1700000000.0000005, 6), reference_fixed(1700000000.0000005, 6));
}

// Register maps show as many decimals as their scale has, so no value sits halfway between
// two printed numbers; there the fast path must print what to_chars prints.
TEST(TextAppend, FixedPointAgreesWithToCharsOnRegisterValues) {
  const std::pair<double, int> scales[] = {{1, 0},     {0.1, 1}, {0.01, 2},
                                           {0.001, 3}, {0.5, 1}, {100, 0}};
  for (const auto& [scale, decimals] : scales) {
    for (std::int64_t raw = -70000; raw <= 70000; raw += 7) {
      const double v = static_cast<double>(raw) * scale;
      std::string expected = reference_fixed(v, decimals);
      if (expected[0] == '-' && expected.find_first_not_of("-0.") == std::string::npos) {
        expected.erase(0, 1);
      }
      ASSERT_EQ(fixed(v, decimals), expected) << raw << " * " << scale;
    }
  }
}

TEST(TextAppend, JsonStringsAreEscaped) {
  std::string out;
  append_json_string(out, "a\"b\\c\nd\te\x01 °C");
  EXPECT_EQ(out, "\"a\\\"b\\\\c\\nd\\te\\u0001 °C\"");
}

// Plain text is scanned eight bytes at a time: every byte value, at every place of a block and
// of the tail after it, is escaped as one character at a time would escape it.
TEST(TextAppend, JsonStringsAreEscapedWhereverTheByteIs) {
  const auto reference = [](std::string_view text) {
    std::string r = "\"";
    for (const char ch : text) {
      const auto c = static_cast<unsigned char>(ch);
      if (c == '"' || c == '\\') {
        r += '\\';
        r += ch;
      } else if (c == '\n') {
        r += "\\n";
      } else if (c == '\r') {
        r += "\\r";
      } else if (c == '\t') {
        r += "\\t";
      } else if (c < 0x20) {
        static constexpr char kHex[] = "0123456789abcdef";
        r += "\\u00";
        r += kHex[c >> 4];
        r += kHex[c & 0xF];
      } else {
        r += ch;
      }
    }
    return r + "\"";
  };
  for (int c = 0; c < 256; ++c) {
    for (std::size_t at = 0; at < 19; ++at) {
      std::string text(19, 'a');
      text[at] = static_cast<char>(c);
      if (at + 1 < text.size()) text[at + 1] = static_cast<char>(255 - c);  // a neighbour too
      std::string out;
      append_json_string(out, text);
      ASSERT_EQ(out, reference(text)) << "byte " << c << " at " << at;
    }
  }
}

TEST(TextAppend, CsvFieldsAreQuotedOnlyWhenNeeded) {
  std::string out;
  append_csv_field(out, "plain");
  out += '|';
  append_csv_field(out, "a, b");
  out += '|';
  append_csv_field(out, "say \"hi\"");
  out += '|';
  append_csv_field(out, "two\nlines");
  EXPECT_EQ(out, "plain|\"a, b\"|\"say \"\"hi\"\"\"|\"two\nlines\"");
}

TEST(TextAppend, HexAndTimes) {
  std::string out;
  const std::vector<std::uint8_t> bytes = {0x01, 0xAB, 0xFF};
  append_hex(out, bytes);
  out += '|';
  append_spaced_hex(out, bytes);
  out += '|';
  append_hex_byte(out, 0x1F);
  EXPECT_EQ(out, "01abff|01 ab ff|0x1F");
  out.clear();
  append_utc_date_time(out, 1790000000.0123456);
  EXPECT_EQ(out, "2026-09-21 14:13:20.012346");
}

}  // namespace
}  // namespace pvtap::analyzer
