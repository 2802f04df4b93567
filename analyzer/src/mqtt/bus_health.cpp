// BusHealth: counting and the health JSON.
#include "mqtt/bus_health.h"

#include "formatting/json_text.h"
#include "formatting/number_text.h"

namespace pvtap::analyzer {

const HealthField kHealthFields[22] = {
    {"frames", "frames", "", true},
    {"damaged_frames", "bad checks", "", true},
    {"timeouts", "timeouts", "", true},
    {"unanswered_damaged_requests", "damaged requests left unanswered", "", true},
    {"exceptions", "exceptions", "", true},
    {"unsolicited", "unsolicited replies", "", true},
    {"address_conflicts", "address conflicts", "", true},
    {"masters", "masters", "", false},
    {"collisions", "collisions", "", true},
    {"lost_in_collision", "requests lost in a collision", "", true},
    {"echoes", "echoed requests", "", true},
    {"noise_bytes", "noise bytes", "", true},
    {"gaps", "gaps", "", true},
    {"latency_p50_ms", "latency p50", "ms", false},
    {"latency_p95_ms", "latency p95", "ms", false},
    {"latency_max_ms", "latency max", "ms", false},
    {"latency_total_p50_ms", "latency p50 since start", "ms", false},
    {"latency_total_p95_ms", "latency p95 since start", "ms", false},
    {"latency_total_max_ms", "latency max since start", "ms", false},
    {"poll_blocks_missing", "poll blocks missing", "", false},
    {"stations_answering", "stations answering", "", false},
    {"events_dropped", "MQTT events dropped", "", true},
};

namespace {

void append_ms(std::string& out, std::string_view key, const DistributionSummary& d,
               double seconds) {
  append_json_key(out, key);
  if (d.count == 0) {
    out += "null";
  } else {
    append_fixed(out, seconds * 1e3, 3);
  }
}

void append_latency(std::string& out, std::string_view prefix, const DistributionAccumulator& a) {
  const DistributionSummary d = a.summary();
  const std::string p(prefix);
  append_ms(out, p + "_p50_ms", d, d.p50);
  append_ms(out, p + "_p95_ms", d, d.p95);
  append_ms(out, p + "_max_ms", d, d.max);
  append_json_count(out, p + "_count", d.count);
}

void append_line_errors(std::string& out, const std::optional<LineErrorCounts>& e) {
  append_json_key(out, "line_errors");
  if (!e) {
    out += "null";
    return;
  }
  out += "{\"framing\":";
  append_uint(out, e->framing);
  append_json_count(out, "overrun", e->overrun);
  append_json_count(out, "parity", e->parity);
  append_json_count(out, "breaks", e->breaks);
  append_json_count(out, "buffer_overrun", e->buffer_overrun);
  out += '}';
}

}  // namespace

void BusHealth::count(const SessionFrame& f) {
  events.add(f);
  if (f.latency) latency_interval.add(*f.latency);
}

void append_health_json(std::string& out, const BusHealth& h, const HealthContext& c) {
  out += "{\"ts\":";
  append_fixed(out, c.now, 6);
  out += ",\"interval_s\":";
  append_fixed(out, c.interval, 3);
  const EventCounts& e = h.events.counts();
  append_json_count(out, "frames", e.frames);
  append_json_count(out, "damaged_frames", e.damaged_frames);
  append_json_count(out, "timeouts", e.timeouts);
  append_json_count(out, "unanswered_damaged_requests", e.unanswered_damaged_requests);
  append_json_count(out, "exceptions", e.exceptions);
  append_json_count(out, "unsolicited", e.unsolicited);
  append_json_count(out, "address_conflicts", e.address_conflicts);
  append_json_count(out, "masters", c.sharing.masters);
  append_json_count(out, "collisions", c.sharing.collisions);
  append_json_count(out, "lost_in_collision", c.sharing.lost_in_collision);
  append_json_count(out, "echoes", c.sharing.echoes);
  append_json_count(out, "noise_bytes", e.noise_bytes);
  append_json_count(out, "gaps", e.gaps.gaps);
  append_latency(out, "latency", h.latency_interval);
  append_latency(out, "latency_total", h.events.latency());
  append_json_count(out, "stations", c.stations);
  append_json_count(out, "stations_answering", c.stations_answering);
  append_json_count(out, "poll_blocks", c.poll_blocks);
  append_json_count(out, "poll_blocks_missing", c.poll_blocks_missing);
  append_json_count(out, "events_queued", c.events_queued);
  append_json_count(out, "events_dropped", c.events_dropped);
  append_line_errors(out, h.line_errors);
  if (!c.bus.empty()) {
    out += ",\"bus\":";
    append_json_string(out, c.bus);
  }
  out += '}';
}

}  // namespace pvtap::analyzer
