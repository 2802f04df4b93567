// MqttTopics: topic names.
#include "mqtt/mqtt_topics.h"

namespace pvtap::analyzer {

std::string topic_level(std::string_view name) {
  std::string out;
  out.reserve(name.size());
  for (const char c : name) {
    const bool plain = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
                       c == '-' || c == '_';
    if (plain || !out.empty()) out += plain ? c : '_';
  }
  while (!out.empty() && out.back() == '_') out.pop_back();
  return out;
}

std::string MqttTopics::bus_level(std::string_view bus) const {
  std::string level = bus == lone_serial_bus_ ? std::string() : topic_level(bus);
  return level.empty() ? "bus" : level;
}

std::string value_key(const DecodedValue& v) {
  if (v.def == nullptr) return {};
  std::string key(v.def->key);
  if (v.def->is_range()) {
    key += '_';
    key += std::to_string(v.instance + 1);
  }
  return key;
}

std::string MqttTopics::bus(std::string_view bus_level) const {
  std::string t = prefix_;
  t += '/';
  t += bus_level;
  return t;
}

std::string MqttTopics::station(std::string_view bus_level, std::uint8_t station) const {
  std::string t = bus(bus_level);
  t += '/';
  t += std::to_string(station);
  return t;
}

std::string MqttTopics::value(std::string_view bus_level, std::uint8_t station,
                              std::string_view key) const {
  std::string t = this->station(bus_level, station);
  t += '/';
  t += key;
  return t;
}

}  // namespace pvtap::analyzer
