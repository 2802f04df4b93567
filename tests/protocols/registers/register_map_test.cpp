// The built-in register maps, the map loader's diagnostics, and merging user maps.
#include "pvtap/registers/register_map.h"

#include <gtest/gtest.h>

#include <set>
#include <string>
#include <thread>
#include <vector>

#include "small_register_map.h"

namespace pvtap {
namespace {

const RegisterMap& loaded(Dialect d) {
  const RegisterMap& map = builtin_register_map(d);
  EXPECT_FALSE(map.empty()) << load_builtin_register_map(d).error_text();
  return map;
}

const RegisterDef& entry(Dialect d, std::string_view key) {
  const RegisterDef* def = loaded(d).find_key(key);
  if (def == nullptr) throw std::runtime_error("no entry " + std::string(key));
  return *def;
}

std::string errors_of(std::string_view toml) {
  RegisterMapResult result = load_register_map(toml, "test.toml");
  EXPECT_FALSE(result) << "the map should have been rejected";
  return result.error_text();
}

TEST(RegisterMap, BuiltinMapsLoadWithoutErrors) {
  for (Dialect d : {Dialect::Ascii, Dialect::Hybrid, Dialect::Gsl}) {
    RegisterMapResult result = load_builtin_register_map(d);
    ASSERT_TRUE(result) << result.error_text();
    EXPECT_EQ(result->dialect(), d);
    EXPECT_EQ(result->mode(), MapMode::Replace);
    EXPECT_EQ(result->source_name(), "builtin:" + std::string(to_string(d)) + ".toml");
  }
}

TEST(RegisterMap, BuiltinMapsHaveEveryEntryOfTheReference) {
  EXPECT_EQ(loaded(Dialect::Ascii).size(), 23u);
  EXPECT_EQ(loaded(Dialect::Hybrid).size(), 76u);
  EXPECT_EQ(loaded(Dialect::Gsl).size(), 61u);
}

TEST(RegisterMap, BuiltinMapCoversEveryReferenceAddress) {
  const RegisterMap& ascii = loaded(Dialect::Ascii);
  for (unsigned a : {0x04u, 0x06u, 0x08u, 0x0Au, 0x20u, 0x22u, 0x1E0u, 0x1E2u, 0x1E4u}) {
    EXPECT_TRUE(ascii.locate(static_cast<std::uint16_t>(a))) << std::hex << a;
  }
  for (unsigned a = 0x50; a <= 0x6E; a += 2) {
    if (a == 0x5E) continue;  // between the line block (0x50..0x5C) and the power block
    EXPECT_TRUE(ascii.locate(static_cast<std::uint16_t>(a))) << std::hex << a;
  }
  const RegisterMap& hybrid = loaded(Dialect::Hybrid);
  for (unsigned a = 0x1000; a <= 0x109F; ++a) {
    EXPECT_TRUE(hybrid.locate(static_cast<std::uint16_t>(a))) << std::hex << a;
  }
  const RegisterMap& gsl = loaded(Dialect::Gsl);
  std::vector<std::pair<unsigned, unsigned>> runs{{1000, 1009}, {1030, 1033}, {1050, 1100},
                                                  {1250, 1252}, {1500, 1505}, {2010, 2010}};
  for (auto [first, last] : runs) {
    for (unsigned id = first; id <= last; ++id) {
      EXPECT_TRUE(gsl.locate(static_cast<std::uint16_t>(id))) << id;
    }
  }
  EXPECT_FALSE(gsl.locate(1010));
  EXPECT_FALSE(hybrid.locate(0x10A0));
}

TEST(RegisterMap, KeysAreUniqueAndSafeAsFieldNames) {
  for (Dialect d : {Dialect::Ascii, Dialect::Hybrid, Dialect::Gsl}) {
    std::set<std::string_view> keys;
    for (const RegisterDef& def : loaded(d).registers()) {
      EXPECT_TRUE(keys.insert(def.key).second) << "duplicate key " << def.key;
      ASSERT_FALSE(def.key.empty());
      EXPECT_TRUE(def.key[0] >= 'a' && def.key[0] <= 'z') << def.key;
      for (char c : def.key) {
        EXPECT_TRUE((c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_') << def.key;
      }
      EXPECT_FALSE(def.name.empty()) << def.key;
    }
  }
}

TEST(RegisterMap, RegistersAreSortedByAddress) {
  for (Dialect d : {Dialect::Ascii, Dialect::Hybrid, Dialect::Gsl}) {
    const auto defs = loaded(d).registers();
    for (std::size_t i = 1; i < defs.size(); ++i) {
      EXPECT_LE(defs[i - 1].address, defs[i].address) << defs[i].key;
    }
  }
}

TEST(RegisterMap, HybridEntriesAreExact) {
  const RegisterDef& battery = entry(Dialect::Hybrid, "battery_voltage");
  EXPECT_EQ(battery.address, 0x1006);
  EXPECT_EQ(battery.name, "battery voltage");
  EXPECT_DOUBLE_EQ(battery.scale, 0.1);
  EXPECT_EQ(battery.unit, "V");
  EXPECT_EQ(battery.kind, RegisterKind::Number);
  EXPECT_EQ(battery.words, 1);
  EXPECT_EQ(battery.decimals, 1);
  EXPECT_FALSE(battery.is_signed);

  const RegisterDef& energy = entry(Dialect::Hybrid, "total_discharge_energy");
  EXPECT_EQ(energy.address, 0x100E);
  EXPECT_EQ(energy.words, 2);
  EXPECT_EQ(energy.pair_rule, PairRule::Binary);
  EXPECT_EQ(energy.unit, "kWh");

  const RegisterDef& mode = entry(Dialect::Hybrid, "working_mode_setting");
  EXPECT_EQ(mode.address, 0x103B);
  EXPECT_EQ(mode.kind, RegisterKind::Enum);
  EXPECT_EQ(mode.value_text(3), "energy saving");
  EXPECT_EQ(entry(Dialect::Hybrid, "battery_type_setting").value_text(3), "LiFePO4");
  EXPECT_EQ(entry(Dialect::Hybrid, "inverter_running_state").value_text(7), "commissioning");

  const RegisterDef& faults = entry(Dialect::Hybrid, "fault_code_2");
  EXPECT_EQ(faults.kind, RegisterKind::Bits);
  EXPECT_EQ(faults.bit_name(1), "AC input under-voltage");
  EXPECT_EQ(faults.bit_name(13), "");
  EXPECT_EQ(faults.bit_name(15), "manual fault");
  EXPECT_EQ(entry(Dialect::Hybrid, "fault_code_1").bits.size(), 16u);
  EXPECT_EQ(entry(Dialect::Hybrid, "pv_controller_fault").bit_name(14), "PV array under-voltage");
  EXPECT_EQ(entry(Dialect::Hybrid, "custom_parameters").bit_name(9), "parallel machine");
  EXPECT_EQ(entry(Dialect::Hybrid, "internal_state").bit_name(10), "inverter phase-locked");

  EXPECT_EQ(entry(Dialect::Hybrid, "set_parameter_10").address, 0x1041);
  EXPECT_EQ(entry(Dialect::Hybrid, "set_parameter_2").address, 0x1049);
  EXPECT_EQ(entry(Dialect::Hybrid, "set_parameter_1").value_text(1), "on");

  const RegisterDef& device = entry(Dialect::Hybrid, "device_number");
  EXPECT_EQ(device.address, 0x1060);
  EXPECT_EQ(device.kind, RegisterKind::DeviceNumber);
  EXPECT_EQ(device.words, 2);
  EXPECT_EQ(device.value_text(0x31), "inverter");
  EXPECT_EQ(device.value_text(0x41), "wind-solar hybrid controller");
  EXPECT_EQ(device.values.size(), 7u);
}

TEST(RegisterMap, AsciiEntriesAreExact) {
  const RegisterDef& energy = entry(Dialect::Ascii, "cumulative_energy");
  EXPECT_EQ(energy.address, 0x0062);
  EXPECT_EQ(energy.words, 2);
  EXPECT_EQ(energy.pair_rule, PairRule::Decimal);
  EXPECT_DOUBLE_EQ(energy.scale, 0.001);
  EXPECT_EQ(energy.decimals, 3);
  EXPECT_EQ(entry(Dialect::Ascii, "phase_and_capacity").kind, RegisterKind::BcdPhaseCapacity);
  EXPECT_EQ(entry(Dialect::Ascii, "manufacture_date").kind, RegisterKind::BcdYearMonth);
  EXPECT_EQ(entry(Dialect::Ascii, "inverter_status").bit_name(14), "inverter running");
  EXPECT_EQ(entry(Dialect::Ascii, "line_frequency").address, 0x005C);
  // The pair covers 0x0062 and 0x0064: ASCII addresses step by 2.
  auto low = loaded(Dialect::Ascii).locate(0x0064);
  ASSERT_TRUE(low);
  EXPECT_EQ(low->def, &energy);
  EXPECT_EQ(low->word, 1);
  EXPECT_EQ(low->value_address, 0x0062);
  EXPECT_FALSE(loaded(Dialect::Ascii).locate(0x0063));
}

TEST(RegisterMap, GslEntriesAreExact) {
  const RegisterDef& model = entry(Dialect::Gsl, "model_name");
  EXPECT_EQ(model.address, 1000);
  EXPECT_EQ(model.kind, RegisterKind::Text);
  EXPECT_EQ(model.words, 5);
  EXPECT_EQ(entry(Dialect::Gsl, "manufacturer_name").address, 1005);
  EXPECT_EQ(entry(Dialect::Gsl, "grid_frequency").address, 1056);
  EXPECT_TRUE(entry(Dialect::Gsl, "power_factor_setting").is_signed);
  EXPECT_EQ(entry(Dialect::Gsl, "total_energy").pair_rule, PairRule::FromOptions);
  EXPECT_EQ(entry(Dialect::Gsl, "total_co2_reduction").address, 1094);
  EXPECT_EQ(entry(Dialect::Gsl, "on_off_command").value_text(0x5555), "start");
  EXPECT_EQ(entry(Dialect::Gsl, "on_off_command").value_text(0xAAAA), "stop");
  EXPECT_EQ(entry(Dialect::Gsl, "power_factor_mode").value_text(2), "lagging");
  EXPECT_EQ(entry(Dialect::Gsl, "clock_year").address, 1503);
  EXPECT_EQ(entry(Dialect::Gsl, "last_shutdown_second").address, 1084);
  EXPECT_EQ(entry(Dialect::Gsl, "status_word").bit_name(11), "feeding the grid");
  EXPECT_EQ(entry(Dialect::Gsl, "alarm_word_3").bit_name(13), "DSP fault protection");
  EXPECT_DOUBLE_EQ(entry(Dialect::Gsl, "energy_this_year").scale, 100.0);
}

TEST(RegisterMap, SingleEntryIsCarvedOutOfARange) {
  const RegisterMap& hybrid = loaded(Dialect::Hybrid);
  const RegisterDef& range = entry(Dialect::Hybrid, "manufacturer_parameter");
  EXPECT_TRUE(range.is_range());
  EXPECT_EQ(range.repeat, 0x55);
  auto before = hybrid.locate(0x105F);
  ASSERT_TRUE(before);
  EXPECT_EQ(before->def, &range);
  EXPECT_EQ(before->instance, 0x14);
  auto device = hybrid.locate(0x1061);
  ASSERT_TRUE(device);
  EXPECT_EQ(device->def->key, "device_number");
  EXPECT_EQ(device->word, 1);
  EXPECT_EQ(hybrid.find_address(0x104B), &range);
}

TEST(RegisterMap, FormatsAddressesAsTheReferenceWritesThem) {
  EXPECT_EQ(format_register_address(Dialect::Ascii, 0x0020).view(), "0x0020");
  EXPECT_EQ(format_register_address(Dialect::Ascii, 0x01E0).view(), "0x01E0");
  EXPECT_EQ(format_register_address(Dialect::Hybrid, 0x100E).view(), "0x100E");
  EXPECT_EQ(format_register_address(Dialect::Gsl, 1056).view(), "1056");
  EXPECT_EQ(format_register_address(Dialect::Gsl, 7).view(), "7");
}

TEST(RegisterMap, BuiltinMapIsParsedOnceAcrossThreads) {
  std::vector<const RegisterMap*> seen(4);
  std::vector<std::thread> threads;
  for (std::size_t i = 0; i < seen.size(); ++i) {
    threads.emplace_back([&seen, i] { seen[i] = &builtin_register_map(Dialect::Gsl); });
  }
  for (auto& t : threads) t.join();
  for (const RegisterMap* m : seen) EXPECT_EQ(m, seen[0]);
  EXPECT_EQ(seen[0]->registers().data(), builtin_register_map(Dialect::Gsl).registers().data());
}

TEST(RegisterMap, LoadsAMinimalMap) {
  RegisterMapResult result = load_register_map(kSmallRegisterMap, "small.toml");
  ASSERT_TRUE(result) << result.error_text();
  EXPECT_EQ(result->size(), 1u);
  EXPECT_EQ(result->title(), "small");
  EXPECT_EQ(result->registers()[0].line, 4u);
}

TEST(RegisterMap, SyntaxErrorNamesFileAndLine) {
  const std::string text = errors_of("dialect = \"gsl\"\n\n[[register]]\naddress = = 3\n");
  EXPECT_NE(text.find("test.toml:4:"), std::string::npos) << text;
}

TEST(RegisterMap, MissingOrUnknownDialectIsReported) {
  EXPECT_NE(errors_of("title = \"x\"\n").find("test.toml:1:1: the map must name its dialect"),
            std::string::npos);
  const std::string text = errors_of("\ndialect = \"profibus\"\n");
  EXPECT_NE(text.find("test.toml:2:"), std::string::npos) << text;
  EXPECT_NE(text.find("unknown dialect 'profibus'"), std::string::npos) << text;
}

TEST(RegisterMap, UnknownKindIsReportedAtItsLine) {
  const std::string text = errors_of(R"toml(dialect = "gsl"
[[register]]
address = 1050
key = "v"
name = "v"
kind = "float"
)toml");
  EXPECT_NE(text.find("test.toml:6:"), std::string::npos) << text;
  EXPECT_NE(text.find("unknown kind 'float'"), std::string::npos) << text;
}

TEST(RegisterMap, BitIndexAbove15IsReportedAtItsLine) {
  const std::string text = errors_of(R"toml(dialect = "gsl"
[[register]]
address = 1030
key = "alarms"
name = "alarms"
kind = "bits"
[register.bits]
0 = "first"
16 = "too far"
)toml");
  EXPECT_NE(text.find("test.toml:9:"), std::string::npos) << text;
  EXPECT_NE(text.find("bit 16 is out of range 0 .. 15"), std::string::npos) << text;
}

TEST(RegisterMap, DuplicateAddressAndKeyAreReported) {
  const std::string text = errors_of(R"toml(dialect = "hybrid"
[[register]]
address = 0x1006
key = "battery_voltage"
name = "battery voltage"

[[register]]
address = 0x1006
key = "battery_voltage_again"
name = "again"

[[register]]
address = 0x1007
key = "battery_voltage"
name = "same key"
)toml");
  EXPECT_NE(text.find("test.toml:7:1: register 'battery_voltage_again' (0x1006): duplicate "
                      "address, also defined at line 2"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("test.toml:12:1: register 'battery_voltage' (0x1007): key is already used "
                      "by the entry at line 2"),
            std::string::npos)
      << text;
}

TEST(RegisterMap, OverlappingPairIsReported) {
  const std::string text = errors_of(R"toml(dialect = "hybrid"
[[register]]
address = 0x100E
key = "energy"
name = "energy"
words = 2

[[register]]
address = 0x100F
key = "low_word"
name = "low word"
)toml");
  EXPECT_NE(text.find("test.toml:8:"), std::string::npos) << text;
  EXPECT_NE(text.find("overlaps register 'energy' (line 2)"), std::string::npos) << text;
}

TEST(RegisterMap, BadKeyCharactersAreReported) {
  const std::string text = errors_of(R"toml(dialect = "ascii"
[[register]]
address = 0x0020
key = "PV-Voltage"
name = "PV voltage"
)toml");
  EXPECT_NE(text.find("test.toml:2:"), std::string::npos) << text;
  EXPECT_NE(text.find("key must start with a lowercase letter"), std::string::npos) << text;
  EXPECT_NE(text.find("key may hold only lowercase letters, digits and '_'"), std::string::npos)
      << text;
}

TEST(RegisterMap, UnknownFieldsAndWrongTypesAreReported) {
  const std::string text = errors_of(R"toml(dialect = "gsl"
[[register]]
address = 1050
key = "v"
name = "v"
scael = 0.1
words = "two"
)toml");
  EXPECT_NE(text.find("test.toml:6:1: unknown register field 'scael'"), std::string::npos) << text;
  EXPECT_NE(text.find("test.toml:7:9: words must be an integer"), std::string::npos) << text;
}

TEST(RegisterMap, KindRulesAreChecked) {
  const std::string text = errors_of(R"toml(dialect = "gsl"
[[register]]
address = 1
key = "number_with_values"
name = "n"
kind = "number"
values = { 0 = "off" }

[[register]]
address = 2
key = "enum_too_big"
name = "e"
values = { 70000 = "huge" }

[[register]]
address = 3
key = "named_elsewhere"
name = "x"
values = "no_such_enum"

[[register]]
address = 4
key = "pair_rule_on_one_word"
name = "p"
combine = "decimal"

[[register]]
address = 5
key = "long_text"
name = "t"
kind = "text"
words = 17
)toml");
  EXPECT_NE(text.find("test.toml:2:1: register 'number_with_values' (1): 'values' needs kind enum"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("test.toml:13:12: register 'enum_too_big' (2): value 70000 does not fit"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("test.toml:19:10: no enum named 'no_such_enum'"), std::string::npos) << text;
  EXPECT_NE(text.find("'combine' applies only to 2-word registers"), std::string::npos) << text;
  EXPECT_NE(text.find("a text register is 1 to 16 word(s) wide, not 17"), std::string::npos)
      << text;
}

TEST(RegisterMap, AsciiRangeMustStepByTwo) {
  const std::string text = errors_of(R"toml(dialect = "ascii"
[[register]]
address = 0x0100
last = 0x0103
key = "block"
name = "block"
kind = "raw"
)toml");
  EXPECT_NE(text.find("test.toml:4:"), std::string::npos) << text;
}

constexpr std::string_view kUserExtension = R"toml(dialect = "hybrid"
mode = "extend"

# the site's firmware reports battery voltage in 0.01 V
[[register]]
address = 0x1006
key = "battery_voltage"
name = "battery voltage (fine)"
scale = 0.01
unit = "V"

[[register]]
address = 0x1050
key = "site_limit"
name = "site export limit"
unit = "W"
)toml";

TEST(RegisterMap, UserMapOverridesAndExtendsTheBuiltinMap) {
  RegisterMapResult user = load_register_map(kUserExtension, "site.toml");
  ASSERT_TRUE(user) << user.error_text();
  EXPECT_EQ(user->mode(), MapMode::Extend);
  RegisterMapResult merged = resolve_user_register_map(user.value());
  ASSERT_TRUE(merged) << merged.error_text();
  const RegisterMap& map = merged.value();
  EXPECT_EQ(map.size(), builtin_register_map(Dialect::Hybrid).size() + 1);
  EXPECT_EQ(map.source_name(), "builtin:hybrid.toml + site.toml");
  const RegisterDef* battery = map.find_key("battery_voltage");
  ASSERT_NE(battery, nullptr);
  EXPECT_EQ(battery->name, "battery voltage (fine)");
  EXPECT_DOUBLE_EQ(battery->scale, 0.01);
  EXPECT_EQ(battery->decimals, 2);
  // The user's single carves 0x1050 out of the manufacturer range, which stays.
  EXPECT_EQ(map.locate(0x1050)->def->key, "site_limit");
  EXPECT_EQ(map.locate(0x1051)->def->key, "manufacturer_parameter");
  EXPECT_EQ(map.find_key("working_mode")->value_text(1), "battery priority");
  EXPECT_EQ(map.find_key("fault_code_1")->bit_name(6), "output short circuit");
}

// Two extend files for one dialect stack in order, in pvtap as in the plugin; a replace file
// after them stands alone.
TEST(RegisterMap, ExtendMapsStackInTheOrderGiven) {
  RegisterMapResult first = load_register_map(kUserExtension, "site.toml");
  RegisterMapResult second = load_register_map(R"toml(dialect = "hybrid"
mode = "extend"
[[register]]
address = 0x1051
key = "site_reserve"
name = "site reserve"
unit = "W"
)toml",
                                               "reserve.toml");
  ASSERT_TRUE(first) << first.error_text();
  ASSERT_TRUE(second) << second.error_text();
  RegisterMapResult one = stack_register_map(builtin_register_map(Dialect::Hybrid), first.value());
  ASSERT_TRUE(one) << one.error_text();
  RegisterMapResult both = stack_register_map(one.value(), second.value());
  ASSERT_TRUE(both) << both.error_text();
  EXPECT_EQ(both->locate(0x1050)->def->key, "site_limit") << "the first file's entry stays";
  EXPECT_EQ(both->locate(0x1051)->def->key, "site_reserve");
  EXPECT_DOUBLE_EQ(both->find_key("battery_voltage")->scale, 0.01);
  RegisterMapResult replace = load_register_map(R"toml(dialect = "hybrid"
mode = "replace"
[[register]]
address = 0x1000
key = "only"
name = "only register"
)toml",
                                                "replace.toml");
  ASSERT_TRUE(replace) << replace.error_text();
  RegisterMapResult alone = stack_register_map(both.value(), replace.value());
  ASSERT_TRUE(alone) << alone.error_text();
  EXPECT_EQ(alone->size(), 1u);
}

TEST(RegisterMap, UserKeyMovesTheBuiltinEntry) {
  RegisterMapResult user = load_register_map(R"toml(dialect = "gsl"
mode = "extend"
[[register]]
address = 3000
key = "grid_frequency"
name = "grid frequency (moved)"
scale = 0.01
unit = "Hz"
)toml",
                                             "moved.toml");
  ASSERT_TRUE(user) << user.error_text();
  RegisterMapResult merged = resolve_user_register_map(user.value());
  ASSERT_TRUE(merged) << merged.error_text();
  EXPECT_FALSE(merged->locate(1056));
  EXPECT_EQ(merged->find_key("grid_frequency")->address, 3000);
}

TEST(RegisterMap, ReplacingMapStandsAlone) {
  RegisterMapResult user = load_register_map(kSmallRegisterMap, "small.toml");
  ASSERT_TRUE(user);
  RegisterMapResult resolved = resolve_user_register_map(user.value());
  ASSERT_TRUE(resolved);
  EXPECT_EQ(resolved->size(), 1u);
}

TEST(RegisterMap, MergeRefusesAnotherDialect) {
  RegisterMapResult user = load_register_map(kSmallRegisterMap, "small.toml");
  ASSERT_TRUE(user);
  RegisterMapResult merged = merge_register_maps(builtin_register_map(Dialect::Gsl), user.value());
  EXPECT_FALSE(merged);
  EXPECT_NE(merged.error_text().find("small.toml: a hybrid map cannot extend a gsl map"),
            std::string::npos)
      << merged.error_text();
}

TEST(RegisterMap, MapOutlivesCopiesAndKeepsItsViews) {
  std::string_view name;
  RegisterMap copy;
  {
    RegisterMapResult result = load_register_map(kSmallRegisterMap, "small.toml");
    ASSERT_TRUE(result);
    copy = result.value();
    name = copy.registers()[0].name;
  }
  EXPECT_EQ(name, "battery voltage");
  EXPECT_EQ(copy.find_key("battery_voltage")->unit, "V");
}

}  // namespace
}  // namespace pvtap
