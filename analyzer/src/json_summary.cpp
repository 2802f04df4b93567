// The last jsonl line: the summary fields first, then the details of each bus.
#include <string>

#include "frame_findings.h"
#include "summary_writers.h"
#include "text_append.h"

namespace pvtap::analyzer {
namespace {

void key(std::string& o, std::string_view name) {
  o += ",\"";
  o += name;
  o += "\":";
}

void count(std::string& o, std::string_view name, std::uint64_t value) {
  key(o, name);
  append_uint(o, value);
}

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
    key(o, name);
    if (d.count == 0) {
      o += "null";
    } else {
      milliseconds(o, value);
    }
  }
  o += '}';
}

void station_object(std::string& o, const StationSummary& s) {
  o += "{\"requests\":";
  append_uint(o, s.requests);
  count(o, "responses", s.responses);
  count(o, "bad_checks", s.bad_checks);
  count(o, "timeouts", s.timeouts);
  count(o, "exceptions", s.exceptions);
  count(o, "unsolicited", s.unsolicited);
  count(o, "duplicates", s.duplicates);
  key(o, "latency_ms");
  distribution(o, s.latency);
  key(o, "values");
  o += '[';
  for (std::size_t i = 0; i < s.latest_values.size(); ++i) {
    if (i > 0) o += ',';
    append_value_json(o, s.latest_values[i].value, s.latest_values[i].dialect);
  }
  o += "]}";
}

void stations(std::string& o, const AuditReport& report) {
  key(o, "stations");
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

void timing(std::string& o, const BusReport& r, const AuditSettings& settings) {
  const BusGapReport& bus = r.timing.bus;
  o += "{\"judged\":";
  o += bus.measurable ? "true" : "false";
  key(o, "reason");
  if (bus.measurable) {
    o += "null";
  } else {
    append_json_string(o, bus.not_measurable_reason);
  }
  count(o, "baud", settings.baud);
  key(o, "t15_ms");
  milliseconds(o, bus.t15);
  key(o, "t35_ms");
  milliseconds(o, bus.t35);
  key(o, "gap_ms");
  distribution(o, bus.gaps);
  count(o, "t15_violations", bus.inner_gap_t15.count);
  count(o, "t35_violations", bus.spacing_t35.count);
  o += '}';
}

void polls(std::string& o, const BusReport& r) {
  o += '[';
  for (std::size_t i = 0; i < r.timing.poll_periods.size(); ++i) {
    const PollPeriod& p = r.timing.poll_periods[i];
    if (i > 0) o += ',';
    o += "{\"dialect\":\"";
    o += to_string(p.dialect);
    o += '"';
    count(o, "station", p.station);
    count(o, "function", p.function);
    count(o, "intervals", p.period.intervals);
    key(o, "period_ms");
    milliseconds(o, p.period.mean);
    key(o, "jitter_ms");
    milliseconds(o, p.period.stddev);
    key(o, "max_deviation_ms");
    milliseconds(o, p.period.max_deviation);
    o += '}';
  }
  o += ']';
}

void buses(std::string& o, const AuditReport& report) {
  key(o, "buses");
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
    count(o, "bytes", bus.report.bytes.bytes_in);
    count(o, "frames", bus.report.bytes.frames);
    key(o, "timing");
    timing(o, bus.report, report.settings);
    key(o, "polls");
    polls(o, bus.report);
    o += '}';
  }
  o += ']';
}

void details(std::string& o, const AuditReport& report, const BusReport& t) {
  count(o, "frame_bytes", t.bytes.frame_bytes);
  count(o, "noise_runs", t.bytes.noise_runs);
  count(o, "lost_bytes", t.gaps.lost_bytes);
  count(o, "gaps", t.gaps.gaps);
  count(o, "malformed_frames", t.malformed_frames);
  count(o, "unsolicited", t.unsolicited);
  count(o, "late_replies", t.late_replies);
  count(o, "duplicates", t.duplicates);
  count(o, "byte_count_mismatches", t.count_mismatches);
  count(o, "unanswered_at_end", t.unanswered_at_end);
  count(o, "unanswered_after_loss", t.unanswered_after_loss);
  key(o, "exception_codes");
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
    key(o, "network");
    o += "{\"flows_analyzed\":";
    append_uint(o, report.flows.flows_analyzed);
    count(o, "flows_ignored", report.flows.flows_ignored);
    count(o, "ignored_bytes", report.flows.ignored_bytes);
    count(o, "retransmitted_bytes", report.flows.retransmitted_bytes);
    count(o, "out_of_order_segments", report.flows.out_of_order_segments);
    o += '}';
  }
}

}  // namespace

void write_json_summary(const AuditReport& report, OutputStream& out) {
  const BusReport t = report.totals();
  std::string& o = out.buffer();
  o += "{\"type\":\"summary\"";
  count(o, "bytes", t.bytes.bytes_in);
  count(o, "frames", t.bytes.frames);
  count(o, "requests", t.requests);
  count(o, "responses", t.responses);
  count(o, "bad_checks", t.bytes.bad_frames);
  count(o, "timeouts", t.timeouts);
  count(o, "noise_bytes", t.bytes.noise_bytes);
  count(o, "exceptions", t.exceptions);
  key(o, "latency_ms");
  distribution(o, report.latency);
  stations(o, report);
  details(o, report, t);
  buses(o, report);
  append_live_sources_json(report.live, o);
  o += "}\n";
  out.done();
}

}  // namespace pvtap::analyzer
