// Display text of decoded register values, for every kind and the doubtful cases.
#include "pvtap/registers/register_format.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "pvtap/codec/function_codes.h"

namespace pvtap {
namespace {

// One of each kind at consecutive Hybrid addresses from 0x2000.
constexpr std::string_view kEveryKind = R"toml(dialect = "hybrid"
[[register]]
address = 0x2000
key = "plain"
name = "plain"

[[register]]
address = 0x2001
key = "scaled"
name = "scaled"
scale = 0.25
unit = "kvar"

[[register]]
address = 0x2002
key = "wide_raw"
name = "wide raw"
kind = "raw"
words = 2

[[register]]
address = 0x2004
key = "capacity"
name = "capacity"
kind = "bcd_phase_capacity"
scale = 0.1
unit = "kW"

[[register]]
address = 0x2005
key = "date"
name = "date"
kind = "bcd_year_month"

[[register]]
address = 0x2006
key = "digits"
name = "digits"
kind = "bcd"
scale = 0.01
unit = "V"

[[register]]
address = 0x2007
key = "label"
name = "label"
kind = "text"
words = 2

[[register]]
address = 0x2009
key = "fixed"
name = "fixed decimals"
scale = 0.1
decimals = 3
unit = "A"
)toml";

// Values point into their map, so the map must outlive them: keep it for the whole run.
const RegisterDecoder& kinds_decoder() {
  static const RegisterDecoder decoder = [] {
    RegisterDecoder d;
    RegisterMapResult map = load_register_map(kEveryKind, "kinds.toml");
    EXPECT_TRUE(map) << map.error_text();
    if (map) d.use_map(map.value());
    return d;
  }();
  return decoder;
}

std::vector<DecodedValue> decode_at(std::uint16_t start, std::span<const std::uint16_t> words) {
  const RegisterDecoder& decoder = kinds_decoder();
  std::vector<DecodedValue> out;
  decoder.decode_block(Dialect::Hybrid, start, words, ValueOrigin::ReadReply, out);
  return out;
}

std::string text_at(std::uint16_t start, std::initializer_list<std::uint16_t> words) {
  const std::vector<std::uint16_t> list(words);
  const std::vector<DecodedValue> values = decode_at(start, list);
  return values.empty() ? std::string("<none>") : format_value(values.front());
}

TEST(RegisterFormat, Numbers) {
  EXPECT_EQ(text_at(0x2000, {65535}), "65535");
  EXPECT_EQ(text_at(0x2001, {7}), "1.75 kvar");
  EXPECT_EQ(text_at(0x2009, {12}), "1.200 A");
}

TEST(RegisterFormat, ValueAsShownIsTheNumberOfTheText) {
  const std::vector<std::uint16_t> words{2206};
  const std::vector<DecodedValue> values = decode_at(0x2009, words);
  ASSERT_EQ(values.size(), 1u);
  EXPECT_NE(values[0].value, 220.6);  // 2206 x 0.1 in binary: 220.60000000000002
  EXPECT_EQ(value_as_shown(values[0]), 220.6);
  EXPECT_EQ(format_value(values[0]), "220.600 A");
  const std::vector<std::uint16_t> unmapped{7};
  const std::vector<DecodedValue> raw = decode_at(0x3000, unmapped);
  ASSERT_EQ(raw.size(), 1u);
  EXPECT_EQ(value_as_shown(raw[0]), raw[0].value);
}

TEST(RegisterFormat, RawWordsInHex) {
  EXPECT_EQ(text_at(0x2002, {0x00AB, 0xCDEF}), "0x00ABCDEF");
}

TEST(RegisterFormat, BcdValues) {
  EXPECT_EQ(text_at(0x2004, {0x3100}), "three phase, 10.0 kW");
  EXPECT_EQ(text_at(0x2004, {0x2055}), "2 phases, 5.5 kW");
  EXPECT_EQ(text_at(0x2004, {0x10A0}), "invalid BCD 0x10A0");
  EXPECT_EQ(text_at(0x2005, {0x1203}), "2012-03");
  EXPECT_EQ(text_at(0x2006, {0x1234}), "12.34 V");
  const std::vector<std::uint16_t> bad_month{0x0513};
  const DecodedValue date = decode_at(0x2005, bad_month).front();
  EXPECT_TRUE(date.has(ValueWarning::InvalidDate));
  EXPECT_EQ(format_value(date), "2005-13");
  const std::vector<std::uint16_t> bad_digit{0x00F0};
  EXPECT_TRUE(decode_at(0x2006, bad_digit).front().has(ValueWarning::InvalidBcd));
}

TEST(RegisterFormat, TextWithNonPrintableCharacters) {
  const std::vector<std::uint16_t> words{0x4F4B, 0x0721};
  const DecodedValue label = decode_at(0x2007, words).front();
  EXPECT_EQ(format_value(label), "OK?!");
  EXPECT_TRUE(label.has(ValueWarning::NonPrintableText));
}

TEST(RegisterFormat, EmptyBitListSaysNone) {
  const RegisterDecoder decoder;
  std::vector<DecodedValue> out;
  const std::vector<std::uint16_t> words{0};
  decoder.decode_block(Dialect::Hybrid, 0x101C, words, ValueOrigin::ReadReply, out);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(format_value(out[0]), "none");
}

TEST(RegisterFormat, AppendsToAnExistingString) {
  const RegisterDecoder decoder;
  std::vector<DecodedValue> out;
  const std::vector<std::uint16_t> words{523};
  decoder.decode_block(Dialect::Hybrid, 0x1006, words, ValueOrigin::ReadReply, out);
  std::string line = "battery: ";
  append_value_text(line, out[0]);
  EXPECT_EQ(line, "battery: 52.3 V");
}

TEST(RegisterFormat, ValueAddresses) {
  const RegisterDecoder decoder;
  std::vector<DecodedValue> out;
  const std::vector<std::uint16_t> words{1, 2};
  decoder.decode_block(Dialect::Ascii, 0x0020, words, ValueOrigin::ReadReply, out);
  EXPECT_EQ(format_value_address(out[1], Dialect::Ascii).view(), "0x0022");
}

TEST(RegisterFormat, WarningsAreDescribed) {
  EXPECT_NE(describe(ValueWarning::LowPartOver9999).find("9999"), std::string_view::npos);
  EXPECT_NE(describe(ValueWarning::Incomplete).find("not in the frame"), std::string_view::npos);
}

}  // namespace
}  // namespace pvtap
