// MqttTopics: the topic of everything pvtap publishes, from one prefix.
//
//   PREFIX/status                        online | offline (retained; the last will)
//   PREFIX/<bus>/health                  JSON per interval (retained)
//   PREFIX/<bus>/events                  JSON events as in --format jsonl (QoS 1)
//   PREFIX/<bus>/<station>/<key>         the value of one register (retained)
//   PREFIX/<bus>/<station>/state         JSON of all the station's latest values (retained)
//   PREFIX/<bus>/<station>/availability  online | offline (retained)
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

#include "pvtap/registers/register_decoder.h"

namespace pvtap::analyzer {

// A name made safe as one topic level and as a Home Assistant id: characters other than
// letters, digits, '-' and '_' become '_' ("/dev/ttyUSB0" is "dev_ttyUSB0").
std::string topic_level(std::string_view name);
// The key of a value: the map's key, with the register's number for one of a range
// ("cell_voltage_3"). Empty for words outside the map.
std::string value_key(const DecodedValue& v);

class MqttTopics {
 public:
  MqttTopics(std::string prefix, std::string lone_serial_bus)
      : prefix_(std::move(prefix)), lone_serial_bus_(std::move(lone_serial_bus)) {}

  // The topic level of a bus: "bus" for the run's one serial tap (MqttOptions), otherwise its
  // name made a topic level.
  std::string bus_level(std::string_view bus) const;

  const std::string& prefix() const { return prefix_; }
  std::string status() const { return prefix_ + "/status"; }
  std::string bus(std::string_view bus_level) const;
  std::string health(std::string_view bus_level) const { return bus(bus_level) + "/health"; }
  std::string events(std::string_view bus_level) const { return bus(bus_level) + "/events"; }
  std::string station(std::string_view bus_level, std::uint8_t station) const;
  std::string value(std::string_view bus_level, std::uint8_t station, std::string_view key) const;
  std::string state(std::string_view bus_level, std::uint8_t s) const {
    return station(bus_level, s) + "/state";
  }
  std::string availability(std::string_view bus_level, std::uint8_t s) const {
    return station(bus_level, s) + "/availability";
  }

 private:
  std::string prefix_;
  std::string lone_serial_bus_;
};

}  // namespace pvtap::analyzer
