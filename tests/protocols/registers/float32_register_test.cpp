// float32 registers and the word order of 2-word values: map rules, decoding and text.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "pvtap/codec/function_codes.h"
#include "pvtap/registers/register_decoder.h"
#include "pvtap/registers/register_format.h"
#include "pvtap/registers/register_map.h"

namespace pvtap {
namespace {

constexpr std::string_view kMeterMap = R"toml(dialect = "modbus"

[[register]]
address = 0x0000
key = "voltage"
name = "voltage"
kind = "float32"
unit = "V"
decimals = 1

[[register]]
address = 0x0002
key = "power_swapped"
name = "power"
kind = "float32"
word_order = "low_first"
unit = "W"

[[register]]
address = 0x0004
key = "energy_wh"
name = "energy"
kind = "float32"
scale = 0.001
unit = "kWh"

[[register]]
address = 0x0006
key = "counter_swapped"
name = "counter"
words = 2
combine = "binary"
word_order = "low_first"

[[register]]
address = 0x0008
key = "offset"
name = "offset"
words = 2
signed = true
)toml";

// Loaded once: decoded values point into the map, so it must outlive them.
const RegisterMap& meter_map() {
  static const RegisterMap map = [] {
    RegisterMapResult result = load_register_map(kMeterMap, "meter.toml");
    if (!result) throw std::runtime_error(result.error_text());
    return result.value();
  }();
  return map;
}

std::vector<DecodedValue> decode_words(const RegisterMap& map, WordList words) {
  RegisterDecoder decoder;
  decoder.use_map(map);
  std::vector<DecodedValue> out;
  decoder.decode_block(Dialect::Modbus, 0, words.span(), ValueOrigin::ReadReply, out);
  return out;
}

std::string errors_of(std::string_view toml) {
  RegisterMapResult result = load_register_map(toml, "test.toml");
  EXPECT_FALSE(result) << "the map should have been rejected";
  return result ? std::string{} : result.error_text();
}

TEST(Float32Register, IsATwoWordNumberWithItsOwnEncoding) {
  const RegisterMap& map = meter_map();
  const RegisterDef* voltage = map.find_key("voltage");
  ASSERT_NE(voltage, nullptr);
  EXPECT_EQ(voltage->kind, RegisterKind::Number);
  EXPECT_TRUE(voltage->is_float());
  EXPECT_EQ(voltage->words, 2u);
  EXPECT_EQ(voltage->word_order, WordOrder::HighFirst);
  EXPECT_EQ(voltage->decimals, 1u);
  EXPECT_EQ(map.find_key("power_swapped")->word_order, WordOrder::LowFirst);
  // Without decimals a float32 shows three digits, more when its scale asks for more.
  EXPECT_EQ(map.find_key("power_swapped")->decimals, 3u);
  EXPECT_FALSE(map.find_key("counter_swapped")->is_float());
}

TEST(Float32Register, DecodesHighWordFirstAndLowWordFirst) {
  // 230.1 = 0x4366199A; 1234.5 = 0x449A5000 sent low word first; 12345 Wh = 0x4640E400.
  const std::vector<DecodedValue> v = decode_words(
      meter_map(),
      {0x4366, 0x199A, 0x5000, 0x449A, 0x4640, 0xE400, 0x0002, 0x0001, 0xFFFF, 0xFFFE});
  ASSERT_EQ(v.size(), 5u);
  EXPECT_FLOAT_EQ(static_cast<float>(v[0].value), 230.1f);
  EXPECT_EQ(format_value(v[0]), "230.1 V");
  EXPECT_DOUBLE_EQ(value_as_shown(v[0]), 230.1);
  EXPECT_EQ(v[0].raw, 0x4366199Au);
  EXPECT_DOUBLE_EQ(v[1].value, 1234.5);
  EXPECT_EQ(v[1].raw, 0x449A5000u);
  EXPECT_EQ(format_value(v[1]), "1234.500 W");
  EXPECT_DOUBLE_EQ(v[2].value, 12.345);
  EXPECT_EQ(format_value(v[2]), "12.345 kWh");
  // An integer pair sent low word first: 0x0001_0002.
  EXPECT_EQ(v[3].raw, 0x00010002u);
  EXPECT_DOUBLE_EQ(v[3].value, 65538.0);
  EXPECT_DOUBLE_EQ(v[4].value, -2.0);  // int32 0xFFFFFFFE
  for (const DecodedValue& value : v) EXPECT_EQ(value.warnings, 0u) << value.key();
}

TEST(Float32Register, NegativeValuesNeedNoSignedSetting) {
  const std::vector<DecodedValue> v = decode_words(meter_map(), {0xC400, 0x2000});
  ASSERT_FALSE(v.empty());
  EXPECT_DOUBLE_EQ(v[0].value, -512.5);
  EXPECT_EQ(format_value(v[0]), "-512.5 V");
}

TEST(Float32Register, NanAndInfinityAreFlaggedAndShownAsSuch) {
  const std::vector<DecodedValue> v =
      decode_words(meter_map(), {0x7FC0, 0x0000, 0x0000, 0xFF80, 0x7F80, 0x0000});
  ASSERT_EQ(v.size(), 3u);
  EXPECT_TRUE(std::isnan(v[0].value));
  EXPECT_TRUE(v[0].has(ValueWarning::NotFinite));
  EXPECT_EQ(format_value(v[0]), "not a number (0x7FC00000)");
  EXPECT_TRUE(std::isnan(value_as_shown(v[0])));
  EXPECT_EQ(v[1].value, -INFINITY);  // 0xFF800000 sent low word first
  EXPECT_EQ(format_value(v[1]), "-infinity W");
  EXPECT_TRUE(v[1].has(ValueWarning::NotFinite));
  EXPECT_EQ(format_value(v[2]), "infinity kWh");
  EXPECT_EQ(describe(ValueWarning::NotFinite), "float32 value is not a number or infinite");
}

TEST(Float32Register, HalfAValueInTheFrameIsIncomplete) {
  const std::vector<DecodedValue> v = decode_words(meter_map(), {0x4366});
  ASSERT_EQ(v.size(), 1u);
  EXPECT_TRUE(v[0].has(ValueWarning::Incomplete));
  EXPECT_FALSE(v[0].has(ValueWarning::NotFinite));
}

TEST(Float32Register, MapRulesAreChecked) {
  const std::string text = errors_of(R"toml(dialect = "modbus"
[[register]]
address = 0
key = "three_words"
name = "x"
kind = "float32"
words = 3

[[register]]
address = 10
key = "signed_float"
name = "x"
kind = "float32"
signed = true

[[register]]
address = 20
key = "combined_float"
name = "x"
kind = "float32"
combine = "decimal"

[[register]]
address = 30
key = "one_word_order"
name = "x"
word_order = "low_first"

[[register]]
address = 40
key = "bad_order"
name = "x"
words = 2
word_order = "middle_endian"
)toml");
  EXPECT_NE(text.find("register 'three_words' (0x0000): a float32 register is 2 word(s) wide, "
                      "not 3"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("'signed_float' (0x000A): a float32 register carries its own sign"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("'combine' does not apply to a float32 register"), std::string::npos) << text;
  EXPECT_NE(text.find("'one_word_order' (0x001E): 'word_order' applies only to 2-word"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("test.toml:34:14: unknown word order 'middle_endian'"), std::string::npos)
      << text;
}

TEST(Float32Register, ExtendingAMapKeepsEncodingAndWordOrder) {
  const RegisterMap& base = meter_map();
  RegisterMapResult overlay = load_register_map(R"toml(dialect = "modbus"
mode = "extend"
[[register]]
address = 0x0020
key = "frequency"
name = "frequency"
kind = "float32"
unit = "Hz"
)toml",
                                                "overlay.toml");
  ASSERT_TRUE(overlay) << overlay.error_text();
  RegisterMapResult merged = merge_register_maps(base, overlay.value());
  ASSERT_TRUE(merged) << merged.error_text();
  const RegisterDef* power = merged->find_key("power_swapped");
  ASSERT_NE(power, nullptr);
  EXPECT_TRUE(power->is_float());
  EXPECT_EQ(power->word_order, WordOrder::LowFirst);
  EXPECT_EQ(merged->find_key("counter_swapped")->word_order, WordOrder::LowFirst);
  EXPECT_FALSE(merged->find_key("counter_swapped")->is_float());
  EXPECT_TRUE(merged->find_key("frequency")->is_float());
}

}  // namespace
}  // namespace pvtap
