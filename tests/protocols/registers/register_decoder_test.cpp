// The table-driven register decoder against the seed's values (PROTOCOLS.md section 5).
#include "pvtap/registers/register_decoder.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "frame_builders.h"
#include "pvtap/codec/function_codes.h"
#include "pvtap/registers/register_format.h"

namespace pvtap {
namespace {

Frame hybrid_reply(std::uint8_t function, WordList words) {
  Frame f;
  f.dialect = Dialect::Hybrid;
  f.role = Role::Response;
  f.station = 6;
  f.function = function;
  f.byte_count = static_cast<std::uint8_t>(4 + 2 * words.size());
  f.device = DeviceNumber{0x31, 103};
  f.words = words;
  return f;
}

Frame gsl_reply(WordList words) {
  Frame f;
  f.dialect = Dialect::Gsl;
  f.role = Role::Response;
  f.station = 1;
  f.function = fc::kGslReadHolding;
  f.byte_count = static_cast<std::uint8_t>(2 * words.size());
  f.words = words;
  return f;
}

// Decodes a frame and returns its values keyed for easy lookup.
struct Decoded {
  DecodeReport report;
  std::vector<DecodedValue> values;

  const DecodedValue& at(std::string_view key) const {
    for (const DecodedValue& v : values) {
      if (v.key() == key) return v;
    }
    throw std::runtime_error("no value " + std::string(key));
  }
  std::string text(std::string_view key) const { return format_value(at(key)); }
};

Decoded decode(const Frame& frame, const Frame* request = nullptr, DecoderOptions options = {}) {
  Decoded d;
  d.report = RegisterDecoder(options).decode(frame, request, d.values);
  return d;
}

std::vector<std::string_view> bit_names(const DecodedValue& v) {
  std::vector<std::string_view> names;
  for (const BitName b : v.set_bits()) names.push_back(b.name);
  return names;
}

TEST(RegisterDecoder, AsciiFaultWordsOfTheSeed) {
  const Decoded d = decode(test::ascii_reply(1, 0x0004, {0x0008, 0x40A2, 0x0021, 0x0000}));
  ASSERT_EQ(d.report.status, DecodeStatus::Decoded);
  ASSERT_EQ(d.values.size(), 4u);
  EXPECT_EQ(d.values[1].address, 0x0006);  // addresses step by 2
  EXPECT_EQ(d.values[3].key(), "reserved_000a");
  EXPECT_EQ(bit_names(d.at("solar_fault")),
            (std::vector<std::string_view>{"PV under-voltage limit exceeded"}));
  EXPECT_EQ(bit_names(d.at("inverter_status")),
            (std::vector<std::string_view>{"over-current time exceeded",
                                           "inverter fuse open (transformer type only)",
                                           "over-temperature", "inverter running"}));
  EXPECT_EQ(bit_names(d.at("line_fault")),
            (std::vector<std::string_view>{"line over-voltage", "under-frequency"}));
  EXPECT_EQ(d.at("inverter_status").warnings, 0);
}

TEST(RegisterDecoder, AsciiPvWordsOfTheSeed) {
  const Decoded d = decode(test::ascii_reply(1, 0x0020, {266, 57}));
  EXPECT_DOUBLE_EQ(d.at("pv_voltage").value, 266.0);
  EXPECT_DOUBLE_EQ(d.at("pv_current").value, 5.7);
  EXPECT_EQ(d.at("pv_current").unit(), "A");
  EXPECT_EQ(d.text("pv_voltage"), "266 V");
  EXPECT_EQ(d.text("pv_current"), "5.7 A");
}

TEST(RegisterDecoder, AsciiLineWordsOfTheSeed) {
  const Decoded d = decode(test::ascii_reply(1, 0x0050, {217, 0, 0, 65, 0, 0, 601}));
  ASSERT_EQ(d.values.size(), 7u);
  EXPECT_DOUBLE_EQ(d.at("line_voltage_r").value, 217.0);
  EXPECT_DOUBLE_EQ(d.at("line_voltage_t").value, 0.0);
  EXPECT_DOUBLE_EQ(d.at("line_current_r").value, 6.5);
  EXPECT_DOUBLE_EQ(d.at("line_frequency").value, 60.1);
  EXPECT_EQ(d.at("line_frequency").address, 0x005C);
  EXPECT_EQ(d.text("line_frequency"), "60.1 Hz");
}

TEST(RegisterDecoder, AsciiPowerWordsOfTheSeed) {
  const Decoded d =
      decode(test::ascii_reply(1, 0x0060, {2724, 57, 230, 2518, 2980, 998, 11340, 0}));
  ASSERT_EQ(d.values.size(), 7u);  // the energy pair takes two words
  EXPECT_EQ(d.text("pv_power"), "2.724 kW");
  const DecodedValue& energy = d.at("cumulative_energy");
  EXPECT_EQ(energy.raw, 570230u);
  EXPECT_NEAR(energy.value, 570.230, 1e-9);
  EXPECT_EQ(energy.words_present, 2);
  EXPECT_EQ(energy.warnings, 0);
  EXPECT_EQ(d.text("cumulative_energy"), "570.230 kWh");
  EXPECT_EQ(d.text("inverter_output_power"), "2.518 kW");
  EXPECT_EQ(d.text("inverter_max_output_power"), "2.980 kW");
  EXPECT_EQ(d.text("power_factor"), "99.8 %");
  EXPECT_EQ(d.text("energy_today"), "1134.0 kWh");
  EXPECT_EQ(d.at("unused_006e").address, 0x006E);
}

TEST(RegisterDecoder, AsciiSystemWordsOfTheSeed) {
  const Decoded d = decode(test::ascii_reply(1, 0x01E0, {0x1030, 0x0510, 0x0001}));
  const DecodedValue& capacity = d.at("phase_and_capacity");
  EXPECT_EQ(capacity.bcd.first, 1);
  EXPECT_EQ(capacity.bcd.second, 30);
  EXPECT_DOUBLE_EQ(capacity.value, 3.0);
  EXPECT_EQ(d.text("phase_and_capacity"), "single phase, 3.0 kW");
  const DecodedValue& date = d.at("manufacture_date");
  EXPECT_EQ(date.bcd.first, 2005);
  EXPECT_EQ(date.bcd.second, 10);
  EXPECT_EQ(d.text("manufacture_date"), "2005-10");
  EXPECT_DOUBLE_EQ(d.at("serial_number").value, 1.0);
  EXPECT_EQ(d.text("serial_number"), "1");
}

TEST(RegisterDecoder, AsciiLowPartAbove9999IsWarned) {
  const Decoded d = decode(test::ascii_reply(1, 0x0062, {57, 10230}));
  const DecodedValue& energy = d.at("cumulative_energy");
  EXPECT_TRUE(energy.has(ValueWarning::LowPartOver9999));
  EXPECT_EQ(energy.raw, 57u * 10000u + 10230u);
  EXPECT_FALSE(decode(test::ascii_reply(1, 0x0062, {57, 9999}))
                   .at("cumulative_energy")
                   .has(ValueWarning::LowPartOver9999));
}

TEST(RegisterDecoder, PairSplitByTheReadIsIncomplete) {
  const Decoded tail = decode(test::ascii_reply(1, 0x0060, {2724, 57}));
  const DecodedValue& high_only = tail.at("cumulative_energy");
  EXPECT_FALSE(high_only.complete());
  EXPECT_EQ(high_only.words_present, 1);
  EXPECT_DOUBLE_EQ(high_only.value, 0.0);
  EXPECT_EQ(format_value(high_only), "incomplete (1 of 2 words in the frame)");

  const Decoded head = decode(test::ascii_reply(1, 0x0064, {230, 2518}));
  ASSERT_EQ(head.values.size(), 2u);
  EXPECT_TRUE(head.values[0].has(ValueWarning::Incomplete));
  EXPECT_EQ(head.values[0].address, 0x0062);
  EXPECT_EQ(head.values[0].wire_address, 0x0064);
  EXPECT_EQ(head.values[1].key(), "inverter_output_power");
}

TEST(RegisterDecoder, HybridRunningDataWithItsRequest) {
  WordList words{2300, 2310, 2295, 5000, 2, 450,    523,    412,
                 3,    1000, 5002, 1,    3, 0x0429, 0x0001, 0x0002};
  const Frame request = test::read_request(Dialect::Hybrid, 6, fc::kHybridRunningData, 0x1000, 16);
  const Decoded d = decode(hybrid_reply(fc::kHybridRunningData, words), &request);
  ASSERT_EQ(d.report.status, DecodeStatus::Decoded);
  EXPECT_FALSE(d.report.start_assumed);
  EXPECT_FALSE(d.report.count_mismatch);
  EXPECT_EQ(d.report.start, 0x1000);
  ASSERT_EQ(d.values.size(), 15u);
  EXPECT_EQ(d.text("battery_voltage"), "52.3 V");
  EXPECT_EQ(d.at("battery_voltage").wire_address, 0x1006);
  EXPECT_EQ(d.text("inverter_output_frequency"), "50.00 Hz");
  EXPECT_EQ(d.at("working_mode").enum_text, "grid priority");
  EXPECT_EQ(d.at("inverter_running_state").enum_text, "inverting normally");
  EXPECT_EQ(d.text("pv_controller_fan"), "on");
  EXPECT_EQ(bit_names(d.at("internal_state")),
            (std::vector<std::string_view>{"diesel start/stop command (1 run)",
                                           "energy-saving mode allowed", "bypass relay closed",
                                           "inverter phase-locked"}));
  const DecodedValue& energy = d.at("total_discharge_energy");
  EXPECT_EQ(energy.raw, 65538u);
  EXPECT_EQ(d.text("total_discharge_energy"), "6553.8 kWh");
}

TEST(RegisterDecoder, HybridReplyWithoutRequestAssumesTheDefaultStart) {
  const Frame reply = hybrid_reply(fc::kHybridSettings, {2880, 2840, 2700});
  const Decoded d = decode(reply);
  ASSERT_EQ(d.report.status, DecodeStatus::Decoded);
  EXPECT_TRUE(d.report.start_assumed);
  EXPECT_EQ(d.report.start, 0x1024);
  EXPECT_EQ(d.values[0].key(), "battery_over_voltage");
  EXPECT_EQ(d.text("over_voltage_recovery_voltage"), "270.0 V");
  EXPECT_NE(describe(d.report).find("assumed"), std::string_view::npos);

  // A request of another function code does not belong to this reply.
  const Frame other = test::read_request(Dialect::Hybrid, 6, fc::kHybridRunningData, 0x1000, 3);
  const Decoded mismatched = decode(reply, &other);
  EXPECT_TRUE(mismatched.report.start_assumed);
  EXPECT_TRUE(mismatched.report.request_unusable);
  EXPECT_EQ(mismatched.values[0].key(), "battery_over_voltage");
}

TEST(RegisterDecoder, HybridCountMismatchIsFlagged) {
  const Frame request = test::read_request(Dialect::Hybrid, 6, fc::kHybridSettings, 0x1024, 0x1A);
  const Decoded d = decode(hybrid_reply(fc::kHybridSettings, {2880, 2840}), &request);
  EXPECT_TRUE(d.report.count_mismatch);
  EXPECT_EQ(d.values.size(), 2u);
}

TEST(RegisterDecoder, HybridDeviceNumber) {
  // 06 11 08 31 00 00 67 31 00 00 67: device info of inverter no. 103.
  const Decoded d = decode(hybrid_reply(fc::kHybridDeviceInfo, {0x3100, 0x0067}));
  ASSERT_EQ(d.values.size(), 1u);
  const DecodedValue& device = d.at("device_number");
  EXPECT_TRUE(d.report.start_assumed);
  EXPECT_EQ(device.device.type_code, 0x31);
  EXPECT_EQ(device.device.serial, 103u);
  EXPECT_EQ(device.enum_text, "inverter");
  EXPECT_EQ(format_value(device), "31 inverter, serial 103");

  const DecodedValue header = RegisterDecoder().decode_device_number(DeviceNumber{0x22, 107});
  EXPECT_EQ(header.origin, ValueOrigin::DeviceHeader);
  EXPECT_EQ(header.key(), "device_number");
  EXPECT_EQ(header.enum_text, "PWM controller");
  EXPECT_EQ(header.device.serial, 107u);
  EXPECT_EQ(format_value(header), "22 PWM controller, serial 107");

  const DecodedValue unknown = RegisterDecoder().decode_device_number(DeviceNumber{0x99, 1});
  EXPECT_TRUE(unknown.has(ValueWarning::UnknownEnumValue));
}

TEST(RegisterDecoder, HybridWriteRequestAndEcho) {
  Frame request = test::read_request(Dialect::Hybrid, 6, fc::kHybridWriteParameter, 0x102A, 0);
  request.count.reset();
  request.words = WordList{0x093C};
  const Decoded written = decode(request);
  ASSERT_EQ(written.values.size(), 1u);
  EXPECT_EQ(written.report.origin, ValueOrigin::WriteRequest);
  EXPECT_EQ(written.values[0].key(), "over_discharge_voltage");
  EXPECT_EQ(format_value(written.values[0]), "236.4 V");

  Frame echo = hybrid_reply(fc::kHybridWriteParameter, {0x093C});
  echo.start = 0x102A;
  const Decoded echoed = decode(echo);
  ASSERT_EQ(echoed.values.size(), 1u);
  EXPECT_EQ(echoed.values[0].origin, ValueOrigin::WriteReply);
  EXPECT_DOUBLE_EQ(echoed.values[0].value, 236.4);
}

TEST(RegisterDecoder, FramesWithoutRegisterValues) {
  Frame restore = hybrid_reply(fc::kHybridRestoreFactory, {});
  restore.start = 0x1024;
  restore.count = 0x7B;
  EXPECT_EQ(decode(restore).report.status, DecodeStatus::NoRegisterData);
  Frame error = hybrid_reply(fc::kHybridError, {});
  EXPECT_EQ(decode(error).report.status, DecodeStatus::NoRegisterData);
  const Frame read = test::read_request(Dialect::Gsl, 6, fc::kGslReadHolding, 0x041A, 3);
  const Decoded d = decode(read);
  EXPECT_EQ(d.report.status, DecodeStatus::NoRegisterData);
  EXPECT_TRUE(d.values.empty());
}

TEST(RegisterDecoder, HybridManufacturerBlockUsesTheRange) {
  WordList words;
  for (unsigned i = 0; i < 0x55; ++i) words.push_back(static_cast<std::uint16_t>(i));
  const Decoded d = decode(hybrid_reply(fc::kHybridManufacturer, words));
  ASSERT_EQ(d.values.size(), 0x55u - 1u);  // the device number takes two words
  EXPECT_EQ(d.values[0].key(), "manufacturer_parameter");
  EXPECT_EQ(d.values[0].instance, 0);
  EXPECT_EQ(d.values[0x15].key(), "device_number");
  EXPECT_EQ(d.values[0x16].address, 0x1062);
  EXPECT_EQ(d.values[0x16].instance, 0x17);
  EXPECT_EQ(format_value(d.values[1]), "0x0001");
}

TEST(RegisterDecoder, GslReadWithDecimalIds) {
  const Frame request = test::read_request(Dialect::Gsl, 6, fc::kGslReadHolding, 0x041A, 3);
  const Decoded d = decode(gsl_reply({2200, 2210, 2190}), &request);
  ASSERT_EQ(d.values.size(), 3u);
  EXPECT_EQ(d.values[0].key(), "grid_voltage_ab");
  EXPECT_EQ(d.values[0].address, 1050);
  EXPECT_EQ(d.values[0].wire_address, 0x041A);
  EXPECT_EQ(format_value(d.values[2]), "219.0 V");
  EXPECT_EQ(format_value_address(d.values[2], Dialect::Gsl).view(), "1052");
}

TEST(RegisterDecoder, GslReadWithHexIds) {
  DecoderOptions hex;
  hex.gsl_ids = GslIdReading::Hex;
  const Frame request = test::read_request(Dialect::Gsl, 6, fc::kGslReadHolding, 0x1050, 3);
  const Decoded d = decode(gsl_reply({2200, 2210, 2190}), &request, hex);
  ASSERT_EQ(d.values.size(), 3u);
  EXPECT_EQ(d.values[0].key(), "grid_voltage_ab");
  EXPECT_EQ(d.values[0].address, 1050);
  EXPECT_EQ(d.values[0].wire_address, 0x1050);

  // Read with the decimal default, 0x1050 is ID 4176, which the map does not know.
  const Decoded decimal = decode(gsl_reply({2200}), &request);
  ASSERT_EQ(decimal.values.size(), 1u);
  EXPECT_TRUE(decimal.values[0].has(ValueWarning::NotInMap));
  EXPECT_EQ(decimal.values[0].address, 4176);
}

TEST(RegisterDecoder, GslHexIdsSkipAddressesWithHexDigits) {
  DecoderOptions hex;
  hex.gsl_ids = GslIdReading::Hex;
  const Frame request = test::read_request(Dialect::Gsl, 6, fc::kGslReadHolding, 0x1099, 2);
  const Decoded d = decode(gsl_reply({1, 2}), &request, hex);
  ASSERT_EQ(d.values.size(), 2u);
  EXPECT_EQ(d.values[0].key(), "reserved_1096");
  EXPECT_TRUE(d.values[1].has(ValueWarning::NoWrittenAddress));
  EXPECT_EQ(format_value_address(d.values[1], Dialect::Gsl).view(), "0x109A");
}

TEST(RegisterDecoder, GslReplyWithoutRequestCannotBePlaced) {
  const Decoded d = decode(gsl_reply({2200, 2210}));
  EXPECT_EQ(d.report.status, DecodeStatus::StartUnknown);
  EXPECT_TRUE(d.values.empty());
  EXPECT_NE(describe(d.report).find("request"), std::string_view::npos);
}

TEST(RegisterDecoder, GslPairUnderBothRules) {
  const Frame request = test::read_request(Dialect::Gsl, 6, fc::kGslReadHolding, 1086, 2);
  const Frame reply = gsl_reply({0x0001, 0x0002});
  const Decoded binary = decode(reply, &request);
  EXPECT_EQ(binary.at("total_energy").raw, 65538u);
  EXPECT_EQ(binary.text("total_energy"), "6553.8 kWh");

  DecoderOptions decimal;
  decimal.pair_rule = PairRule::Decimal;
  const Decoded ten_thousands = decode(reply, &request, decimal);
  EXPECT_EQ(ten_thousands.at("total_energy").raw, 10002u);
  EXPECT_EQ(ten_thousands.text("total_energy"), "1000.2 kWh");

  const Frame big_low = gsl_reply({0x0001, 12000});
  EXPECT_TRUE(
      decode(big_low, &request, decimal).at("total_energy").has(ValueWarning::LowPartOver9999));
  EXPECT_FALSE(decode(big_low, &request).at("total_energy").has(ValueWarning::LowPartOver9999));
}

TEST(RegisterDecoder, GslPairCutByTheReadIsIncomplete) {
  const Frame request = test::read_request(Dialect::Gsl, 6, fc::kGslReadHolding, 1085, 2);
  const Decoded d = decode(gsl_reply({12, 0x0001}), &request);
  ASSERT_EQ(d.values.size(), 2u);
  EXPECT_EQ(d.text("grid_connected_time_today"), "1.2 h");
  EXPECT_TRUE(d.at("total_energy").has(ValueWarning::Incomplete));
}

TEST(RegisterDecoder, GslTextRegisters) {
  const Frame request = test::read_request(Dialect::Gsl, 6, fc::kGslReadHolding, 1000, 10);
  const Decoded d = decode(gsl_reply({0x4753, 0x4C30, 0x3030, 0x3530, 0x304B,    // GSL000500K
                                      0x4B53, 0x5441, 0x5253, 0x4F4C, 0x4152}),  // KSTARSOLAR
                           &request);
  ASSERT_EQ(d.values.size(), 2u);
  EXPECT_EQ(d.at("model_name").text(), "GSL000500K");
  EXPECT_EQ(d.text("manufacturer_name"), "KSTARSOLAR");

  const Frame short_name = gsl_reply({0x4B53, 0x5441, 0x5200, 0x0000, 0x0000});
  const Frame second = test::read_request(Dialect::Gsl, 6, fc::kGslReadHolding, 1005, 5);
  const Decoded padded = decode(short_name, &second);
  EXPECT_EQ(padded.at("manufacturer_name").text(), "KSTAR");
  EXPECT_EQ(padded.at("manufacturer_name").warnings, 0);
}

TEST(RegisterDecoder, GslSignedPowerFactor) {
  const Frame request = test::read_request(Dialect::Gsl, 6, fc::kGslReadHolding, 1092, 2);
  const Decoded d = decode(gsl_reply({0xFFA1, 98}), &request);  // -95, 98
  EXPECT_EQ(d.at("power_factor_setting").signed_raw, -95);
  EXPECT_DOUBLE_EQ(d.at("power_factor_setting").value, -0.95);
  EXPECT_EQ(d.text("power_factor_setting"), "-0.95");
  EXPECT_DOUBLE_EQ(d.at("total_power_factor").value, 0.98);  // unsigned entries stay unsigned
}

TEST(RegisterDecoder, GslBitsAndUnnamedBits) {
  const Frame request = test::read_request(Dialect::Gsl, 6, fc::kGslReadHolding, 1033, 1);
  const Decoded d = decode(gsl_reply({0x0830 | 0x0001}), &request);
  const DecodedValue& status = d.at("status_word");
  std::vector<BitName> bits(status.set_bits().begin(), status.set_bits().end());
  ASSERT_EQ(bits.size(), 4u);
  EXPECT_EQ(bits[0].index, 0);
  EXPECT_EQ(bits[0].name, "");
  EXPECT_EQ(bits[1].name, "AC output switch closed");
  EXPECT_EQ(bits[3].name, "feeding the grid");
  EXPECT_TRUE(status.has(ValueWarning::UnnamedBitSet));
  EXPECT_EQ(format_value(status), "bit 0, AC output switch closed, inverter on, feeding the grid");
}

TEST(RegisterDecoder, GslOnOffCommandEnum) {
  Frame write = test::read_request(Dialect::Gsl, 6, fc::kGslWriteSingle, 2010, 0);
  write.count.reset();
  write.words = WordList{0x5555};
  const Decoded start = decode(write);
  EXPECT_EQ(start.report.origin, ValueOrigin::WriteRequest);
  EXPECT_EQ(start.at("on_off_command").enum_text, "start");

  write.words = WordList{0x1234};
  const Decoded invalid = decode(write);
  EXPECT_TRUE(invalid.at("on_off_command").has(ValueWarning::UnknownEnumValue));
  EXPECT_EQ(invalid.text("on_off_command"), "unknown value 4660");

  Frame echo = write;
  echo.role = Role::Response;
  echo.words = WordList{0xAAAA};
  const Decoded stopped = decode(echo);
  EXPECT_EQ(stopped.report.origin, ValueOrigin::WriteReply);
  EXPECT_EQ(stopped.text("on_off_command"), "stop");
}

TEST(RegisterDecoder, GslWriteMultipleClock) {
  Frame write = test::read_request(Dialect::Gsl, 6, fc::kGslWriteMultiple, 1500, 6);
  write.byte_count = 12;
  write.words = WordList{13, 45, 7, 2011, 6, 30};
  const Decoded d = decode(write);
  ASSERT_EQ(d.values.size(), 6u);
  EXPECT_EQ(d.text("clock_hour"), "13");
  EXPECT_EQ(d.text("clock_year"), "2011");
  EXPECT_EQ(d.values[5].key(), "clock_day");
  EXPECT_EQ(d.values[5].origin, ValueOrigin::WriteRequest);
}

TEST(RegisterDecoder, UnmappedWordsAreStillReported) {
  const Frame request = test::read_request(Dialect::Gsl, 6, fc::kGslReadHolding, 1040, 1);
  const Decoded d = decode(gsl_reply({0xBEEF}), &request);
  ASSERT_EQ(d.values.size(), 1u);
  EXPECT_EQ(d.values[0].def, nullptr);
  EXPECT_TRUE(d.values[0].has(ValueWarning::NotInMap));
  EXPECT_EQ(format_value(d.values[0]), "0xBEEF");
}

TEST(RegisterDecoder, UsesAUserMap) {
  RegisterMapResult user = load_register_map(R"toml(dialect = "gsl"
mode = "extend"
[[register]]
address = 1040
key = "site_meter"
name = "site meter"
scale = 0.5
unit = "kW"
)toml",
                                             "site.toml");
  ASSERT_TRUE(user) << user.error_text();
  RegisterMapResult merged = resolve_user_register_map(user.value());
  ASSERT_TRUE(merged) << merged.error_text();
  RegisterDecoder decoder;
  decoder.use_map(merged.value());
  std::vector<DecodedValue> out;
  const Frame request = test::read_request(Dialect::Gsl, 6, fc::kGslReadHolding, 1040, 1);
  decoder.decode(gsl_reply({5}), &request, out);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(out[0].key(), "site_meter");
  EXPECT_EQ(format_value(out[0]), "2.5 kW");
}

TEST(RegisterDecoder, ReusedOutputDoesNotGrowAfterWarmUp) {
  RegisterDecoder decoder;
  std::vector<DecodedValue> out;
  const Frame power = test::ascii_reply(1, 0x0060, {2724, 57, 230, 2518, 2980, 998, 11340, 0});
  decoder.decode(power, nullptr, out);
  const DecodedValue* storage = out.data();
  const std::size_t capacity = out.capacity();
  for (int i = 0; i < 100; ++i) {
    out.clear();
    const DecodeReport report = decoder.decode(power, nullptr, out);
    EXPECT_EQ(report.first, 0u);
    EXPECT_EQ(report.count, 7u);
  }
  EXPECT_EQ(out.data(), storage);
  EXPECT_EQ(out.capacity(), capacity);
}

TEST(RegisterDecoder, AppendsAfterExistingValues) {
  RegisterDecoder decoder;
  std::vector<DecodedValue> out;
  decoder.decode(test::ascii_reply(1, 0x0020, {266, 57}), nullptr, out);
  const DecodeReport second = decoder.decode(test::ascii_reply(1, 0x0050, {217}), nullptr, out);
  EXPECT_EQ(second.first, 2u);
  EXPECT_EQ(second.count, 1u);
  EXPECT_EQ(out[2].key(), "line_voltage_r");
}

TEST(RegisterDecoder, WireAddressMapping) {
  EXPECT_EQ(wire_address_of(Dialect::Gsl, 1050, GslIdReading::Decimal), 0x041A);
  EXPECT_EQ(wire_address_of(Dialect::Gsl, 1050, GslIdReading::Hex), 0x1050);
  EXPECT_EQ(written_address_of(Dialect::Gsl, 0x1050, GslIdReading::Hex), 1050);
  EXPECT_EQ(written_address_of(Dialect::Gsl, 0x105A, GslIdReading::Hex), std::nullopt);
  EXPECT_EQ(wire_address_of(Dialect::Gsl, 12000, GslIdReading::Hex), std::nullopt);
  EXPECT_EQ(wire_address_of(Dialect::Hybrid, 0x1006, GslIdReading::Hex), 0x1006);
}

}  // namespace
}  // namespace pvtap
