// RetainedTopics: what MQTT holds of each bus between publications (its stations, its health)
// and the retained topics made of it once per interval.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <string_view>

#include "broker/mqtt_client.h"
#include "mqtt/bus_health.h"
#include "mqtt/mqtt_topics.h"
#include "mqtt/publish_schedule.h"
#include "mqtt/station_table.h"
#include "writers/value_json_cache.h"

namespace pvtap::analyzer {

// MqttBus: one bus as MQTT holds it.
struct MqttBus {
  std::string name;   // as the sessions name it
  std::string level;  // its topic level
  StationTable stations;
  BusHealth health;
  bool health_discovered = false;
  // Its session, which alone says how many masters share it and where they collided; null
  // until an event from a session came.
  const BusSession* session = nullptr;
};

// Each station's availability, values and state, the discovery configs of registers seen for
// the first time and each bus's health, each sent when it changed; all of it again after a
// reconnection, since a restarted broker may have lost it.
class RetainedTopics {
 public:
  // `raw`: the stations' words no map names are published too (--mqtt-raw).
  RetainedTopics(MqttClient& client, const MqttTopics& topics, const PublishSchedule& schedule,
                 bool discovery, bool raw = false);

  // Made on first use.
  MqttBus& bus(std::string_view name);
  // What is due at `now`. Availability is judged even while the broker is away (a change is
  // also an event, which waits in the client's queue); values are then held, latest only.
  void publish(double now);

 private:
  void judge_availability(MqttBus& bus, double now);
  void publish_bus(MqttBus& bus, double now);
  void publish_station(MqttBus& bus, StationState& s);
  void publish_discovery(MqttBus& bus, StationState& s);
  void publish_health(MqttBus& bus, double now);
  void forget_published();

  MqttClient& client_;
  const MqttTopics& topics_;
  const PublishSchedule& schedule_;
  bool discovery_;
  bool raw_;
  std::map<std::string, MqttBus, std::less<>> buses_;
  ValueJsonCache values_;
  std::string scratch_;
  std::uint64_t connections_seen_ = 0;
};

}  // namespace pvtap::analyzer
