// The example maps of examples/maps load, and decode a forged reply of their device.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "frame_builders.h"
#include "pvtap/codec/frame_codec.h"
#include "pvtap/registers/register_decoder.h"
#include "pvtap/registers/register_format.h"

namespace pvtap {
namespace {

const RegisterMap& sdm630_map() {
  static const RegisterMap map = [] {
    const std::string path = std::string(PVTAP_EXAMPLE_MAPS) + "/eastron-sdm630.toml";
    std::ifstream in(path);
    if (!in) throw std::runtime_error("cannot open " + path);
    std::ostringstream text;
    text << in.rdbuf();
    RegisterMapResult result = load_register_map(text.str(), "eastron-sdm630.toml");
    if (!result) throw std::runtime_error(result.error_text());
    return result.value();
  }();
  return map;
}

// The frame as the wire carries it, parsed back by the codec.
Frame on_the_wire(const Frame& frame) {
  const std::vector<std::uint8_t> bytes = encode_frame(frame);
  ParseOutcome parsed = parse_frame(bytes, frame.dialect, frame.role);
  if (!parsed) throw std::runtime_error("the forged frame does not parse");
  return parsed.value();
}

Frame input_reply(std::uint8_t station, WordList words) {
  Frame f = test::frame_of(Dialect::Modbus, Role::Response, station, fc::kGslReadInput);
  f.byte_count = static_cast<std::uint8_t>(2 * words.size());
  f.words = words;
  return on_the_wire(f);
}

std::vector<DecodedValue> decode_at(std::uint8_t station, std::uint16_t start, WordList words) {
  RegisterDecoder decoder;
  decoder.use_station_map(10, sdm630_map());
  const Frame request =
      on_the_wire(test::read_request(Dialect::Modbus, station, fc::kGslReadInput, start,
                                     static_cast<std::uint16_t>(words.size())));
  std::vector<DecodedValue> out;
  const DecodeReport report = decoder.decode(input_reply(station, words), &request, out);
  EXPECT_EQ(report.status, DecodeStatus::Decoded);
  return out;
}

TEST(ExampleMaps, EastronSdm630Loads) {
  const RegisterMap& map = sdm630_map();
  EXPECT_EQ(map.dialect(), Dialect::Modbus);
  EXPECT_EQ(map.title(), "Eastron SDM630");
  for (const RegisterDef& def : map.registers()) {
    EXPECT_TRUE(def.is_float()) << def.key;
    EXPECT_EQ(def.words, 2u) << def.key;
  }
  ASSERT_NE(map.find_address(0x0046), nullptr);
  EXPECT_EQ(map.find_address(0x0046)->key, "frequency");
  EXPECT_EQ(map.find_address(0x0048)->unit, "kWh");
  EXPECT_EQ(map.find_address(0x0034)->key, "total_power");
}

TEST(ExampleMaps, EastronSdm630DecodesPhaseVoltages) {
  // 230.1 V, 231.4 V, 229.8 V as float32 words, high word first.
  const std::vector<DecodedValue> v =
      decode_at(10, 0x0000, {0x4366, 0x199A, 0x4367, 0x6666, 0x4365, 0xCCCD});
  ASSERT_EQ(v.size(), 3u);
  EXPECT_EQ(v[0].key(), "phase1_voltage");
  EXPECT_EQ(format_value(v[0]), "230.1 V");
  EXPECT_DOUBLE_EQ(value_as_shown(v[0]), 230.1);
  EXPECT_EQ(format_value(v[1]), "231.4 V");
  EXPECT_EQ(format_value(v[2]), "229.8 V");
  for (const DecodedValue& value : v) EXPECT_EQ(value.warnings, 0u);
}

TEST(ExampleMaps, EastronSdm630DecodesFrequencyAndEnergy) {
  // 49.98 Hz, 1234.5 kWh imported, 0 kWh exported.
  const std::vector<DecodedValue> v =
      decode_at(10, 0x0046, {0x4247, 0xEB85, 0x449A, 0x5000, 0x0000, 0x0000});
  ASSERT_EQ(v.size(), 3u);
  EXPECT_EQ(format_value(v[0]), "49.98 Hz");
  EXPECT_EQ(v[1].name(), "total import active energy");
  EXPECT_EQ(format_value(v[1]), "1234.500 kWh");
  EXPECT_EQ(format_value(v[2]), "0.000 kWh");
}

TEST(ExampleMaps, OtherStationsKeepTheirOwnMap) {
  const std::vector<DecodedValue> v = decode_at(11, 0x0000, {0x4366, 0x199A});
  ASSERT_EQ(v.size(), 2u);
  EXPECT_TRUE(v[0].has(ValueWarning::NotInMap));
  EXPECT_EQ(v[0].raw, 0x4366u);
}

}  // namespace
}  // namespace pvtap
