// Payloads of value, state and station-event topics.
#include "mqtt/mqtt_payloads.h"

#include "formatting/json_text.h"
#include "formatting/number_text.h"
#include "mqtt/station_table.h"
#include "pvtap/registers/register_format.h"
#include "report/frame_findings.h"
#include "writers/value_json_cache.h"

namespace pvtap::analyzer {
namespace {

bool is_text_kind(RegisterKind kind) {
  return kind == RegisterKind::Text || kind == RegisterKind::BcdYearMonth ||
         kind == RegisterKind::DeviceNumber;
}

void append_bus(std::string& out, std::string_view bus) {
  if (bus.empty()) return;
  out += ",\"bus\":";
  append_json_string(out, bus);
}

}  // namespace

void append_value_payload(std::string& out, const DecodedValue& v) {
  if (v.def != nullptr && is_text_kind(v.def->kind)) {
    pvtap::append_value_text(out, v);
    return;
  }
  append_value_json_reading(out, v);
}

void append_state_json(std::string& out, const StationState& s, std::string_view bus,
                       ValueJsonCache& values) {
  out += "{\"ts\":";
  append_fixed(out, s.last_reply, 6);
  out += ",\"station\":";
  append_uint(out, s.address);
  out += ",\"dialect\":\"";
  out += to_string(s.dialect);
  out += "\",\"values\":{";
  bool first = true;
  for (const auto& [key, held] : s.values) {
    if (!first) out += ',';
    first = false;
    append_json_string(out, key);
    out += ':';
    values.append(out, held.value, s.dialect);
  }
  out += '}';
  append_bus(out, bus);
  out += '}';
}

void append_station_event_json(std::string& out, bool online, double now, const StationState& s,
                               std::string_view bus) {
  out += online ? "{\"type\":\"station_online\",\"ts\":" : "{\"type\":\"station_offline\",\"ts\":";
  append_fixed(out, now, 6);
  out += ",\"dialect\":\"";
  out += to_string(s.dialect);
  out += "\",\"station\":";
  append_uint(out, s.address);
  out += ",\"last_reply_ts\":";
  append_fixed(out, s.last_reply, 6);
  if (const auto period = s.period()) {
    out += ",\"poll_period_s\":";
    append_fixed(out, *period, 3);
  }
  append_bus(out, bus);
  out += '}';
}

}  // namespace pvtap::analyzer
