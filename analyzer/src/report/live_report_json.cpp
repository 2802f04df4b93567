// The live sources in the jsonl summary line: "devices":[...] and "interface":{...}.
#include "formatting/json_writer.h"
#include "report/report_writers.h"

namespace pvtap::analyzer {
namespace {

// A note that is absent is null, so that `jq 'select(.x)'` finds only the real ones.
void note(JsonWriter& w, JsonKey name, std::string_view value) {
  if (value.empty()) {
    w.field_null(name);
  } else {
    w.field(name, value);
  }
}

// "line_errors":{"framing":0,...}, or null with "line_errors_note" saying why.
void line_errors(JsonWriter& w, const DeviceReport& d) {
  if (!d.line_errors) {
    w.field_null("line_errors");
    w.field("line_errors_note", d.line_errors_note);
    return;
  }
  const LineErrorCounts& e = *d.line_errors;
  w.key("line_errors");
  w.begin_object();
  w.field("framing", e.framing);
  w.field("parity", e.parity);
  w.field("overrun", e.overrun);
  w.field("buffer_overrun", e.buffer_overrun);
  w.field("break", e.breaks);
  w.end_object();
}

void device(JsonWriter& w, const DeviceReport& d) {
  w.begin_object();
  w.field("path", d.path);
  w.field("adapter", d.adapter);
  w.field("line", d.line);
  w.field("reads", d.reads);
  w.field("bytes", d.bytes);
  w.key("latency_timer_ms");
  if (d.latency_timer_ms) {
    w.integer(*d.latency_timer_ms);
  } else {
    w.null();
  }
  note(w, "latency_note", d.latency_note);
  line_errors(w, d);
  w.field("outages", d.outages);
  w.field_fixed("outage_seconds", d.outage_seconds, 3);
  w.field_bool("lost_at_end", d.lost_at_end);
  note(w, "last_error", d.last_error);
  w.end_object();
}

void optional_number(JsonWriter& w, JsonKey name, std::optional<std::uint64_t> v) {
  w.key(name);
  if (v) {
    w.uint(*v);
  } else {
    w.null();
  }
}

void interface(JsonWriter& w, const InterfaceReport& i) {
  w.key("interface");
  w.begin_object();
  w.field("name", i.name);
  w.field("filter", i.filter);
  w.field("link_type", i.link_type);
  w.field("packets", i.packets);
  optional_number(w, "dropped", i.dropped);
  optional_number(w, "interface_dropped", i.interface_dropped);
  w.end_object();
}

}  // namespace

void write_live_sources_json(JsonWriter& w, const LiveSources& live) {
  if (!live.active()) return;
  w.field_fixed("live_seconds", live.seconds, 3);
  w.field_bool("stopped_by_signal", live.stopped_by_signal);
  if (!live.devices.empty()) {
    w.key("devices");
    w.begin_array();
    for (const DeviceReport& d : live.devices) device(w, d);
    w.end_array();
  }
  if (live.interface) interface(w, *live.interface);
}

}  // namespace pvtap::analyzer
