// RetainedTopics: per interval, what changed; after a reconnection, everything.
#include "mqtt/retained_topics.h"

#include "mqtt/ha_discovery.h"
#include "mqtt/mqtt_payloads.h"

namespace pvtap::analyzer {

RetainedTopics::RetainedTopics(MqttClient& client, const MqttTopics& topics,
                               const PublishSchedule& schedule, bool discovery, bool raw)
    : client_(client), topics_(topics), schedule_(schedule), discovery_(discovery), raw_(raw) {}

MqttBus& RetainedTopics::bus(std::string_view name) {
  auto it = buses_.find(name);
  if (it == buses_.end()) {
    MqttBus bus;
    bus.name = std::string(name);
    bus.level = topics_.bus_level(name);
    bus.stations.publish_raw(raw_);
    it = buses_.emplace(bus.name, std::move(bus)).first;
  }
  return it->second;
}

void RetainedTopics::publish(double now) {
  for (auto& [name, bus] : buses_) judge_availability(bus, now);
  if (!client_.connected()) return;
  if (const std::uint64_t n = client_.connections(); n != connections_seen_) {
    connections_seen_ = n;
    forget_published();
  }
  for (auto& [name, bus] : buses_) publish_bus(bus, now);
}

void RetainedTopics::forget_published() {
  for (auto& [name, bus] : buses_) {
    bus.health_discovered = false;
    for (auto& [address, s] : bus.stations.stations()) {
      s.replied_since_state = true;
      s.identity_changed = true;
      if (s.online) {
        client_.publish_retained(topics_.availability(bus.level, address),
                                 *s.online ? "online" : "offline", 1);
      }
      for (auto& [key, held] : s.values) {
        held.published.clear();
        held.discovered = false;
      }
    }
  }
}

void RetainedTopics::judge_availability(MqttBus& bus, double now) {
  for (auto& [address, s] : bus.stations.stations()) {
    const bool answering = s.answering(now);
    if (s.online == answering) continue;
    if (s.online) {
      scratch_.clear();
      append_station_event_json(scratch_, answering, now, s, bus.name);
      client_.publish_event(topics_.events(bus.level), scratch_);
    }
    s.online = answering;
    // Sent now when connected, again with everything after a reconnection.
    client_.publish_retained(topics_.availability(bus.level, address),
                             answering ? "online" : "offline", 1);
  }
}

void RetainedTopics::publish_bus(MqttBus& bus, double now) {
  for (auto& [address, s] : bus.stations.stations()) {
    schedule_.pace(client_);
    if (discovery_) publish_discovery(bus, s);
    publish_station(bus, s);
  }
  publish_health(bus, now);
}

void RetainedTopics::publish_station(MqttBus& bus, StationState& s) {
  for (auto& [key, held] : s.values) {
    scratch_.clear();
    append_value_payload(scratch_, held.value);
    if (scratch_ == held.published) continue;
    if (client_.publish_retained(topics_.value(bus.level, s.address, key), scratch_, 0)) {
      held.published = scratch_;
    }
  }
  if (!s.replied_since_state) return;
  scratch_.clear();
  append_state_json(scratch_, s, bus.name, values_);
  if (client_.publish_retained(topics_.state(bus.level, s.address), scratch_, 0)) {
    s.replied_since_state = false;
  }
}

void RetainedTopics::publish_discovery(MqttBus& bus, StationState& s) {
  const DiscoveryScope scope{&topics_, bus.name, bus.level, schedule_.live()};
  for (auto& [key, held] : s.values) {
    if (held.discovered && !s.identity_changed) continue;
    bool sent = true;
    for (const QueuedMessage& m : discovery_configs(scope, s, key, held)) {
      sent = client_.publish_retained(m.topic, m.payload, 1) && sent;
    }
    held.discovered = sent;
  }
  s.identity_changed = false;
  if (bus.health_discovered) return;
  bool sent = true;
  for (const QueuedMessage& m : health_discovery_configs(scope)) {
    sent = client_.publish_retained(m.topic, m.payload, 1) && sent;
  }
  bus.health_discovered = sent;
}

void RetainedTopics::publish_health(MqttBus& bus, double now) {
  HealthContext c;
  c.now = now;
  c.interval = schedule_.interval();
  c.bus = bus.name;
  for (const auto& [address, s] : bus.stations.stations()) {
    ++c.stations;
    if (s.online.value_or(true)) ++c.stations_answering;
  }
  c.poll_blocks = bus.stations.blocks();
  c.poll_blocks_missing = bus.stations.blocks_missing(now);
  c.events_queued = client_.events_queued();
  c.events_dropped = client_.events_dropped();
  if (bus.session) c.sharing = bus.session->sharing();
  scratch_.clear();
  append_health_json(scratch_, bus.health, c);
  client_.publish_retained(topics_.health(bus.level), scratch_, 0);
  bus.health.start_interval();
}

}  // namespace pvtap::analyzer
