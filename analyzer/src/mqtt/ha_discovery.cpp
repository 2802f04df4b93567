// Home Assistant discovery configs.
#include "mqtt/ha_discovery.h"

#include <array>

#include "formatting/json_text.h"
#include "formatting/number_text.h"
#include "mqtt/bus_health.h"
#include "mqtt/mqtt_payloads.h"

namespace pvtap::analyzer {
namespace {

struct UnitClass {
  std::string_view unit;
  SensorClass sensor;
};

// Units of the built-in maps, with the device class Home Assistant has for them.
constexpr std::array<UnitClass, 13> kUnitClasses{{
    {"V", {"voltage", "measurement"}},
    {"mV", {"voltage", "measurement"}},
    {"A", {"current", "measurement"}},
    {"W", {"power", "measurement"}},
    {"kW", {"power", "measurement"}},
    {"VA", {"apparent_power", "measurement"}},
    {"kvar", {"reactive_power", "measurement"}},
    {"Wh", {"energy", "total_increasing"}},
    {"kWh", {"energy", "total_increasing"}},
    {"Hz", {"frequency", "measurement"}},
    {"°C", {"temperature", "measurement"}},
    {"h", {"duration", "measurement"}},
    {"kg", {"weight", "measurement"}},
}};

constexpr std::string_view kAlarmWords[] = {"alarm", "fault", "error", "warning", "protect"};

constexpr std::string_view kDiscoveryPrefix = "homeassistant";

bool is_numeric(RegisterKind kind) {
  return kind == RegisterKind::Number || kind == RegisterKind::Bcd ||
         kind == RegisterKind::BcdPhaseCapacity;
}

bool names_alarm(std::string_view text) {
  for (const std::string_view w : kAlarmWords) {
    if (text.find(w) != std::string_view::npos) return true;
  }
  return false;
}

// Ids of Home Assistant nodes: the bus's from prefix and bus, a station's with its address.
std::string bus_node_id(const DiscoveryScope& scope) {
  return topic_level(scope.topics->prefix()) + "_" + std::string(scope.bus_level);
}

std::string node_id(const DiscoveryScope& scope, std::uint8_t station) {
  return bus_node_id(scope) + "_" + std::to_string(station);
}

std::string identity_text(const StationState& s, std::string_view key) {
  const auto it = s.values.find(key);
  if (it == s.values.end()) return {};
  std::string text;
  append_value_payload(text, it->second.value);
  return text;
}

void append_member(std::string& out, std::string_view key, std::string_view text) {
  append_json_key(out, key);
  append_json_string(out, text);
}

void append_station_device(std::string& out, const DiscoveryScope& scope, const StationState& s) {
  out += ",\"device\":{\"identifiers\":[";
  append_json_string(out, "pvtap_" + node_id(scope, s.address));
  out += "],\"name\":";
  std::string name(to_string(s.dialect));
  name += " station " + std::to_string(s.address);
  if (!scope.bus.empty()) name += " on " + std::string(scope.bus);
  append_json_string(out, name);
  std::string model = identity_text(s, "model_name");
  if (model.empty()) model = s.device.product;
  const std::string device = identity_text(s, "device_number");
  const std::string serial = identity_text(s, "serial_number");
  std::string maker = identity_text(s, "manufacturer_name");
  if (maker.empty()) maker = s.device.vendor;
  std::string firmware = identity_text(s, "firmware_version");
  if (firmware.empty()) firmware = s.device.revision;
  if (!model.empty() || !device.empty())
    append_member(out, "model", model.empty() ? device : model);
  if (!serial.empty() || !device.empty()) {
    append_member(out, "serial_number", serial.empty() ? device : serial);
  }
  if (!maker.empty()) append_member(out, "manufacturer", maker);
  if (!firmware.empty()) append_member(out, "sw_version", firmware);
  append_member(out, "via_device", "pvtap_" + bus_node_id(scope));
  out += '}';
}

void append_availability(std::string& out, const DiscoveryScope& scope, std::uint8_t station) {
  out += ",\"availability_mode\":\"all\",\"availability\":[{\"topic\":";
  if (scope.live) {
    append_json_string(out, scope.topics->status());
    out += "},{\"topic\":";
  }
  append_json_string(out, scope.topics->availability(scope.bus_level, station));
  out += "}]";
}

// The members every entity of a station has: name, ids, where it reads its state.
std::string entity_head(const DiscoveryScope& scope, const StationState& s,
                        const std::string& object, std::string_view name,
                        const std::string& state_topic) {
  std::string o = "{\"name\":";
  append_json_string(o, name);
  append_member(o, "unique_id", "pvtap_" + node_id(scope, s.address) + "_" + object);
  append_member(o, "object_id", node_id(scope, s.address) + "_" + object);
  append_member(o, "state_topic", state_topic);
  return o;
}

std::string config_topic(std::string_view component, const std::string& node,
                         const std::string& object) {
  std::string t(kDiscoveryPrefix);
  t += '/';
  t += component;
  t += '/' + node + '/' + object + "/config";
  return t;
}

QueuedMessage sensor_config(const DiscoveryScope& scope, const StationState& s,
                            std::string_view key, const HeldValue& held) {
  const RegisterDef& def = *held.value.def;
  const std::string object = topic_level(key);
  std::string o =
      entity_head(scope, s, object, def.name, scope.topics->value(scope.bus_level, s.address, key));
  if (is_numeric(def.kind)) {
    const SensorClass c = sensor_class_of(def.unit);
    if (!def.unit.empty()) append_member(o, "unit_of_measurement", def.unit);
    if (!c.device_class.empty()) append_member(o, "device_class", c.device_class);
    append_member(o, "state_class", c.state_class);
    append_json_key(o, "suggested_display_precision");
    append_uint(o, def.decimals);
  } else if (def.kind == RegisterKind::Enum) {
    // The value topic carries the number; the state topic has its text.
    o.erase(o.rfind(",\"state_topic\""));
    append_member(o, "state_topic", scope.topics->state(scope.bus_level, s.address));
    std::string tpl = "{{ value_json['values']['";
    tpl += key;
    tpl += "']['text'] }}";
    append_member(o, "value_template", tpl);
  }
  if (is_identity_key(def.key)) append_member(o, "entity_category", "diagnostic");
  append_availability(o, scope, s.address);
  append_station_device(o, scope, s);
  o += '}';
  return {config_topic("sensor", node_id(scope, s.address), object), std::move(o)};
}

QueuedMessage bit_config(const DiscoveryScope& scope, const StationState& s, std::string_view key,
                         const HeldValue& held, const BitName& bit) {
  const RegisterDef& def = *held.value.def;
  const std::string object = topic_level(key) + "_bit" + std::to_string(bit.index);
  std::string o =
      entity_head(scope, s, object, bit.name, scope.topics->value(scope.bus_level, s.address, key));
  std::string tpl = "{{ 'ON' if (value | int // ";
  append_uint(tpl, std::uint64_t{1} << bit.index);
  tpl += ") % 2 == 1 else 'OFF' }}";
  append_member(o, "value_template", tpl);
  if (names_alarm(def.name) || names_alarm(def.key)) append_member(o, "device_class", "problem");
  append_availability(o, scope, s.address);
  append_station_device(o, scope, s);
  o += '}';
  return {config_topic("binary_sensor", node_id(scope, s.address), object), std::move(o)};
}

}  // namespace

SensorClass sensor_class_of(std::string_view unit) {
  for (const UnitClass& u : kUnitClasses) {
    if (u.unit == unit) return u.sensor;
  }
  return {"", "measurement"};
}

std::vector<QueuedMessage> discovery_configs(const DiscoveryScope& scope,
                                             const StationState& station, std::string_view key,
                                             const HeldValue& held) {
  std::vector<QueuedMessage> out;
  if (held.value.def == nullptr) return out;
  out.push_back(sensor_config(scope, station, key, held));
  if (held.value.def->kind != RegisterKind::Bits) return out;
  for (const BitName& bit : held.value.def->bits) {
    if (!bit.name.empty()) out.push_back(bit_config(scope, station, key, held, bit));
  }
  return out;
}

std::vector<QueuedMessage> health_discovery_configs(const DiscoveryScope& scope) {
  std::vector<QueuedMessage> out;
  const std::string node = bus_node_id(scope);
  for (const HealthField& f : kHealthFields) {
    std::string o = "{\"name\":";
    append_json_string(o, f.name);
    append_member(o, "unique_id", "pvtap_" + node + "_" + std::string(f.key));
    append_member(o, "object_id", node + "_" + std::string(f.key));
    append_member(o, "state_topic", scope.topics->health(scope.bus_level));
    append_member(o, "value_template", "{{ value_json." + std::string(f.key) + " }}");
    append_member(o, "entity_category", "diagnostic");
    append_member(o, "state_class", f.counter ? "total_increasing" : "measurement");
    if (!f.unit.empty()) {
      append_member(o, "unit_of_measurement", f.unit);
      append_member(o, "device_class", "duration");
    }
    if (scope.live) {
      o += ",\"availability_topic\":";
      append_json_string(o, scope.topics->status());
    }
    o += ",\"device\":{\"identifiers\":[";
    append_json_string(o, "pvtap_" + node);
    o += "],\"name\":";
    append_json_string(o, "pvtap " + scope.topics->prefix() + " " + std::string(scope.bus_level));
    o += ",\"manufacturer\":\"pvtap\",\"model\":\"passive RS485 tap\"}}";
    out.push_back({config_topic("sensor", node, std::string(f.key)), std::move(o)});
  }
  return out;
}

}  // namespace pvtap::analyzer
