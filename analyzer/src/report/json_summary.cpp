// The last jsonl line: the summary fields first, then the details of each bus.
#include <optional>
#include <string>
#include <string_view>

#include "formatting/json_writer.h"
#include "report/frame_findings.h"
#include "report/report_writers.h"
#include "report/value_json.h"

namespace pvtap::analyzer {
namespace {

void milliseconds(JsonWriter& w, double seconds) {
  w.fixed(seconds * 1e3, 3);
}

// A time in ms, or null where there is none.
void optional_milliseconds(JsonWriter& w, JsonKey name, std::optional<double> seconds) {
  w.key(name);
  if (seconds) {
    milliseconds(w, *seconds);
  } else {
    w.null();
  }
}

struct NamedFigure {
  JsonKey name;
  double value;
};

// {"count":n,"min":..,"mean":..,"p50":..,"p95":..,"p99":..,"max":..} in ms; null values when
// nothing was measured.
void distribution(JsonWriter& w, const DistributionSummary& d) {
  w.begin_object();
  w.field("count", d.count);
  const NamedFigure figures[] = {{"min", d.min}, {"mean", d.mean}, {"p50", d.p50},
                                 {"p95", d.p95}, {"p99", d.p99},   {"max", d.max}};
  for (const auto& [name, value] : figures) {
    optional_milliseconds(w, name, d.count == 0 ? std::nullopt : std::optional(value));
  }
  w.end_object();
}

void device_object(JsonWriter& w, const DeviceName& d) {
  w.key("device");
  w.begin_object();
  w.field("name", d.text());
  const auto part = [&](JsonKey key, const std::string& value) {
    if (!value.empty()) w.field(key, value);
  };
  part("vendor", d.vendor);
  part("product", d.product);
  part("revision", d.revision);
  part("server_id", d.server_id);
  w.end_object();
}

void station_object(JsonWriter& w, const StationSummary& s) {
  w.begin_object();
  w.field("requests", s.requests);
  w.field("responses", s.responses);
  w.field("bad_checks", s.bad_checks);
  w.field("timeouts", s.timeouts);
  w.field("damaged_replies", s.damaged_replies);
  w.field("exceptions", s.exceptions);
  w.field("unsolicited", s.unsolicited);
  w.field("duplicates", s.duplicates);
  w.field("address_conflicts", s.address_conflicts);
  // Only stations that named themselves, or changed dialect, carry these keys.
  if (!s.device.empty()) device_object(w, s.device);
  if (s.dialect_changes > 0) w.field("dialect_changes", s.dialect_changes);
  w.key("latency_ms");
  distribution(w, s.latency);
  w.key("values");
  w.begin_array();
  for (const LatestValue& v : s.latest_values) write_latest_value_json(w, v);
  w.end_array();
  // Only stations with blocks no map names carry them.
  if (!s.inferred.empty()) {
    w.key("inferred");
    w.begin_array();
    for (const InferredBlock& b : s.inferred) write_inferred_block_json(w, b);
    w.end_array();
  }
  w.end_object();
}

void stations(JsonWriter& w, const AuditReport& report) {
  w.key("stations");
  w.begin_object();
  for (const BusFindings& bus : report.buses) {
    for (const StationSummary& s : bus.report.stations) {
      w.key_text(station_key(report, bus, s.station));
      station_object(w, s);
    }
  }
  w.end_object();
}

// {"damaged_frames":n,"unanswered_damaged_requests":n,"claimed":{"88":1,...}}: the damaged
// frames no station can be named for, by the address they claimed.
void unknown_station(JsonWriter& w, const UnknownStation& u) {
  w.key("unknown_station");
  w.begin_object();
  w.field("damaged_frames", u.damaged_frames);
  w.field("unanswered_damaged_requests", u.unanswered_damaged_requests);
  w.key("claimed");
  w.begin_object();
  for (const auto& claimed : u.claimed) {
    std::string address;
    append_uint(address, claimed.station);
    w.key_text(address);
    w.uint(claimed.frames);
  }
  w.end_object();
  w.end_object();
}

void timing(JsonWriter& w, const BusReport& r, const AuditSettings& settings) {
  const BusGapReport& bus = r.timing.bus;
  w.begin_object();
  w.field_bool("judged", bus.measurable);
  w.key("reason");
  if (bus.measurable) {
    w.null();
  } else {
    w.string(bus.not_measurable_reason);
  }
  // Only where a source vouches for the times, so that other reports keep their shape.
  if (!bus.timestamp_source.empty()) w.field("timed_by", bus.timestamp_source);
  w.field("baud", settings.baud);
  w.key("t15_ms");
  milliseconds(w, bus.t15);
  w.key("t35_ms");
  milliseconds(w, bus.t35);
  w.key("gap_ms");
  distribution(w, bus.gaps);
  w.field("t15_violations", bus.inner_gap_t15.count);
  w.field("t35_violations", bus.spacing_t35.count);
  w.end_object();
}

// A poll block's start or count: the wire number, or null where the request has none.
void optional_count(JsonWriter& w, JsonKey name, std::optional<std::uint16_t> value) {
  w.key(name);
  if (value) {
    w.uint(*value);
  } else {
    w.null();
  }
}

// A poll block as "polls" and a master's "plan" begin it: station, dialect, function, start,
// count.
void poll_block(JsonWriter& w, const PollPeriod& p) {
  w.field("station", p.block.station);
  w.field("dialect", to_string(p.block.dialect));
  w.field("function", p.block.function);
  optional_count(w, "start", p.block.start);
  optional_count(w, "count", p.block.count);
}

// A poll period figure in ms; null for a block requested once (no interval measured).
void period_figure(JsonWriter& w, JsonKey name, const PollPeriod& p, double seconds) {
  optional_milliseconds(w, name, p.period.intervals == 0 ? std::nullopt : std::optional(seconds));
}

void polls(JsonWriter& w, const BusReport& r) {
  w.begin_array();
  for (const PollPeriod& p : r.timing.poll_periods) {
    w.begin_object();
    poll_block(w, p);
    w.field("intervals", p.period.intervals);
    period_figure(w, "period_ms", p, p.period.mean);
    period_figure(w, "jitter_ms", p, p.period.stddev);
    period_figure(w, "max_deviation_ms", p, p.period.max_deviation);
    w.end_object();
  }
  w.end_array();
}

// The masters told apart by their poll cycles: each with its cycle, share, turnaround and the
// poll blocks of its plan (as "polls" writes them, by station, function, start and count).
void masters(JsonWriter& w, const BusReport& r) {
  w.begin_array();
  for (const MasterPlan& m : r.timing.masters) {
    w.begin_object();
    optional_milliseconds(w, "period_ms", m.period > 0 ? std::optional(m.period) : std::nullopt);
    w.field("requests", m.requests);
    w.field_fixed("share", m.share, 3);
    optional_milliseconds(w, "turnaround_ms", m.turnaround);
    w.key("plan");
    w.begin_array();
    for (const std::size_t k : m.polls) {
      const PollPeriod& p = r.timing.poll_periods[k];
      w.begin_object();
      poll_block(w, p);
      optional_milliseconds(w, "cycle_ms", p.cycle);
      w.end_object();
    }
    w.end_array();
    w.end_object();
  }
  w.end_array();
}

void buses(JsonWriter& w, const AuditReport& report) {
  w.key("buses");
  w.begin_array();
  for (const BusFindings& bus : report.buses) {
    w.begin_object();
    w.key("bus");
    if (bus.name.empty()) {
      w.null();
    } else {
      w.string(bus.name);
    }
    w.field("bytes", bus.report.bytes.bytes_in);
    w.field("frames", bus.report.bytes.frames);
    if (bus.serial) write_serial_line_json(w, *bus.serial);
    w.key("timing");
    timing(w, bus.report, report.settings);
    w.key("polls");
    polls(w, bus.report);
    w.field("untracked_poll_requests", bus.report.timing.untracked_poll_requests);
    w.key("masters");
    masters(w, bus.report);
    w.field("requests_while_reply_due", bus.report.timing.requests_while_reply_due);
    w.field("collisions", bus.report.collisions);
    w.field("lost_in_collision", bus.report.lost_in_collision);
    w.end_object();
  }
  w.end_array();
}

// Modbus/TCP flows, only where there are some, so that a report of serial gateways keeps
// its shape.
void mbap(JsonWriter& w, const NetworkStats& n) {
  w.key("mbap");
  w.begin_object();
  w.field("flows", n.mbap_flows);
  w.field("adus", n.mbap_adus);
  w.field("carrier_bytes", n.mbap_carrier_bytes);
  w.field("findings", n.mbap_findings);
  w.field("skipped_bytes", n.mbap_skipped_bytes);
  w.end_object();
}

// The logger sticks' V5 frames: what they carried and their findings (latency on their buses
// is measured at the LAN side).
void solarman_v5_totals(JsonWriter& w, const NetworkStats& n) {
  const solarman_v5::Totals& v = n.v5;
  w.key("solarman_v5");
  w.begin_object();
  w.field("flows", n.v5_flows);
  w.field("frames", v.frames);
  w.field("rtu_frames", v.rtu_frames);
  w.field("stick_frames", v.stick_frames);
  w.field("heartbeats", v.heartbeats);
  w.field("data_reports", v.data_reports);
  w.field("stick_answers", v.stick_answers);
  w.field("carrier_bytes", v.carrier_bytes);
  w.field("rtu_bytes", v.rtu_bytes);
  w.field("quirk_bytes", v.quirk_bytes);
  w.field("quirk_frames", v.quirk_frames);
  w.field("bad_checksums", v.checksum_failures);
  w.field("truncated_frames", v.truncated);
  w.field("length_mismatches", v.length_mismatches);
  w.field("broken_bytes", v.broken_bytes);
  w.field("noise_bytes", v.noise_bytes);
  w.field("stick_codes", v.stick_codes);
  w.field("stick_timeouts", v.stick_timeouts);
  w.field("refused_requests", v.refused_requests);
  w.field("other_stick_codes", v.other_codes);
  w.field("replies_after_next_request", v.replies_after_next_request);
  w.field("unpaired_replies", v.unpaired_replies);
  w.key("stick_findings");
  w.begin_array();
  for (const std::string& example : n.v5_finding_examples) w.string(example);
  w.end_array();
  w.end_object();
}

void network(JsonWriter& w, const NetworkStats& n) {
  w.key("network");
  w.begin_object();
  w.field("flows_analyzed", n.flows_analyzed);
  w.field("flows_ignored", n.flows_ignored);
  w.field("ignored_bytes", n.ignored_bytes);
  w.field("retransmitted_bytes", n.retransmitted_bytes);
  w.field("out_of_order_segments", n.out_of_order_segments);
  if (n.mbap_flows > 0) mbap(w, n);
  if (n.v5_flows > 0) solarman_v5_totals(w, n);
  w.end_object();
}

// "dialect 0x02": count.
void exception_codes(JsonWriter& w, const BusReport& t) {
  w.key("exception_codes");
  w.begin_object();
  for (const auto& e : t.exception_codes) {
    std::string name(to_string(e.dialect));
    name += ' ';
    append_hex_byte(name, e.code);
    w.key_text(name);
    w.uint(e.count);
  }
  w.end_object();
}

void details(JsonWriter& w, const AuditReport& report, const BusReport& t) {
  w.field("frame_bytes", t.bytes.frame_bytes);
  w.field("noise_runs", t.bytes.noise_runs);
  w.field("lost_bytes", t.gaps.lost_bytes);
  w.field("gaps", t.gaps.gaps);
  w.field("malformed_frames", t.malformed_frames);
  w.field("unsolicited", t.unsolicited);
  w.field("late_replies", t.late_replies);
  w.field("duplicates", t.duplicates);
  w.field("address_conflicts", t.address_conflicts);
  w.field("echoes", t.echoes);
  w.field("collisions", t.collisions);
  w.field("lost_in_collision", t.lost_in_collision);
  w.field("byte_count_mismatches", t.count_mismatches);
  // Findings of plain Modbus traffic: only where there are some, so that a report of
  // inverters alone keeps its shape.
  if (t.quantity_problems > 0) w.field("quantity_problems", t.quantity_problems);
  if (t.write_count_problems > 0) w.field("write_count_problems", t.write_count_problems);
  if (t.forbidden_broadcasts > 0) w.field("forbidden_broadcasts", t.forbidden_broadcasts);
  if (t.dialect_changes > 0) w.field("dialect_changes", t.dialect_changes);
  if (t.gateway_timeouts > 0) w.field("gateway_timeouts", t.gateway_timeouts);
  w.field("unanswered_at_end", t.unanswered_at_end);
  w.field("unanswered_after_loss", t.unanswered_after_loss);
  exception_codes(w, t);
  if (report.network) network(w, report.flows);
}

void input(JsonWriter& w, const InputReport& in) {
  w.begin_object();
  w.field("path", in.path);
  w.field("link_type", in.link_type);
  w.field("records", in.records);
  if (!in.pair.empty()) w.field("pair", in.pair);
  w.field("file_bytes", in.file_bytes);
  w.field("read_bytes", in.read_bytes);
  if (in.first_time) {
    w.field_fixed("first_ts", *in.first_time, 6);
    w.field_fixed("last_ts", in.last_time, 6);
  }
  if (in.damaged()) {
    const bool corrupt = in.error.rfind("corrupt", 0) == 0;
    w.field("damage", std::string_view(in.unreadable ? "not read"
                                       : corrupt     ? "corrupt"
                                                     : "truncated"));
    w.field("error", in.error);
  }
  if (in.steps_back > 0) {
    w.field("clock_steps_back", in.steps_back);
    w.field("first_step_back_record", in.first_step_back_record);
    w.key("largest_step_back_ms");
    milliseconds(w, in.largest_step_back);
  }
  w.end_object();
}

// The files in the order read, each with how reading it went.
void inputs(JsonWriter& w, const AuditReport& report) {
  w.key("inputs");
  w.begin_array();
  for (const InputReport& in : report.inputs) input(w, in);
  w.end_array();
}

}  // namespace

void write_json_summary(const AuditReport& report, OutputStream& out) {
  const BusReport t = report.totals();
  JsonWriter w(out.buffer());
  w.begin_object();
  w.field_plain("type", "summary");
  w.field("bytes", t.bytes.bytes_in);
  w.field("frames", t.bytes.frames);
  w.field("requests", t.requests);
  w.field("responses", t.responses);
  w.field("bad_checks", t.bytes.bad_frames);
  w.field("timeouts", t.timeouts);
  w.field("damaged_replies", t.damaged_replies);
  w.field("unanswered_damaged_requests", t.unanswered_damaged_requests);
  w.field("noise_bytes", t.bytes.noise_bytes);
  w.field("exceptions", t.exceptions);
  w.key("latency_ms");
  distribution(w, report.latency);
  stations(w, report);
  unknown_station(w, t.unknown_station);
  details(w, report, t);
  buses(w, report);
  if (!report.inputs.empty()) inputs(w, report);
  write_live_sources_json(w, report.live);
  w.end_object();
  w.buffer() += '\n';
  out.done();
}

}  // namespace pvtap::analyzer
