// The text report's sections of one bus (text_bus_sections.h).
#include "report/text_bus_sections.h"

#include <cstdio>
#include <string>

#include "formatting/number_text.h"
#include "pvtap/carriers/solarman_v5_pairing.h"
#include "pvtap/codec/function_codes.h"
#include "pvtap/registers/register_format.h"
#include "pvtap/statistics/timing_statistics.h"
#include "report/frame_findings.h"
#include "report/poll_block_text.h"
#include "report/report_line.h"
#include "report/report_writers.h"
#include "report/text_wording.h"

namespace pvtap::analyzer {
namespace {

using namespace text_wording;

// "unknown station: 3 damaged frames (claimed 33, 81, 88), 12 noise bytes": what no station
// can be named for (a damaged frame's station byte may be the damage).
void unknown_station_line(const BusReport& b, std::string& o) {
  const UnknownStation& unknown = b.unknown_station;
  if (unknown.damaged_frames == 0 && b.bytes.noise_bytes == 0) return;
  const std::string claimed = claimed_addresses(unknown);
  o += report_line("  unknown station: %llu damaged frames (claimed %s), %llu noise bytes",
                   u(unknown.damaged_frames), claimed.c_str(), u(b.bytes.noise_bytes));
}

// What stations said of themselves and findings about a station as a whole, below the table
// (a table of inverters alone stays as it always was).
void station_notes(const BusReport& b, std::string& o) {
  for (const StationSummary& s : b.stations) {
    if (!s.device.empty()) {
      o += report_line("  station %u is %s", s.station, s.device.text().c_str());
    }
    if (s.dialect_changes > 0) {
      o += report_line("  station %u changed dialect %llu time(s): see the frames marked so",
                       s.station, u(s.dialect_changes));
    }
  }
}

// Each station two devices answer for is a finding, with both answering patterns.
void address_conflicts(const BusReport& b, std::string& o) {
  o += report_line("address conflicts: %llu (second replies to one request with other contents)",
                   u(b.address_conflicts));
  for (const StationSummary& s : b.stations) {
    if (s.address_conflicts == 0) continue;
    o += report_line(
        "FINDING: two devices answer to station %u: %llu of its requests got a second reply "
        "with other contents; %s",
        s.station, u(s.address_conflicts), answering_patterns(s).c_str());
  }
}

void station_table(const AuditReport& r, const BusReport& b, std::string& o) {
  // Noise alone (a file of other bytes) makes no table: the findings count it.
  if (b.stations.empty() && b.unknown_station.damaged_frames == 0) return;
  o += report_line("stations:");
  o += report_line("  %-8s %9s %9s %5s %8s %10s %11s %10s  %s", "station", "requests", "responses",
                   "bad", "timeouts", "exceptions", "unsolicited", "duplicates",
                   "latency ms p50 / p95 / max");
  for (const StationSummary& s : b.stations) {
    std::string latency = "-";
    if (s.latency.count > 0) {
      char buf[96];
      std::snprintf(buf, sizeof buf, "%.1f / %.1f / %.1f", ms(s.latency.p50), ms(s.latency.p95),
                    ms(s.latency.max));
      latency = buf;
    }
    o += report_line("  %-8u %9llu %9llu %5llu %8llu %10llu %11llu %10llu  %s", s.station,
                     u(s.requests), u(s.responses), u(s.bad_checks), u(s.timeouts), u(s.exceptions),
                     u(s.unsolicited), u(s.duplicates), latency.c_str());
  }
  station_notes(b, o);
  unknown_station_line(b, o);
  (void)r;
}

void frame_example(const AuditReport& r, const FrameExample& e, std::string& o) {
  std::string raw;
  append_spaced_hex(raw, e.bytes);
  std::string expected;
  append_spaced_hex(expected, check_wire_bytes(e.dialect, e.check.expected));
  o += report_line("  %s  st %u  %s %s  %s: check should be %s; raw %s", when(r, e.time).c_str(),
                   e.station, std::string(to_string(e.dialect)).c_str(),
                   std::string(to_string(e.role)).c_str(),
                   function_text(e.dialect, e.function).c_str(), expected.c_str(), raw.c_str());
}

// A gateway's 0x0B replies, or a logger stick's code 05 (on a `v5:` bus), which the timeouts
// count: the device behind it did not answer.
std::string gateway_text(const BusFindings& bus) {
  const std::string n = std::to_string(bus.report.gateway_timeouts);
  if (bus.name.starts_with("v5:")) {
    return ", " + n +
           " answered by the stick's code 05 (the device behind the stick did not answer: a "
           "timeout on its serial bus)";
  }
  return ", " + n +
         " answered by the gateway's exception 0x0B (the device behind the gateway did not "
         "answer: a timeout on its serial bus)";
}

void findings(const AuditReport& r, const BusFindings& bus, std::string& o) {
  const BusReport& b = bus.report;
  o += report_line("bad checks: %llu", u(b.bytes.bad_frames));
  examples_shown(b.bad_check_examples.size(), b.bytes.bad_frames, o);
  for (const FrameExample& e : b.bad_check_examples) frame_example(r, e, o);
  o += report_line("timeouts: %s%s", timeouts_explained(b).c_str(),
                   b.gateway_timeouts > 0 ? gateway_text(bus).c_str() : "");
  examples_shown(b.timeout_examples.size(), b.timeouts, o);
  for (const TimeoutExample& e : b.timeout_examples) {
    const bool coded = e.timeout.reason == TimeoutReason::CarrierNoReply;
    o +=
        report_line("  %s  st %u  %s  %s%s%s", when(r, e.request_time).c_str(), e.timeout.station,
                    std::string(to_string(e.timeout.dialect)).c_str(),
                    function_text(e.timeout.dialect, e.timeout.function).c_str(), coded ? ": " : "",
                    coded ? solarman_v5::no_reply_reason(e.timeout.carrier_code).c_str() : "");
  }
  o += report_line("damaged replies: %llu (they answered their request: not timeouts)",
                   u(b.damaged_replies));
  o += report_line("damaged requests left unanswered: %llu (the slave rightly ignored them)",
                   u(b.unanswered_damaged_requests));
  if (b.unanswered_at_end + b.unanswered_after_loss > 0) {
    o += report_line(
        "not counted as timeouts: %llu still waiting when the input ended, %llu waiting "
        "while capture data was lost",
        u(b.unanswered_at_end), u(b.unanswered_after_loss));
  }
  o += report_line(
      "unsolicited replies: %llu (%llu late for a timed-out request); duplicate replies: "
      "%llu; byte count mismatches: %llu",
      u(b.unsolicited), u(b.late_replies), u(b.duplicates), u(b.count_mismatches));
  address_conflicts(b, o);
  // Not the bus's fault but the tap's: said only where it happens.
  if (b.echoes > 0) {
    o += report_line(
        "echoes: %llu of %llu requests seen twice, back to back (the tap's adapter repeating "
        "what its master sent; each counted once, as one request)",
        u(b.echoes), u(b.requests));
  }
  if (b.collisions > 0) {
    o += report_line(
        "FINDING: %llu collisions on a bus of more than one master (two transmissions at once: "
        "bytes of no frame, or two requests overlapping); %llu requests lost in a collision, "
        "counted among the %llu timeouts",
        u(b.collisions), u(b.lost_in_collision), u(b.timeouts));
  }
  if (b.quantity_problems > 0) {
    o += report_line("requests asking a quantity out of the specification's range: %llu",
                     u(b.quantity_problems));
  }
  if (b.write_count_problems > 0) {
    o += report_line("writes whose byte count disagrees with their quantity: %llu",
                     u(b.write_count_problems));
  }
  if (b.forbidden_broadcasts > 0) {
    o += report_line(
        "requests broadcast to address 0 that only writes may use (no station answers them): "
        "%llu",
        u(b.forbidden_broadcasts));
  }
  o += report_line("exceptions and error replies: %llu", u(b.exceptions));
  for (const ExceptionTally& e : b.exception_codes) {
    if (const std::string_view whole = error_reply_name(e.dialect); !whole.empty()) {
      o += report_line("  %s: %llu", std::string(whole).c_str(), u(e.count));
    } else {
      o += report_line("  %s exception 0x%02X (%s): %llu",
                       std::string(to_string(e.dialect)).c_str(), e.code,
                       std::string(fc::exception_name(e.dialect, e.code)).c_str(), u(e.count));
    }
  }
  o += report_line("noise: %llu bytes in %llu runs", u(b.bytes.noise_bytes), u(b.bytes.noise_runs));
  o += report_line("data-loss gaps: %llu (%llu bytes lost%s)", u(b.gaps.gaps), u(b.gaps.lost_bytes),
                   b.gaps.gaps_of_unknown_size > 0 ? ", some gaps of unknown size" : "");
}

void latency(const AuditReport& r, const BusReport& b, std::string& o) {
  if (!r.settings.has_timestamps) {
    o += report_line("latency: not measured (the input has no timestamps)");
    return;
  }
  o += report_line("latency, request end to reply start (ms):");
  o += report_line("  %-12s %s", "all", distribution_text(b.timing.latency).c_str());
  for (const StationLatency& s : b.timing.latency_by_station) {
    o += report_line("  station %-4u %s", s.station, distribution_text(s.latency).c_str());
  }
}

void polling(const AuditReport& r, const BusReport& b, std::string& o) {
  if (!r.settings.has_timestamps || b.timing.poll_periods.empty()) return;
  o += report_line("poll period and jitter per poll block (station, function, registers):");
  for (const PollPeriod& p : b.timing.poll_periods) {
    const PollBlock& k = p.block;
    const std::string dialect(to_string(k.dialect));
    const std::string function = function_text(k.dialect, k.function);
    const std::string registers = block_text(r.settings, k);
    if (p.period.intervals == 0) {
      o += report_line("  %-7s st %-4u %-40s %s polled once", dialect.c_str(), k.station,
                       function.c_str(), registers.c_str());
      continue;
    }
    o += report_line(
        "  %-7s st %-4u %-40s %s %llu intervals  period %.1f ms  jitter %.1f ms  "
        "max deviation %.1f ms",
        dialect.c_str(), k.station, function.c_str(), registers.c_str(), u(p.period.intervals),
        ms(p.period.mean), ms(p.period.stddev), ms(p.period.max_deviation));
  }
  if (b.timing.untracked_poll_requests > 0) {
    o += report_line("  %llu requests of further blocks not tracked (more than %zu blocks)",
                     u(b.timing.untracked_poll_requests), TimingStatistics::kMaxPollBlocks);
  }
}

// The masters told apart by their poll cycles, each with its plan; two or more are a finding
// with its evidence.
void masters(const AuditReport& r, const BusReport& b, std::string& o) {
  const std::vector<MasterPlan>& list = b.timing.masters;
  if (list.empty()) return;
  if (list.size() > 1) {
    std::string cycles;
    for (const MasterPlan& m : list) {
      char buf[48];
      std::snprintf(buf, sizeof buf, "%s%.1f ms", cycles.empty() ? "" : ", ", ms(m.period));
      cycles += buf;
    }
    o += report_line(
        "FINDING: %zu masters on one bus: %zu independent poll cycles (%s); %llu "
        "requests sent while another request's reply was due",
        list.size(), list.size(), cycles.c_str(), u(b.timing.requests_while_reply_due));
  } else if (b.timing.requests_while_reply_due >= kSecondMasterRequests) {
    o += report_line(
        "FINDING: more than one master on this bus: %llu requests sent while another "
        "request's reply was due (the bus is too busy for their poll cycles to show)",
        u(b.timing.requests_while_reply_due));
  }
  o += report_line("masters: %zu (told apart by their poll cycles)", list.size());
  for (std::size_t i = 0; i < list.size(); ++i) {
    const MasterPlan& m = list[i];
    std::string cycle = "no cycle measured", turnaround = "none measured";
    char buf[64];
    if (m.period > 0) {
      std::snprintf(buf, sizeof buf, "cycle %.1f ms", ms(m.period));
      cycle = buf;
    }
    if (m.turnaround) {
      std::snprintf(buf, sizeof buf, "%.1f ms", ms(*m.turnaround));
      turnaround = buf;
    }
    o += report_line("  master %zu: %s, %llu requests (%.1f %% of the bus's), turnaround %s", i + 1,
                     cycle.c_str(), u(m.requests), m.share * 100.0, turnaround.c_str());
    for (const std::size_t k : m.polls) {
      const PollBlock& block = b.timing.poll_periods[k].block;
      o += report_line("    %-7s st %-4u %-40s %s", std::string(to_string(block.dialect)).c_str(),
                       block.station, function_text(block.dialect, block.function).c_str(),
                       block_text(r.settings, block).c_str());
    }
  }
}

void bus_timing(const AuditReport& r, const BusReport& b, std::string& o) {
  const BusGapReport& g = b.timing.bus;
  o += report_line("bus timing at %u baud (t1.5 = %.3f ms, t3.5 = %.3f ms):", r.settings.baud,
                   ms(g.t15), ms(g.t35));
  if (!g.measurable) {
    o += report_line("  not judged: %s", g.not_measurable_reason.c_str());
    return;
  }
  if (!g.timestamp_source.empty()) o += report_line("  timed by: %s", g.timestamp_source.c_str());
  o += report_line("  silence between frames (ms): %s", distribution_text(g.gaps).c_str());
  o += report_line("  RTU frames with a silence over t1.5 inside: %llu", u(g.inner_gap_t15.count));
  o += report_line("  RTU frames starting less than t3.5 after the previous one: %llu",
                   u(g.spacing_t35.count));
}

void latest_values(const AuditReport& r, const BusReport& b, std::string& o) {
  bool any = false;
  for (const StationSummary& s : b.stations) any = any || !s.latest_values.empty();
  if (!any) return;
  o += report_line("latest values (what each station last reported):");
  for (const StationSummary& s : b.stations) {
    if (s.latest_values.empty()) continue;
    if (r.settings.has_timestamps) {
      o += report_line("  station %u (as of %s)", s.station, when(r, s.last_report_time).c_str());
    } else {
      o += report_line("  station %u", s.station);
    }
    for (const LatestValue& v : s.latest_values) {
      o += report_line("    %-7s %-8s %-40s %s", std::string(to_string(v.dialect)).c_str(),
                       std::string(format_value_address(v.value, v.dialect).view()).c_str(),
                       latest_value_name(v).c_str(), latest_value_text(v).c_str());
    }
  }
}

// One section per station with blocks no map names: each block's values as inferred, with
// their evidence and hints.
void inferred_blocks(const AuditReport& r, const BusFindings& bus, std::string& o) {
  bool any = false;
  for (const StationSummary& s : bus.report.stations) any = any || !s.inferred.empty();
  if (!any) return;
  o += report_line("unmapped registers, their types inferred from every reply:");
  for (const StationSummary& s : bus.report.stations) {
    if (s.inferred.empty()) continue;
    o += report_line("  station %s", station_key(r, bus, s.station).c_str());
    for (const InferredBlock& b : s.inferred) {
      o += report_line(
          "    %s at %s, %u words (%s), %u replies:", std::string(table_name(b.table)).c_str(),
          std::string(format_register_address(b.dialect, b.start).view()).c_str(),
          unsigned{b.count}, function_text(b.dialect, b.function).c_str(), b.replies);
      for (const InferredValue& v : b.values) {
        o += report_line("      %-8s %-28s %-26s %3.0f%%  %s", inferred_address(b, v).c_str(),
                         inferred_type(v).c_str(), inferred_reading(v).c_str(),
                         v.confidence * 100.0, v.evidence.c_str());
        if (!v.hint.empty()) o += report_line("      %-8s hint: %s", "", v.hint.c_str());
      }
    }
  }
}

}  // namespace

void append_bus_sections_text(const AuditReport& report, const BusFindings& bus, std::string& o) {
  station_table(report, bus.report, o);
  findings(report, bus, o);
  latency(report, bus.report, o);
  polling(report, bus.report, o);
  masters(report, bus.report, o);
  bus_timing(report, bus.report, o);
  latest_values(report, bus.report, o);
  inferred_blocks(report, bus, o);
}

}  // namespace pvtap::analyzer
