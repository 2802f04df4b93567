// The HTML report's findings: per bus, bad checks, timeouts, conflicts, exceptions, noise, gaps.
#include "html/html_sections.h"

#include "formatting/number_text.h"
#include "html/html_cells.h"
#include "html/html_text.h"
#include "pvtap/codec/function_codes.h"
#include "report/frame_findings.h"
#include "report/report_line.h"
#include "report/report_writers.h"

namespace pvtap::analyzer {
namespace {

using namespace html_cells;

void frame_example(std::string& o, const AuditReport& r, const FrameExample& e) {
  std::string raw, expected, function;
  append_spaced_hex(raw, e.bytes);
  append_spaced_hex(expected, check_wire_bytes(e.dialect, e.check.expected));
  append_function(function, e.dialect, e.function);
  o += "<tr>";
  cell(o, time_text(r, e.time));
  cell(o, std::to_string(e.station));
  cell(o, std::string(to_string(e.dialect)) + " " + std::string(to_string(e.role)));
  cell(o, function);
  cell(o, expected);
  o += "<td class=\"hex\">";
  append_html_escaped(o, raw);
  o += "</td></tr>\n";
}

void examples_table(std::string& o, const AuditReport& r, const std::vector<FrameExample>& list,
                    const char* check_header) {
  if (list.empty()) return;
  o += "<table><tr><th>time</th><th>station</th><th>frame</th><th>function</th><th>";
  o += check_header;
  o += "</th><th>raw</th></tr>\n";
  for (const FrameExample& e : list) frame_example(o, r, e);
  o += "</table>\n";
}

void timeouts_list(std::string& o, const AuditReport& r, const BusReport& b, bool first) {
  o += report_line("<h4%s>Timeouts: %llu</h4><p>", id_attr(first, "findings-timeouts").c_str(),
                   static_cast<unsigned long long>(b.timeouts));
  append_html_escaped(o, timeouts_explained(b));
  o += "</p>\n";
  if (b.timeout_examples.empty()) return;
  o += "<table><tr><th>request time</th><th>station</th><th>dialect</th><th>function</th></tr>\n";
  for (const TimeoutExample& e : b.timeout_examples) {
    std::string function;
    append_function(function, e.timeout.dialect, e.timeout.function);
    o += "<tr>";
    cell(o, time_text(r, e.request_time));
    cell(o, std::to_string(e.timeout.station));
    cell(o, to_string(e.timeout.dialect));
    cell(o, function);
    o += "</tr>\n";
  }
  o += "</table>\n";
}

// Only where there are some: each station two devices answer for is a finding.
void address_conflicts(std::string& o, const BusReport& b, bool first) {
  if (b.address_conflicts == 0) return;
  o += report_line("<h4%s>Address conflicts: %llu</h4>\n",
                   id_attr(first, "findings-conflicts").c_str(),
                   static_cast<unsigned long long>(b.address_conflicts));
  for (const StationSummary& s : b.stations) {
    if (s.address_conflicts == 0) continue;
    o += report_line(
        "<p class=\"finding\">Two devices answer to station %u: %llu of its requests got a "
        "second reply with other contents; ",
        s.station, static_cast<unsigned long long>(s.address_conflicts));
    append_html_escaped(o, answering_patterns(s));
    o += ".</p>\n";
  }
}

void exception_list(std::string& o, const BusReport& b, bool first) {
  o += report_line("<h4%s>Exceptions and error replies: %llu</h4>\n",
                   id_attr(first, "findings-exceptions").c_str(),
                   static_cast<unsigned long long>(b.exceptions));
  if (b.exception_codes.empty()) return;
  o += "<ul>";
  for (const ExceptionTally& e : b.exception_codes) {
    std::string line;
    if (const std::string_view whole = error_reply_name(e.dialect); !whole.empty()) {
      line = whole;
    } else {
      line = std::string(to_string(e.dialect)) + " exception ";
      append_hex_byte(line, e.code);
      line += " (" + std::string(fc::exception_name(e.dialect, e.code)) + ")";
    }
    line += ": " + std::to_string(e.count);
    cell(o, line, "li");
  }
  o += "</ul>\n";
}

void bus_findings(std::string& o, const AuditReport& r, const BusFindings& bus, bool first) {
  const BusReport& b = bus.report;
  const auto u = [](std::uint64_t v) { return static_cast<unsigned long long>(v); };
  o += "<h3>";
  append_html_escaped(o, bus_title(bus));
  o += "</h3>\n";
  o += report_line(
      "<h4%s>Bad checks: %llu</h4><p>%llu damaged replies (the slave "
      "answered; the line damaged the answer), %llu damaged requests left unanswered (the slave "
      "rightly ignored them)</p>\n",
      id_attr(first, "findings-bad").c_str(), u(b.bytes.bad_frames), u(b.damaged_replies),
      u(b.unanswered_damaged_requests));
  examples_table(o, r, b.bad_check_examples, "check should be");
  timeouts_list(o, r, b, first);
  o += report_line(
      "<h4%s>Unsolicited replies: %llu</h4><p>%llu late for a timed-out "
      "request; duplicate replies: %llu; byte count mismatches: %llu</p>\n",
      id_attr(first, "findings-replies").c_str(), u(b.unsolicited), u(b.late_replies),
      u(b.duplicates), u(b.count_mismatches));
  examples_table(o, r, b.unsolicited_examples, "check");
  address_conflicts(o, b, first);
  if (b.echoes > 0) {
    o += report_line(
        "<p>Echoes: %llu of %llu requests were seen twice, back to back: the tap's adapter "
        "repeating what its master sent. Each is counted once, as one request.</p>\n",
        u(b.echoes), u(b.requests));
  }
  if (b.collisions > 0) {
    o += report_line(
        "<p class=\"finding\">Collisions: %llu on a bus of more than one master (two "
        "transmissions at once: bytes of no frame, or two requests overlapping); %llu requests "
        "were lost in a collision, counted among the %llu timeouts.</p>\n",
        u(b.collisions), u(b.lost_in_collision), u(b.timeouts));
  }
  exception_list(o, b, first);
  o += report_line("<h4%s>Noise: %llu bytes in %llu runs</h4>\n",
                   id_attr(first, "findings-noise").c_str(), u(b.bytes.noise_bytes),
                   u(b.bytes.noise_runs));
  o += report_line("<h4%s>Data-loss gaps: %llu</h4><p>%llu bytes lost%s</p>\n",
                   id_attr(first, "findings-gaps").c_str(), u(b.gaps.gaps), u(b.gaps.lost_bytes),
                   b.gaps.gaps_of_unknown_size > 0 ? ", some gaps of unknown size" : "");
}

}  // namespace

void append_html_findings(std::string& o, const AuditReport& r) {
  o += "<section id=\"findings\"><h2>Findings</h2>\n";
  for (std::size_t i = 0; i < r.buses.size(); ++i) bus_findings(o, r, r.buses[i], i == 0);
  o += "</section>\n";
}

}  // namespace pvtap::analyzer
