#include "report/audit_report.h"

#include <algorithm>
#include <cstdio>
#include <map>
#include <utility>

#include "formatting/number_text.h"

namespace pvtap::analyzer {

BusReport AuditReport::totals() const {
  BusReport t;
  std::map<std::pair<Dialect, std::uint8_t>, std::uint64_t> codes;
  for (const BusFindings& bus : buses) {
    const BusReport& r = bus.report;
    t.counters() += r.counters();
    t.unknown_station += r.unknown_station;
    for (const ExceptionTally& e : r.exception_codes) codes[{e.dialect, e.code}] += e.count;
  }
  for (const auto& [key, count] : codes) {
    t.exception_codes.push_back(ExceptionTally{key.first, key.second, count});
  }
  return t;
}

bool has_findings(const AuditReport& report) {
  const BusReport t = report.totals();
  return t.bytes.bad_frames > 0 || t.timeouts > 0 || t.exceptions > 0;
}

bool found_no_frame(const AuditReport& report) {
  return report.totals().bytes.frames == 0;
}

std::string no_frame_hint(const AuditReport& report) {
  const BusReport t = report.totals();
  if (t.bytes.frames > 0) return {};
  if (t.bytes.bytes_in == 0) {
    if (report.flows.flows_ignored > 0) {
      return "no frame: no bus bytes, and " + std::to_string(report.flows.flows_ignored) +
             " TCP/UDP flows ignored (" + std::to_string(report.flows.ignored_bytes) + " bytes): " +
             (report.settings.ports_given ? "is the gateway on another --port?"
                                          : "no serial-to-TCP gateway was recognised; give "
                                            "its port with --port PORT");
    }
    return "no frame: the input holds no bus bytes";
  }
  std::string hint = "no frame in " + std::to_string(t.bytes.bytes_in) + " bus bytes: ";
  if (!report.settings.all_dialects)
    hint += "try --dialect auto (this run read only the dialects given); ";
  return hint +
         "check the tap's baud rate, parity and stop bits (a wrong one reads every "
         "byte as noise); --baud " +
         std::to_string(report.settings.baud) + " only sets the timing rules";
}

std::optional<TimeSpan> AuditReport::time_span() const {
  std::optional<TimeSpan> span;
  for (const BusFindings& b : buses) {
    if (b.report.bytes.bytes_in == 0) continue;
    if (!span) span = TimeSpan{b.report.first_time, b.report.last_time};
    span->first = std::min(span->first, b.report.first_time);
    span->last = std::max(span->last, b.report.last_time);
  }
  if (!settings.has_timestamps) return std::nullopt;
  return span;
}

void append_report_time(std::string& out, const AuditSettings& settings, double time) {
  if (!settings.has_timestamps) return;
  if (settings.time_base == TimeBase::WallClock) {
    append_time_of_day(out, time);
    return;
  }
  out += '+';
  append_fixed(out, time, 6);
  out += " s";
}

std::string time_span_text(const AuditReport& report) {
  const std::optional<TimeSpan> span = report.time_span();
  if (!span) return {};
  std::string out;
  char seconds[48];
  if (report.settings.time_base == TimeBase::WallClock) {
    append_utc_date_time(out, span->first);
    out += " .. ";
    append_utc_date_time(out, span->last);
    std::snprintf(seconds, sizeof seconds, " UTC (%.1f s)", span->seconds());
    return out + seconds;
  }
  append_report_time(out, report.settings, span->first);
  out += " .. ";
  append_report_time(out, report.settings, span->last);
  std::snprintf(seconds, sizeof seconds, "; %.1f s)", span->seconds());
  return out + " from the recording's start (no wall-clock time" + seconds;
}

}  // namespace pvtap::analyzer
