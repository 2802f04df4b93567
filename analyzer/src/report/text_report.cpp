// The text report: what a field engineer reads after an audit.
#include <optional>
#include <string>

#include "formatting/number_text.h"
#include "pvtap/carriers/solarman_v5_pairing.h"
#include "report/report_line.h"
#include "report/report_writers.h"
#include "report/text_bus_sections.h"
#include "report/text_wording.h"

namespace pvtap::analyzer {
namespace {

using namespace text_wording;

void inputs(const AuditReport& r, std::string& o) {
  for (const InputReport& in : r.inputs) {
    if (in.unreadable) {
      o += report_line("input: %s NOT READ: %s", in.path.c_str(), in.error.c_str());
      continue;
    }
    const std::string pair = in.pair.empty() ? "" : ", the " + in.pair + "' pair";
    o += report_line("input: %s (%s, %llu records%s)%s", in.path.c_str(), in.link_type.c_str(),
                     u(in.records), pair.c_str(), in.truncated ? " DAMAGED" : "");
    if (in.truncated) {
      o += report_line("  reading stopped at byte %llu of %llu: %s", u(in.read_bytes),
                       u(in.file_bytes), in.error.c_str());
    }
    if (in.steps_back > 0) {
      o += report_line(
          "  its clock stepped back %llu times (first at record %llu; the largest step %.6f "
          "s): the records after each step are moved on to follow it",
          u(in.steps_back), u(in.first_step_back_record), in.largest_step_back);
    }
  }
}

void span_of_time(const AuditReport& r, std::string& o) {
  const std::string span = time_span_text(r);
  if (!span.empty()) o += report_line("time: %s", span.c_str());
}

// The logger sticks' V5 frames: what they carried and their findings.
void solarman_v5_lines(const NetworkStats& n, std::string& o) {
  const solarman_v5::Totals& v = n.v5;
  o += report_line(
      "Solarman V5 logger sticks: %llu flows, %llu V5 frames (%llu with an RTU frame; %llu of "
      "the sticks' own: %llu heartbeats, %llu data reports; %llu answers to them); latency "
      "measured at the LAN side",
      u(n.v5_flows), u(v.frames), u(v.rtu_frames), u(v.stick_frames), u(v.heartbeats),
      u(v.data_reports), u(v.stick_answers));
  o += report_line(
      "  V5 bytes: %llu carrier, %llu in RTU frames, %llu quirk bytes (two zeros after the RTU "
      "CRC) in %llu replies, %llu bytes of no V5 frame",
      u(v.carrier_bytes), u(v.rtu_bytes), u(v.quirk_bytes), u(v.quirk_frames), u(v.noise_bytes));
  o += report_line(
      "  V5 findings: %llu bad checksums, %llu truncated frames, %llu lengths that do not hold "
      "(%llu bytes in broken frames)",
      u(v.checksum_failures), u(v.truncated), u(v.length_mismatches), u(v.broken_bytes));
  o += report_line(
      "  V5 pairing by sequence byte: %llu replies after the client's next request, %llu "
      "replies to no request waiting; %llu stick codes in place of an RTU frame: %llu code 05 "
      "(no reply on the bus: counted with the timeouts), %llu code 06 refusing a request to "
      "another logger serial, %llu other",
      u(v.replies_after_next_request), u(v.unpaired_replies), u(v.stick_codes), u(v.stick_timeouts),
      u(v.refused_requests), u(v.other_codes));
  for (const std::string& e : n.v5_finding_examples) o += report_line("  %s", e.c_str());
}

void network(const AuditReport& r, std::string& o) {
  if (!r.network) return;
  const NetworkStats& n = r.flows;
  o += report_line(
      "gateway flows: %llu analyzed, %llu ignored (%llu bytes of other traffic); "
      "%llu bytes retransmitted, %llu segments out of order",
      u(n.flows_analyzed), u(n.flows_ignored), u(n.ignored_bytes), u(n.retransmitted_bytes),
      u(n.out_of_order_segments));
  if (n.mbap_flows > 0) {
    o += report_line(
        "Modbus/TCP: %llu flows, %llu ADUs, %llu carrier bytes (MBAP headers); %llu headers "
        "that lied (%llu bytes skipped)",
        u(n.mbap_flows), u(n.mbap_adus), u(n.mbap_carrier_bytes), u(n.mbap_findings),
        u(n.mbap_skipped_bytes));
    examples_shown(n.mbap_finding_examples.size(), n.mbap_findings, o);
    for (const std::string& e : n.mbap_finding_examples) o += report_line("  %s", e.c_str());
  }
  if (n.v5_flows > 0) solarman_v5_lines(n, o);
  const SkippedRecords& s = r.skipped;
  if (s.not_ip + s.other_ip + s.fragments + s.malformed > 0) {
    o += report_line(
        "packets skipped: %llu not IP, %llu neither TCP nor UDP, %llu IP fragments, "
        "%llu malformed",
        u(s.not_ip), u(s.other_ip), u(s.fragments), u(s.malformed));
  }
}

// The buses whose clock is over 2 % off a standard rate; nullopt when no bus's rate was
// measured.
std::optional<std::uint64_t> clock_deviations(const AuditReport& r) {
  std::optional<std::uint64_t> n;
  for (const BusFindings& bus : r.buses) {
    if (bus.serial && bus.serial->measured) n = n.value_or(0) + bus.serial->clock_deviations;
  }
  return n;
}

void totals(const AuditReport& r, std::string& o) {
  const BusReport t = r.totals();
  o += report_line(
      "bus bytes: %llu (%llu in frames, %llu noise in %llu runs; %llu lost in %llu gaps)",
      u(t.bytes.bytes_in), u(t.bytes.frame_bytes), u(t.bytes.noise_bytes), u(t.bytes.noise_runs),
      u(t.gaps.lost_bytes), u(t.gaps.gaps));
  o += report_line("frames: %llu (%llu requests, %llu responses, %llu bad checks, %llu malformed)",
                   u(t.bytes.frames), u(t.requests), u(t.responses), u(t.bytes.bad_frames),
                   u(t.malformed_frames));
  if (const std::string hint = no_frame_hint(r); !hint.empty()) {
    o += report_line("  %s", hint.c_str());
  }
  // Clock deviations only where a line's rate was measured (a logic recording), so that other
  // reports keep their shape.
  std::string clocks;
  if (const std::optional<std::uint64_t> n = clock_deviations(r)) {
    clocks = ", " + std::to_string(*n) + " clock deviations over 2 %";
  }
  o += report_line("findings: %llu bad checks, %llu timeouts, %llu exceptions and error replies%s",
                   u(t.bytes.bad_frames), u(t.timeouts), u(t.exceptions), clocks.c_str());
  o += report_line(
      "  of the bad checks: %llu damaged replies (the slave answered; the line damaged the "
      "answer), %llu damaged requests left unanswered (the slave rightly ignored them)",
      u(t.damaged_replies), u(t.unanswered_damaged_requests));
  o += report_line("  %-8s %10s %10s", "dialect", "requests", "responses");
  for (std::size_t d = 0; d < t.by_dialect.size(); ++d) {
    const RoleCounts& c = t.by_dialect[d];
    if (c.requests + c.responses == 0) continue;
    o +=
        report_line("  %-8s %10llu %10llu", std::string(to_string(static_cast<Dialect>(d))).c_str(),
                    u(c.requests), u(c.responses));
  }
}

}  // namespace

std::string claimed_addresses(const UnknownStation& unknown) {
  std::string text;
  for (const ClaimedStation& c : unknown.claimed) {
    if (!text.empty()) text += ", ";
    append_uint(text, c.station);
  }
  return text.empty() ? "none" : text;
}

std::string station_key(const AuditReport& report, const BusFindings& bus, std::uint8_t station) {
  std::string key = report.buses.size() > 1 && !bus.name.empty() ? bus.name + "/" : "";
  append_uint(key, station);
  return key;
}

void write_text_report(const AuditReport& report, OutputStream& out) {
  std::string& o = out.buffer();
  o += report.live.active() ? "\n== pvtap sniff report ==\n" : "\n== pvtap audit report ==\n";
  inputs(report, o);
  append_live_sources_text(report.live, o);
  span_of_time(report, o);
  network(report, o);
  if (report.written_records > 0) {
    o += report_line("written: %llu frames as link type 252", u(report.written_records));
  }
  totals(report, o);
  for (const BusFindings& bus : report.buses) {
    o += '\n';
    if (report.buses.size() > 1 || !bus.name.empty()) {
      o += report_line("-- bus %s --", bus.name.empty() ? "serial" : bus.name.c_str());
    }
    if (bus.serial) append_serial_line_text(*bus.serial, o);
    append_bus_sections_text(report, bus, o);
  }
  out.done();
}

}  // namespace pvtap::analyzer
