// Home Assistant MQTT discovery: the retained configs under homeassistant/ that make each
// inverter a device with a sensor per register, a binary sensor per alarm bit, and each bus
// a device with a diagnostic sensor per health counter.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "broker/mqtt_outbox.h"
#include "mqtt/mqtt_topics.h"
#include "mqtt/station_table.h"

namespace pvtap::analyzer {

// SensorClass: how Home Assistant should treat a register's unit.
struct SensorClass {
  std::string_view device_class;  // empty: none
  std::string_view state_class;   // "measurement", "total_increasing"
};

// By unit: energy counters (Wh, kWh) are total_increasing (Home Assistant also accepts a
// daily counter's reset to 0 under that class); other numbers are measurements.
SensorClass sensor_class_of(std::string_view unit);

// DiscoveryScope: where a bus's configs point.
struct DiscoveryScope {
  const MqttTopics* topics = nullptr;
  std::string_view bus;        // as the sessions name it
  std::string_view bus_level;  // its topic level
  bool live = true;            // PREFIX/status is kept (not when replaying a capture)
};

// The configs of one register of a station: a sensor, and for a bits register one binary
// sensor per named bit. Uses the station's identity values for the device.
std::vector<QueuedMessage> discovery_configs(const DiscoveryScope& scope,
                                             const StationState& station, std::string_view key,
                                             const HeldValue& held);
// The diagnostic sensors of a bus's health counters.
std::vector<QueuedMessage> health_discovery_configs(const DiscoveryScope& scope);

}  // namespace pvtap::analyzer
