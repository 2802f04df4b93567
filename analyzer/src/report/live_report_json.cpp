// The live sources in the jsonl summary line: "devices":[...] and "interface":{...}.
#include "formatting/json_text.h"
#include "formatting/number_text.h"
#include "report/report_writers.h"

namespace pvtap::analyzer {
namespace {

void text(std::string& o, std::string_view name, std::string_view value) {
  append_json_key(o, name);
  append_json_string(o, value);
}

// A note that is absent is null, so that `jq 'select(.x)'` finds only the real ones.
void note(std::string& o, std::string_view name, std::string_view value) {
  if (value.empty()) {
    append_json_key(o, name);
    o += "null";
  } else {
    text(o, name, value);
  }
}

// "line_errors":{"framing":0,...}, or null with "line_errors_note" saying why.
void line_errors(std::string& o, const DeviceReport& d) {
  append_json_key(o, "line_errors");
  if (!d.line_errors) {
    o += "null";
    text(o, "line_errors_note", d.line_errors_note);
    return;
  }
  const LineErrorCounts& e = *d.line_errors;
  o += "{\"framing\":";
  append_uint(o, e.framing);
  append_json_count(o, "parity", e.parity);
  append_json_count(o, "overrun", e.overrun);
  append_json_count(o, "buffer_overrun", e.buffer_overrun);
  append_json_count(o, "break", e.breaks);
  o += '}';
}

void device(std::string& o, const DeviceReport& d) {
  o += "{\"path\":";
  append_json_string(o, d.path);
  text(o, "adapter", d.adapter);
  text(o, "line", d.line);
  append_json_count(o, "reads", d.reads);
  append_json_count(o, "bytes", d.bytes);
  append_json_key(o, "latency_timer_ms");
  if (d.latency_timer_ms) {
    append_int(o, *d.latency_timer_ms);
  } else {
    o += "null";
  }
  note(o, "latency_note", d.latency_note);
  line_errors(o, d);
  append_json_count(o, "outages", d.outages);
  append_json_key(o, "outage_seconds");
  append_fixed(o, d.outage_seconds, 3);
  append_json_key(o, "lost_at_end");
  o += d.lost_at_end ? "true" : "false";
  note(o, "last_error", d.last_error);
  o += '}';
}

void optional_number(std::string& o, std::string_view name, std::optional<std::uint64_t> v) {
  append_json_key(o, name);
  if (v) {
    append_uint(o, *v);
  } else {
    o += "null";
  }
}

void interface(std::string& o, const InterfaceReport& i) {
  append_json_key(o, "interface");
  o += "{\"name\":";
  append_json_string(o, i.name);
  text(o, "filter", i.filter);
  text(o, "link_type", i.link_type);
  append_json_count(o, "packets", i.packets);
  optional_number(o, "dropped", i.dropped);
  optional_number(o, "interface_dropped", i.interface_dropped);
  o += '}';
}

}  // namespace

void append_live_sources_json(const LiveSources& live, std::string& o) {
  if (!live.active()) return;
  append_json_key(o, "live_seconds");
  append_fixed(o, live.seconds, 3);
  append_json_key(o, "stopped_by_signal");
  o += live.stopped_by_signal ? "true" : "false";
  if (!live.devices.empty()) {
    append_json_key(o, "devices");
    o += '[';
    for (std::size_t k = 0; k < live.devices.size(); ++k) {
      if (k > 0) o += ',';
      device(o, live.devices[k]);
    }
    o += ']';
  }
  if (live.interface) interface(o, *live.interface);
}

}  // namespace pvtap::analyzer
