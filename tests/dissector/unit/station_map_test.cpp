// Station register maps: the station lists of the table's rows, and a station's own map in the
// plan and the tree (the generic map fields, as no field exists for its entries).
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "frame_builders.h"
#include "plan_support.h"
#include "settings/station_list.h"

namespace pvtap::dissector::test {
namespace {

using pvtap::test::read_request;
using Lines = std::vector<std::string>;

TEST(StationList, OneOrSeveralStations) {
  EXPECT_EQ(read_station_list("10").stations, (std::vector<std::uint8_t>{10}));
  EXPECT_EQ(read_station_list(" 10, 11 ,247").stations, (std::vector<std::uint8_t>{10, 11, 247}));
  EXPECT_TRUE(read_station_list("1").ok());
}

TEST(StationList, EveryBadListSaysWhy) {
  EXPECT_EQ(read_station_list("").problem,
            "no station given: write one like 10, or several like 10,11");
  EXPECT_EQ(read_station_list("248").problem,
            "'248' is not a station: stations are 1 to 247 (0 is the broadcast address)");
  EXPECT_EQ(read_station_list("0").problem,
            "'0' is not a station: stations are 1 to 247 (0 is the broadcast address)");
  EXPECT_EQ(read_station_list("10,,11").problem,
            "an empty item is not a station: stations are 1 to 247 (0 is the broadcast address)");
  EXPECT_EQ(read_station_list("1O").problem,
            "'1O' is not a station: stations are 1 to 247 (0 is the broadcast address)");
  EXPECT_EQ(read_station_list("10,11,10").problem, "station 10 is named twice");
  EXPECT_FALSE(read_station_list("10;11").ok());
}

constexpr const char* kMeterMap = R"(
dialect = "modbus"
[[register]]
address = 0x0000
key = "voltage_l1"
name = "voltage phase 1"
scale = 0.1
unit = "V"
[[register]]
address = 0x0001
key = "energy"
name = "energy"
words = 2
scale = 0.01
unit = "kWh"
[[register]]
address = 0x0003
key = "model"
name = "model"
kind = "text"
words = 2
)";

RegisterMap meter_map() {
  RegisterMapResult loaded = load_register_map(kMeterMap, "meter.toml");
  EXPECT_TRUE(loaded) << loaded.error_text();
  return loaded.value();
}

std::vector<std::uint8_t> input_reply(std::uint8_t station, const std::vector<std::uint16_t>& w) {
  Frame f = make_frame(Dialect::Modbus, Role::Response, station, fc::kGslReadInput);
  f.byte_count = static_cast<std::uint8_t>(2 * w.size());
  for (std::uint16_t word : w) f.words.push_back(word);
  return wire(f);
}

// The meter at station 10 answers a read of its five registers from 0.
struct MeterRead {
  std::vector<std::uint8_t> request =
      wire(read_request(Dialect::Modbus, 10, fc::kGslReadInput, 0x0000, 5));
  FrameRecord asked = request_record(request, Dialect::Modbus, 1);
  FrameRecord reply = record_of(Dialect::Modbus, Role::Response, 2);
  std::vector<std::uint8_t> bytes = input_reply(10, {2301, 0x0001, 0x86A0, 0x504D, 0x3130});

  MeterRead() { reply.placed_by = &asked; }
};

TEST(StationMapPlan, ValuesOfTheStationsOwnMapCarryTheirKeyAndText) {
  Planner p;
  p.decoder.use_station_map(10, meter_map());
  MeterRead read;
  const FramePlan plan = p.plan(read.bytes, read.reply);
  ASSERT_EQ(plan.value_count, 3u);
  EXPECT_STREQ(plan.values[0].map_key, "voltage_l1");
  EXPECT_STREQ(plan.values[0].map_value, "voltage phase 1: 230.1 V");
  EXPECT_STREQ(plan.values[0].label, "voltage phase 1 (0x0000)");
  EXPECT_STREQ(plan.values[1].map_value, "energy: 1000.00 kWh");
  EXPECT_STREQ(plan.values[2].map_value, "model: PM10");
}

TEST(StationMapPlan, OtherStationsHaveNoMapFields) {
  Planner p;
  p.decoder.use_station_map(11, meter_map());
  MeterRead read;
  const FramePlan plan = p.plan(read.bytes, read.reply);
  ASSERT_GT(plan.value_count, 0u);
  for (std::size_t i = 0; i < plan.value_count; ++i) {
    EXPECT_EQ(plan.values[i].map_key, nullptr);
    EXPECT_EQ(plan.values[i].map_value, nullptr);
  }
}

TEST(StationMapTree, EntriesShowInTheGenericMapFieldsWithKeyAndNumber) {
  Planner p;
  p.decoder.use_station_map(10, meter_map());
  MeterRead read;
  const FramePlan plan = p.plan(read.bytes, read.reply);
  Lines lines = lines_of(describe_frame(plan, read.reply, p.description(read.bytes.size())));
  Lines values;
  for (const std::string& line : lines) {
    if (line.find("Modbus.Map") != std::string::npos) values.push_back(line);
  }
  EXPECT_EQ(
      values,
      (Lines{"1 Modbus.MapValue [3+2] = 'voltage phase 1: 230.1 V' label \"voltage phase 1 "
             "(0x0000): 230.1 V\" {map entry}",
             "2 Modbus.MapKey [3+2] = 'voltage_l1' (generated)", "2 Modbus.MapNumber [3+2] = 230.1",
             "1 Modbus.MapValue [5+4] = 'energy: 1000.00 kWh' label \"energy (0x0001): "
             "1000.00 kWh\" {map entry}",
             "2 Modbus.MapKey [5+4] = 'energy' (generated)", "2 Modbus.MapNumber [5+4] = 1000",
             "1 Modbus.MapValue [9+4] = 'model: PM10' label \"model (0x0003): PM10\" {map "
             "entry}",
             "2 Modbus.MapKey [9+4] = 'model' (generated)"}));
}

}  // namespace
}  // namespace pvtap::dissector::test
