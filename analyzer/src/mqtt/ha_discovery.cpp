// Home Assistant discovery configs.
#include "mqtt/ha_discovery.h"

#include <array>

#include "formatting/json_writer.h"
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

void write_station_device(JsonWriter& w, const DiscoveryScope& scope, const StationState& s) {
  w.key("device");
  w.begin_object();
  w.key("identifiers");
  w.begin_array();
  w.string("pvtap_" + node_id(scope, s.address));
  w.end_array();
  std::string name(to_string(s.dialect));
  name += " station " + std::to_string(s.address);
  if (!scope.bus.empty()) name += " on " + std::string(scope.bus);
  w.field("name", name);
  std::string model = identity_text(s, "model_name");
  if (model.empty()) model = s.device.product;
  const std::string device = identity_text(s, "device_number");
  const std::string serial = identity_text(s, "serial_number");
  std::string maker = identity_text(s, "manufacturer_name");
  if (maker.empty()) maker = s.device.vendor;
  std::string firmware = identity_text(s, "firmware_version");
  if (firmware.empty()) firmware = s.device.revision;
  if (!model.empty() || !device.empty()) w.field("model", model.empty() ? device : model);
  if (!serial.empty() || !device.empty()) {
    w.field("serial_number", serial.empty() ? device : serial);
  }
  if (!maker.empty()) w.field("manufacturer", maker);
  if (!firmware.empty()) w.field("sw_version", firmware);
  w.field("via_device", "pvtap_" + bus_node_id(scope));
  w.end_object();
}

void write_availability(JsonWriter& w, const DiscoveryScope& scope, std::uint8_t station) {
  w.field_plain("availability_mode", "all");
  w.key("availability");
  w.begin_array();
  if (scope.live) {
    w.begin_object();
    w.field("topic", scope.topics->status());
    w.end_object();
  }
  w.begin_object();
  w.field("topic", scope.topics->availability(scope.bus_level, station));
  w.end_object();
  w.end_array();
}

// Opens an entity of a station with the members every one has: name, ids, where it reads
// its state.
void open_entity(JsonWriter& w, const DiscoveryScope& scope, const StationState& s,
                 const std::string& object, std::string_view name, const std::string& state_topic) {
  w.begin_object();
  w.field("name", name);
  w.field("unique_id", "pvtap_" + node_id(scope, s.address) + "_" + object);
  w.field("object_id", node_id(scope, s.address) + "_" + object);
  w.field("state_topic", state_topic);
}

// Closes an entity of a station: availability and device.
void close_entity(JsonWriter& w, const DiscoveryScope& scope, const StationState& s) {
  write_availability(w, scope, s.address);
  write_station_device(w, scope, s);
  w.end_object();
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
  // The value topic carries an enum's number; the state topic has its text.
  const bool is_enum = def.kind == RegisterKind::Enum;
  const std::string state_topic = is_enum ? scope.topics->state(scope.bus_level, s.address)
                                          : scope.topics->value(scope.bus_level, s.address, key);
  std::string o;
  JsonWriter w(o);
  open_entity(w, scope, s, object, def.name, state_topic);
  if (is_numeric(def.kind)) {
    const SensorClass c = sensor_class_of(def.unit);
    if (!def.unit.empty()) w.field("unit_of_measurement", def.unit);
    if (!c.device_class.empty()) w.field("device_class", c.device_class);
    w.field("state_class", c.state_class);
    w.field("suggested_display_precision", def.decimals);
  } else if (is_enum) {
    std::string tpl = "{{ value_json['values']['";
    tpl += key;
    tpl += "']['text'] }}";
    w.field("value_template", tpl);
  }
  if (is_identity_key(def.key)) w.field("entity_category", "diagnostic");
  close_entity(w, scope, s);
  return {config_topic("sensor", node_id(scope, s.address), object), std::move(o)};
}

QueuedMessage bit_config(const DiscoveryScope& scope, const StationState& s, std::string_view key,
                         const HeldValue& held, const BitName& bit) {
  const RegisterDef& def = *held.value.def;
  const std::string object = topic_level(key) + "_bit" + std::to_string(bit.index);
  std::string o;
  JsonWriter w(o);
  open_entity(w, scope, s, object, bit.name, scope.topics->value(scope.bus_level, s.address, key));
  std::string tpl = "{{ 'ON' if (value | int // ";
  append_uint(tpl, std::uint64_t{1} << bit.index);
  tpl += ") % 2 == 1 else 'OFF' }}";
  w.field("value_template", tpl);
  if (names_alarm(def.name) || names_alarm(def.key)) w.field("device_class", "problem");
  close_entity(w, scope, s);
  return {config_topic("binary_sensor", node_id(scope, s.address), object), std::move(o)};
}

// The bus's own device, which the health sensors belong to.
void write_bus_device(JsonWriter& w, const DiscoveryScope& scope, const std::string& node) {
  w.key("device");
  w.begin_object();
  w.key("identifiers");
  w.begin_array();
  w.string("pvtap_" + node);
  w.end_array();
  w.field("name", "pvtap " + scope.topics->prefix() + " " + std::string(scope.bus_level));
  w.field("manufacturer", "pvtap");
  w.field("model", "passive RS485 tap");
  w.end_object();
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
    std::string o;
    JsonWriter w(o);
    w.begin_object();
    w.field("name", f.name);
    w.field("unique_id", "pvtap_" + node + "_" + std::string(f.key));
    w.field("object_id", node + "_" + std::string(f.key));
    w.field("state_topic", scope.topics->health(scope.bus_level));
    w.field("value_template", "{{ value_json." + std::string(f.key) + " }}");
    w.field("entity_category", "diagnostic");
    w.field("state_class", std::string_view(f.counter ? "total_increasing" : "measurement"));
    if (!f.unit.empty()) {
      w.field("unit_of_measurement", f.unit);
      w.field("device_class", "duration");
    }
    if (scope.live) w.field("availability_topic", scope.topics->status());
    write_bus_device(w, scope, node);
    w.end_object();
    out.push_back({config_topic("sensor", node, std::string(f.key)), std::move(o)});
  }
  return out;
}

}  // namespace pvtap::analyzer
