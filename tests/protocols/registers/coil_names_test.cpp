// Coils and discrete inputs named in a map: loading, lookups, merging and naming coil bits.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "frame_builders.h"
#include "pvtap/codec/function_codes.h"
#include "pvtap/registers/coil_bits.h"
#include "pvtap/registers/register_map.h"

namespace pvtap {
namespace {

constexpr std::string_view kPumpStation = R"toml(dialect = "modbus"

[[register]]
address = 0
key = "flow"
name = "flow"

[[coil]]
address = 3
key = "valve"
name = "inlet valve"

[[coil]]
address = 0
key = "pump"
name = "pump relay"

[[discrete_input]]
address = 0
key = "float_switch"
name = "float switch"
)toml";

const RegisterMap& pump_map() {
  static const RegisterMap map = [] {
    RegisterMapResult result = load_register_map(kPumpStation, "pump.toml");
    if (!result) throw std::runtime_error(result.error_text());
    return result.value();
  }();
  return map;
}

std::string errors_of(std::string_view toml) {
  RegisterMapResult result = load_register_map(toml, "test.toml");
  EXPECT_FALSE(result) << "the map should have been rejected";
  return result ? std::string{} : result.error_text();
}

TEST(CoilNames, MapNamesCoilsAndInputsByAddress) {
  const RegisterMap& map = pump_map();
  ASSERT_EQ(map.coils().size(), 2u);
  EXPECT_EQ(map.coils()[0].key, "pump");  // sorted by address
  EXPECT_EQ(map.coils()[1].line, 8u);     // the line of its [[coil]]
  EXPECT_EQ(map.coil_name(0), "pump relay");
  EXPECT_EQ(map.coil_name(3), "inlet valve");
  EXPECT_EQ(map.coil_name(1), "");
  EXPECT_EQ(map.input_name(0), "float switch");
  EXPECT_EQ(map.input_name(3), "");  // coil 3 is not input 3
  ASSERT_NE(map.find_discrete_input(0), nullptr);
  EXPECT_EQ(map.find_discrete_input(0)->key, "float_switch");
  EXPECT_EQ(RegisterMap().coil_name(0), "");
}

TEST(CoilNames, ReadReplyBitsAreNamedAtTheRequestsAddresses) {
  const Frame request = test::read_request(Dialect::Modbus, 9, fc::kReadCoils, 0, 4);
  Frame reply = test::frame_of(Dialect::Modbus, Role::Response, 9, fc::kReadCoils);
  reply.byte_count = 1;
  reply.data = {0b1001};
  const std::optional<CoilBits> bits = coil_bits(reply, &request);
  ASSERT_TRUE(bits);
  std::vector<std::string> shown;
  for (std::size_t i = 0; i < bits->count; ++i) {
    const CoilDef* def = coil_def(pump_map(), *bits, i);
    shown.push_back((def ? std::string(def->name) : "coil " + std::to_string(*bits->address(i))) +
                    (bits->on(i) ? " on" : " off"));
  }
  EXPECT_EQ(shown, (std::vector<std::string>{"pump relay on", "coil 1 off", "coil 2 off",
                                             "inlet valve on"}));
}

TEST(CoilNames, InputBitsAreLookedUpAmongInputs) {
  const Frame request = test::read_request(Dialect::Modbus, 9, fc::kReadDiscreteInputs, 2, 2);
  Frame reply = test::frame_of(Dialect::Modbus, Role::Response, 9, fc::kReadDiscreteInputs);
  reply.byte_count = 1;
  reply.data = {0b01};
  const std::optional<CoilBits> bits = coil_bits(reply, &request);
  ASSERT_TRUE(bits);
  EXPECT_EQ(coil_def(pump_map(), *bits, 0), nullptr);  // input 2: unnamed; coil 3 is no input
  EXPECT_EQ(coil_def(pump_map(), *bits, 1), nullptr);
  const Frame from_zero = test::read_request(Dialect::Modbus, 9, fc::kReadDiscreteInputs, 0, 1);
  const CoilDef* def = coil_def(pump_map(), *coil_bits(reply, &from_zero), 0);
  ASSERT_NE(def, nullptr);
  EXPECT_EQ(def->name, "float switch");
}

TEST(CoilNames, SingleWriteAndUnplacedReplies) {
  Frame write = test::frame_of(Dialect::Modbus, Role::Request, 9, fc::kWriteSingleCoil);
  write.start = 3;
  write.words = {0xFF00};
  const std::optional<CoilBits> bits = coil_bits(write, nullptr);
  ASSERT_TRUE(bits);
  ASSERT_NE(coil_def(pump_map(), *bits, 0), nullptr);
  EXPECT_EQ(coil_def(pump_map(), *bits, 0)->key, "valve");
  // Without its request a reply's bits have no addresses, so no names.
  Frame reply = test::frame_of(Dialect::Modbus, Role::Response, 9, fc::kReadCoils);
  reply.byte_count = 1;
  reply.data = {0x01};
  const std::optional<CoilBits> unplaced = coil_bits(reply, nullptr);
  ASSERT_TRUE(unplaced);
  EXPECT_FALSE(unplaced->address(0));
  EXPECT_EQ(coil_def(pump_map(), *unplaced, 0), nullptr);
}

TEST(CoilNames, EntryRulesAreChecked) {
  const std::string text = errors_of(R"toml(dialect = "modbus"
[[register]]
address = 0
key = "pump"
name = "pump speed"

[[coil]]
address = 0
key = "pump"
name = "pump relay"

[[coil]]
address = 1
key = "a"
name = "a"

[[coil]]
address = 1
key = "b"
name = "b"

[[discrete_input]]
address = 70000
key = "Bad"
name = ""
colour = "red"
)toml");
  EXPECT_NE(text.find("test.toml:7:1: coil 'pump' (0x0000): key is already used by the entry at "
                      "line 2"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("test.toml:17:1: coil 'b' (0x0001): duplicate address, also defined at "
                      "line 12"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("discrete_input 'Bad': key must start with a lowercase letter"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("discrete_input 'Bad': name is missing or empty"), std::string::npos) << text;
  EXPECT_NE(text.find("discrete_input 'Bad': address must be 0 .. 65535"), std::string::npos)
      << text;
  EXPECT_NE(text.find("test.toml:26:1: unknown discrete_input field 'colour'"), std::string::npos)
      << text;
}

TEST(CoilNames, OnlyModbusFamilyMapsNameCoils) {
  const std::string text = errors_of(R"toml(dialect = "hybrid"
[[coil]]
address = 0
key = "pump"
name = "pump relay"
)toml");
  EXPECT_NE(text.find("coil 'pump' (0x0000): only gsl and modbus maps name coils"),
            std::string::npos)
      << text;
  EXPECT_NE(errors_of("dialect = \"modbus\"\ncoil = 3\n").find("coil entries are written as"),
            std::string::npos);
}

TEST(CoilNames, ExtendingReplacesCoilsByAddressOrKey) {
  RegisterMapResult overlay = load_register_map(R"toml(dialect = "modbus"
mode = "extend"
[[coil]]
address = 0
key = "main_pump"
name = "main pump relay"

[[coil]]
address = 7
key = "valve"
name = "outlet valve"
)toml",
                                                "site.toml");
  ASSERT_TRUE(overlay) << overlay.error_text();
  RegisterMapResult merged = merge_register_maps(pump_map(), overlay.value());
  ASSERT_TRUE(merged) << merged.error_text();
  EXPECT_EQ(merged->coil_name(0), "main pump relay");
  EXPECT_EQ(merged->coil_name(3), "");  // key "valve" moved to 7
  EXPECT_EQ(merged->coil_name(7), "outlet valve");
  EXPECT_EQ(merged->coils().size(), 2u);
  EXPECT_EQ(merged->input_name(0), "float switch");
  EXPECT_NE(merged->find_key("flow"), nullptr);
}

}  // namespace
}  // namespace pvtap
