// Payloads of value, state and station-event topics.
#include "mqtt/mqtt_payloads.h"

#include "formatting/json_writer.h"
#include "mqtt/station_table.h"
#include "pvtap/registers/register_format.h"
#include "report/value_json.h"
#include "writers/value_json_cache.h"

namespace pvtap::analyzer {
namespace {

bool is_text_kind(RegisterKind kind) {
  return kind == RegisterKind::Text || kind == RegisterKind::BcdYearMonth ||
         kind == RegisterKind::DeviceNumber;
}

void write_bus(JsonWriter& w, std::string_view bus) {
  if (!bus.empty()) w.field("bus", bus);
}

}  // namespace

void append_value_payload(std::string& out, const DecodedValue& v) {
  if (v.def != nullptr && is_text_kind(v.def->kind)) {
    pvtap::append_value_text(out, v);
    return;
  }
  JsonWriter w(out);
  write_value_reading(w, v);
}

void append_state_json(std::string& out, const StationState& s, std::string_view bus,
                       ValueJsonCache& values) {
  JsonWriter w(out);
  w.begin_object();
  w.field_fixed("ts", s.last_reply, 6);
  w.field("station", s.address);
  w.field_plain("dialect", to_string(s.dialect));
  w.key("values");
  w.begin_object();
  for (const auto& [key, held] : s.values) {
    w.key_text(key);
    values.write(w, held.value, s.dialect, s.address);
  }
  w.end_object();
  write_bus(w, bus);
  w.end_object();
}

void append_station_event_json(std::string& out, bool online, double now, const StationState& s,
                               std::string_view bus) {
  JsonWriter w(out);
  w.begin_object();
  w.field_plain("type", online ? "station_online" : "station_offline");
  w.field_fixed("ts", now, 6);
  w.field_plain("dialect", to_string(s.dialect));
  w.field("station", s.address);
  w.field_fixed("last_reply_ts", s.last_reply, 6);
  if (const auto period = s.period()) w.field_fixed("poll_period_s", *period, 3);
  write_bus(w, bus);
  w.end_object();
}

}  // namespace pvtap::analyzer
