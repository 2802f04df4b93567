// The last jsonl line: the summary fields first, then the details of each bus.
#include <optional>
#include <string>
#include <string_view>

#include "formatting/json_text.h"
#include "formatting/number_text.h"
#include "report/frame_findings.h"
#include "report/report_writers.h"

namespace pvtap::analyzer {
namespace {

void milliseconds(std::string& o, double seconds) {
  append_fixed(o, seconds * 1e3, 3);
}

// {"count":n,"min":..,"mean":..,"p50":..,"p95":..,"p99":..,"max":..} in ms; null values when
// nothing was measured.
void distribution(std::string& o, const DistributionSummary& d) {
  o += "{\"count\":";
  append_uint(o, d.count);
  const std::pair<const char*, double> fields[] = {{"min", d.min}, {"mean", d.mean},
                                                   {"p50", d.p50}, {"p95", d.p95},
                                                   {"p99", d.p99}, {"max", d.max}};
  for (const auto& [name, value] : fields) {
    append_json_key(o, name);
    if (d.count == 0) {
      o += "null";
    } else {
      milliseconds(o, value);
    }
  }
  o += '}';
}

void device_object(std::string& o, const DeviceName& d) {
  append_json_key(o, "device");
  o += "{\"name\":";
  append_json_string(o, d.text());
  const std::pair<const char*, const std::string*> parts[] = {{"vendor", &d.vendor},
                                                              {"product", &d.product},
                                                              {"revision", &d.revision},
                                                              {"server_id", &d.server_id}};
  for (const auto& [key, value] : parts) {
    if (value->empty()) continue;
    append_json_key(o, key);
    append_json_string(o, *value);
  }
  o += '}';
}

void station_object(std::string& o, const StationSummary& s) {
  o += "{\"requests\":";
  append_uint(o, s.requests);
  append_json_count(o, "responses", s.responses);
  append_json_count(o, "bad_checks", s.bad_checks);
  append_json_count(o, "timeouts", s.timeouts);
  append_json_count(o, "damaged_replies", s.damaged_replies);
  append_json_count(o, "exceptions", s.exceptions);
  append_json_count(o, "unsolicited", s.unsolicited);
  append_json_count(o, "duplicates", s.duplicates);
  append_json_count(o, "address_conflicts", s.address_conflicts);
  // Only stations that named themselves, or changed dialect, carry these keys.
  if (!s.device.empty()) device_object(o, s.device);
  if (s.dialect_changes > 0) append_json_count(o, "dialect_changes", s.dialect_changes);
  append_json_key(o, "latency_ms");
  distribution(o, s.latency);
  append_json_key(o, "values");
  o += '[';
  for (std::size_t i = 0; i < s.latest_values.size(); ++i) {
    if (i > 0) o += ',';
    append_latest_value_json(o, s.latest_values[i]);
  }
  o += ']';
  // Only stations with blocks no map names carry them.
  if (!s.inferred.empty()) {
    append_json_key(o, "inferred");
    o += '[';
    for (std::size_t i = 0; i < s.inferred.size(); ++i) {
      if (i > 0) o += ',';
      append_inferred_block_json(o, s.inferred[i]);
    }
    o += ']';
  }
  o += '}';
}

void stations(std::string& o, const AuditReport& report) {
  append_json_key(o, "stations");
  o += '{';
  bool first = true;
  for (const BusFindings& bus : report.buses) {
    for (const StationSummary& s : bus.report.stations) {
      if (!first) o += ',';
      first = false;
      append_json_string(o, station_key(report, bus, s.station));
      o += ':';
      station_object(o, s);
    }
  }
  o += '}';
}

// {"damaged_frames":n,"unanswered_damaged_requests":n,"claimed":{"88":1,...}}: the damaged
// frames no station can be named for, by the address they claimed.
void unknown_station(std::string& o, const UnknownStation& u) {
  append_json_key(o, "unknown_station");
  o += "{\"damaged_frames\":";
  append_uint(o, u.damaged_frames);
  append_json_count(o, "unanswered_damaged_requests", u.unanswered_damaged_requests);
  append_json_key(o, "claimed");
  o += '{';
  for (std::size_t i = 0; i < u.claimed.size(); ++i) {
    if (i > 0) o += ',';
    std::string address;
    append_uint(address, u.claimed[i].station);
    append_json_string(o, address);
    o += ':';
    append_uint(o, u.claimed[i].frames);
  }
  o += "}}";
}

void timing(std::string& o, const BusReport& r, const AuditSettings& settings) {
  const BusGapReport& bus = r.timing.bus;
  o += "{\"judged\":";
  o += bus.measurable ? "true" : "false";
  append_json_key(o, "reason");
  if (bus.measurable) {
    o += "null";
  } else {
    append_json_string(o, bus.not_measurable_reason);
  }
  // Only where a source vouches for the times, so that other reports keep their shape.
  if (!bus.timestamp_source.empty()) {
    append_json_key(o, "timed_by");
    append_json_string(o, bus.timestamp_source);
  }
  append_json_count(o, "baud", settings.baud);
  append_json_key(o, "t15_ms");
  milliseconds(o, bus.t15);
  append_json_key(o, "t35_ms");
  milliseconds(o, bus.t35);
  append_json_key(o, "gap_ms");
  distribution(o, bus.gaps);
  append_json_count(o, "t15_violations", bus.inner_gap_t15.count);
  append_json_count(o, "t35_violations", bus.spacing_t35.count);
  o += '}';
}

// A poll block's start or count: the wire number, or null where the request has none.
void optional_count(std::string& o, std::string_view name, std::optional<std::uint16_t> value) {
  if (value) {
    append_json_count(o, name, *value);
  } else {
    append_json_key(o, name);
    o += "null";
  }
}

// A poll period figure in ms; null for a block requested once (no interval measured).
void period_figure(std::string& o, std::string_view name, const PollPeriod& p, double seconds) {
  append_json_key(o, name);
  if (p.period.intervals == 0) {
    o += "null";
  } else {
    milliseconds(o, seconds);
  }
}

void polls(std::string& o, const BusReport& r) {
  o += '[';
  for (std::size_t i = 0; i < r.timing.poll_periods.size(); ++i) {
    const PollPeriod& p = r.timing.poll_periods[i];
    if (i > 0) o += ',';
    o += "{\"station\":";
    append_uint(o, p.block.station);
    append_json_key(o, "dialect");
    append_json_string(o, to_string(p.block.dialect));
    append_json_count(o, "function", p.block.function);
    optional_count(o, "start", p.block.start);
    optional_count(o, "count", p.block.count);
    append_json_count(o, "intervals", p.period.intervals);
    period_figure(o, "period_ms", p, p.period.mean);
    period_figure(o, "jitter_ms", p, p.period.stddev);
    period_figure(o, "max_deviation_ms", p, p.period.max_deviation);
    o += '}';
  }
  o += ']';
}

// The masters told apart by their poll cycles: each with its cycle, share, turnaround and the
// poll blocks of its plan (as "polls" writes them, by station, function, start and count).
void masters(std::string& o, const BusReport& r) {
  o += '[';
  for (std::size_t i = 0; i < r.timing.masters.size(); ++i) {
    const MasterPlan& m = r.timing.masters[i];
    if (i > 0) o += ',';
    o += "{\"period_ms\":";
    if (m.period > 0) {
      milliseconds(o, m.period);
    } else {
      o += "null";
    }
    append_json_count(o, "requests", m.requests);
    append_json_key(o, "share");
    append_fixed(o, m.share, 3);
    append_json_key(o, "turnaround_ms");
    if (m.turnaround) {
      milliseconds(o, *m.turnaround);
    } else {
      o += "null";
    }
    append_json_key(o, "plan");
    o += '[';
    for (std::size_t k = 0; k < m.polls.size(); ++k) {
      const PollPeriod& p = r.timing.poll_periods[m.polls[k]];
      if (k > 0) o += ',';
      o += "{\"station\":";
      append_uint(o, p.block.station);
      append_json_key(o, "dialect");
      append_json_string(o, to_string(p.block.dialect));
      append_json_count(o, "function", p.block.function);
      optional_count(o, "start", p.block.start);
      optional_count(o, "count", p.block.count);
      append_json_key(o, "cycle_ms");
      if (p.cycle) {
        milliseconds(o, *p.cycle);
      } else {
        o += "null";
      }
      o += '}';
    }
    o += "]}";
  }
  o += ']';
}

void buses(std::string& o, const AuditReport& report) {
  append_json_key(o, "buses");
  o += '[';
  for (std::size_t i = 0; i < report.buses.size(); ++i) {
    const BusFindings& bus = report.buses[i];
    if (i > 0) o += ',';
    o += "{\"bus\":";
    if (bus.name.empty()) {
      o += "null";
    } else {
      append_json_string(o, bus.name);
    }
    append_json_count(o, "bytes", bus.report.bytes.bytes_in);
    append_json_count(o, "frames", bus.report.bytes.frames);
    if (bus.serial) append_serial_line_json(*bus.serial, o);
    append_json_key(o, "timing");
    timing(o, bus.report, report.settings);
    append_json_key(o, "polls");
    polls(o, bus.report);
    append_json_count(o, "untracked_poll_requests", bus.report.timing.untracked_poll_requests);
    append_json_key(o, "masters");
    masters(o, bus.report);
    append_json_count(o, "requests_while_reply_due", bus.report.timing.requests_while_reply_due);
    append_json_count(o, "collisions", bus.report.collisions);
    append_json_count(o, "lost_in_collision", bus.report.lost_in_collision);
    o += '}';
  }
  o += ']';
}

// Modbus/TCP flows, only where there are some, so that a report of serial gateways keeps
// its shape.
void mbap(std::string& o, const NetworkStats& n) {
  o += ",\"mbap\":{\"flows\":";
  append_uint(o, n.mbap_flows);
  append_json_count(o, "adus", n.mbap_adus);
  append_json_count(o, "carrier_bytes", n.mbap_carrier_bytes);
  append_json_count(o, "findings", n.mbap_findings);
  append_json_count(o, "skipped_bytes", n.mbap_skipped_bytes);
  o += '}';
}

// The logger sticks' V5 frames: what they carried and their findings (latency on their buses
// is measured at the LAN side).
void solarman_v5_totals(std::string& o, const NetworkStats& n) {
  const solarman_v5::Totals& v = n.v5;
  append_json_key(o, "solarman_v5");
  o += "{\"flows\":";
  append_uint(o, n.v5_flows);
  append_json_count(o, "frames", v.frames);
  append_json_count(o, "rtu_frames", v.rtu_frames);
  append_json_count(o, "stick_frames", v.stick_frames);
  append_json_count(o, "heartbeats", v.heartbeats);
  append_json_count(o, "data_reports", v.data_reports);
  append_json_count(o, "stick_answers", v.stick_answers);
  append_json_count(o, "carrier_bytes", v.carrier_bytes);
  append_json_count(o, "rtu_bytes", v.rtu_bytes);
  append_json_count(o, "quirk_bytes", v.quirk_bytes);
  append_json_count(o, "quirk_frames", v.quirk_frames);
  append_json_count(o, "bad_checksums", v.checksum_failures);
  append_json_count(o, "truncated_frames", v.truncated);
  append_json_count(o, "length_mismatches", v.length_mismatches);
  append_json_count(o, "broken_bytes", v.broken_bytes);
  append_json_count(o, "noise_bytes", v.noise_bytes);
  append_json_count(o, "stick_codes", v.stick_codes);
  append_json_count(o, "stick_timeouts", v.stick_timeouts);
  append_json_count(o, "refused_requests", v.refused_requests);
  append_json_count(o, "other_stick_codes", v.other_codes);
  append_json_count(o, "replies_after_next_request", v.replies_after_next_request);
  append_json_count(o, "unpaired_replies", v.unpaired_replies);
  append_json_key(o, "stick_findings");
  o += '[';
  for (std::size_t i = 0; i < n.v5_finding_examples.size(); ++i) {
    if (i > 0) o += ',';
    append_json_string(o, n.v5_finding_examples[i]);
  }
  o += "]}";
}

void details(std::string& o, const AuditReport& report, const BusReport& t) {
  append_json_count(o, "frame_bytes", t.bytes.frame_bytes);
  append_json_count(o, "noise_runs", t.bytes.noise_runs);
  append_json_count(o, "lost_bytes", t.gaps.lost_bytes);
  append_json_count(o, "gaps", t.gaps.gaps);
  append_json_count(o, "malformed_frames", t.malformed_frames);
  append_json_count(o, "unsolicited", t.unsolicited);
  append_json_count(o, "late_replies", t.late_replies);
  append_json_count(o, "duplicates", t.duplicates);
  append_json_count(o, "address_conflicts", t.address_conflicts);
  append_json_count(o, "echoes", t.echoes);
  append_json_count(o, "collisions", t.collisions);
  append_json_count(o, "lost_in_collision", t.lost_in_collision);
  append_json_count(o, "byte_count_mismatches", t.count_mismatches);
  // Findings of plain Modbus traffic: only where there are some, so that a report of
  // inverters alone keeps its shape.
  if (t.quantity_problems > 0) append_json_count(o, "quantity_problems", t.quantity_problems);
  if (t.write_count_problems > 0) {
    append_json_count(o, "write_count_problems", t.write_count_problems);
  }
  if (t.forbidden_broadcasts > 0) {
    append_json_count(o, "forbidden_broadcasts", t.forbidden_broadcasts);
  }
  if (t.dialect_changes > 0) append_json_count(o, "dialect_changes", t.dialect_changes);
  if (t.gateway_timeouts > 0) append_json_count(o, "gateway_timeouts", t.gateway_timeouts);
  append_json_count(o, "unanswered_at_end", t.unanswered_at_end);
  append_json_count(o, "unanswered_after_loss", t.unanswered_after_loss);
  append_json_key(o, "exception_codes");
  o += '{';
  for (std::size_t i = 0; i < t.exception_codes.size(); ++i) {
    if (i > 0) o += ',';
    std::string name(to_string(t.exception_codes[i].dialect));
    name += ' ';
    append_hex_byte(name, t.exception_codes[i].code);
    append_json_string(o, name);
    o += ':';
    append_uint(o, t.exception_codes[i].count);
  }
  o += '}';
  if (report.network) {
    append_json_key(o, "network");
    o += "{\"flows_analyzed\":";
    append_uint(o, report.flows.flows_analyzed);
    append_json_count(o, "flows_ignored", report.flows.flows_ignored);
    append_json_count(o, "ignored_bytes", report.flows.ignored_bytes);
    append_json_count(o, "retransmitted_bytes", report.flows.retransmitted_bytes);
    append_json_count(o, "out_of_order_segments", report.flows.out_of_order_segments);
    if (report.flows.mbap_flows > 0) mbap(o, report.flows);
    if (report.flows.v5_flows > 0) solarman_v5_totals(o, report.flows);
    o += '}';
  }
}

// The files in the order read, each with how reading it went.
void inputs(std::string& o, const AuditReport& report) {
  append_json_key(o, "inputs");
  o += '[';
  for (std::size_t i = 0; i < report.inputs.size(); ++i) {
    const InputReport& in = report.inputs[i];
    if (i > 0) o += ',';
    o += "{\"path\":";
    append_json_string(o, in.path);
    append_json_key(o, "link_type");
    append_json_string(o, in.link_type);
    append_json_count(o, "records", in.records);
    if (!in.pair.empty()) {
      append_json_key(o, "pair");
      append_json_string(o, in.pair);
    }
    append_json_count(o, "file_bytes", in.file_bytes);
    append_json_count(o, "read_bytes", in.read_bytes);
    if (in.first_time) {
      append_json_key(o, "first_ts");
      append_fixed(o, *in.first_time, 6);
      append_json_key(o, "last_ts");
      append_fixed(o, in.last_time, 6);
    }
    if (in.damaged()) {
      append_json_key(o, "damage");
      const bool corrupt = in.error.rfind("corrupt", 0) == 0;
      append_json_string(o, in.unreadable ? "not read" : corrupt ? "corrupt" : "truncated");
      append_json_key(o, "error");
      append_json_string(o, in.error);
    }
    if (in.steps_back > 0) {
      append_json_count(o, "clock_steps_back", in.steps_back);
      append_json_count(o, "first_step_back_record", in.first_step_back_record);
      append_json_key(o, "largest_step_back_ms");
      milliseconds(o, in.largest_step_back);
    }
    o += '}';
  }
  o += ']';
}

}  // namespace

void write_json_summary(const AuditReport& report, OutputStream& out) {
  const BusReport t = report.totals();
  std::string& o = out.buffer();
  o += "{\"type\":\"summary\"";
  append_json_count(o, "bytes", t.bytes.bytes_in);
  append_json_count(o, "frames", t.bytes.frames);
  append_json_count(o, "requests", t.requests);
  append_json_count(o, "responses", t.responses);
  append_json_count(o, "bad_checks", t.bytes.bad_frames);
  append_json_count(o, "timeouts", t.timeouts);
  append_json_count(o, "damaged_replies", t.damaged_replies);
  append_json_count(o, "unanswered_damaged_requests", t.unanswered_damaged_requests);
  append_json_count(o, "noise_bytes", t.bytes.noise_bytes);
  append_json_count(o, "exceptions", t.exceptions);
  append_json_key(o, "latency_ms");
  distribution(o, report.latency);
  stations(o, report);
  unknown_station(o, t.unknown_station);
  details(o, report, t);
  buses(o, report);
  if (!report.inputs.empty()) inputs(o, report);
  append_live_sources_json(report.live, o);
  o += "}\n";
  out.done();
}

}  // namespace pvtap::analyzer
