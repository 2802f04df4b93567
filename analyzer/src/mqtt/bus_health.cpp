// BusHealth: counting and the health JSON.
#include "mqtt/bus_health.h"

#include "formatting/json_writer.h"

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

// The keys of one latency's figures: the interval's and the total's.
struct LatencyKeys {
  JsonKey p50;
  JsonKey p95;
  JsonKey max;
  JsonKey count;
};

void write_ms(JsonWriter& w, JsonKey key, const DistributionSummary& d, double seconds) {
  w.key(key);
  if (d.count == 0) {
    w.null();
  } else {
    w.fixed(seconds * 1e3, 3);
  }
}

void write_latency(JsonWriter& w, const LatencyKeys& keys, const DistributionAccumulator& a) {
  const DistributionSummary d = a.summary();
  write_ms(w, keys.p50, d, d.p50);
  write_ms(w, keys.p95, d, d.p95);
  write_ms(w, keys.max, d, d.max);
  w.field(keys.count, d.count);
}

void write_line_errors(JsonWriter& w, const std::optional<LineErrorCounts>& e) {
  w.key("line_errors");
  if (!e) {
    w.null();
    return;
  }
  w.begin_object();
  w.field("framing", e->framing);
  w.field("overrun", e->overrun);
  w.field("parity", e->parity);
  w.field("breaks", e->breaks);
  w.field("buffer_overrun", e->buffer_overrun);
  w.end_object();
}

}  // namespace

void BusHealth::count(const SessionFrame& f) {
  events.add(f);
  if (f.latency) latency_interval.add(*f.latency);
}

void append_health_json(std::string& out, const BusHealth& h, const HealthContext& c) {
  JsonWriter w(out);
  w.begin_object();
  w.field_fixed("ts", c.now, 6);
  w.field_fixed("interval_s", c.interval, 3);
  const EventCounts& e = h.events.counts();
  w.field("frames", e.frames);
  w.field("damaged_frames", e.damaged_frames);
  w.field("timeouts", e.timeouts);
  w.field("unanswered_damaged_requests", e.unanswered_damaged_requests);
  w.field("exceptions", e.exceptions);
  w.field("unsolicited", e.unsolicited);
  w.field("address_conflicts", e.address_conflicts);
  w.field("masters", c.sharing.masters);
  w.field("collisions", c.sharing.collisions);
  w.field("lost_in_collision", c.sharing.lost_in_collision);
  w.field("echoes", c.sharing.echoes);
  w.field("noise_bytes", e.noise_bytes);
  w.field("gaps", e.gaps.gaps);
  write_latency(w, {"latency_p50_ms", "latency_p95_ms", "latency_max_ms", "latency_count"},
                h.latency_interval);
  write_latency(w,
                {"latency_total_p50_ms", "latency_total_p95_ms", "latency_total_max_ms",
                 "latency_total_count"},
                h.events.latency());
  w.field("stations", c.stations);
  w.field("stations_answering", c.stations_answering);
  w.field("poll_blocks", c.poll_blocks);
  w.field("poll_blocks_missing", c.poll_blocks_missing);
  w.field("events_queued", c.events_queued);
  w.field("events_dropped", c.events_dropped);
  write_line_errors(w, h.line_errors);
  if (!c.bus.empty()) w.field("bus", c.bus);
  w.end_object();
}

}  // namespace pvtap::analyzer
