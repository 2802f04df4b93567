// The HTML report's tables: overview tiles, stations, polling and findings.
#include "html/html_sections.h"

#include <algorithm>
#include <cstdio>

#include "formatting/csv_text.h"
#include "formatting/json_text.h"
#include "formatting/number_text.h"
#include "html/html_text.h"
#include "pvtap/codec/function_codes.h"
#include "pvtap/registers/register_format.h"
#include "report/frame_findings.h"
#include "report/glossary.h"
#include "report/poll_block_text.h"
#include "report/report_line.h"
#include "report/report_writers.h"

namespace pvtap::analyzer {
namespace {

std::string ms_text(double seconds) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.1f", seconds * 1e3);
  return buf;
}

std::string time_text(const AuditReport& r, double time) {
  std::string out;
  append_report_time(out, r.settings, time);
  return out;
}

void cell(std::string& o, std::string_view text, const char* tag = "td") {
  o += '<';
  o += tag;
  o += '>';
  append_html_escaped(o, text);
  o += "</";
  o += tag;
  o += '>';
}

void count_cell(std::string& o, std::uint64_t n) {
  o += "<td class=\"n\">";
  append_uint(o, n);
  o += "</td>";
}

// The tiles link to the first bus's findings: ids are given once.
std::string id_attr(bool first, const char* id) {
  return first ? std::string(" id=\"") + id + "\"" : std::string();
}

// Tile: one health counter of the overview, linking to where it is explained.
struct Tile {
  const char* key;  // the summary field it shows
  const char* label;
  std::uint64_t value;
  const char* section;
};

// A title (the browser's tooltip) with the glossary's meaning of what a heading or tile names.
void title_attribute(std::string& o, const GlossaryTerm* term) {
  if (term == nullptr) return;
  o += " title=\"";
  append_html_escaped(o, term->meaning);
  o += '"';
}

// A table heading that names a glossary term: its meaning is the heading's tooltip.
void term_heading(std::string& o, std::string_view label, std::string_view term) {
  o += "<th";
  title_attribute(o, glossary_term(term));
  o += '>';
  append_html_escaped(o, label);
  o += "</th>";
}

void tile(std::string& o, const Tile& t) {
  o += "<a class=\"tile";
  if (t.value > 0 && std::string_view(t.key) != "frames") o += " finding";
  o += '"';
  title_attribute(o, glossary_term_of_key(t.key));
  o += " href=\"#";
  o += t.section;
  o += "\" data-key=\"";
  o += t.key;
  o += "\"><span class=\"value\">";
  append_uint(o, t.value);
  o += "</span><span class=\"label\">";
  o += t.label;
  o += "</span></a>";
}

std::string bus_title(const BusFindings& bus) {
  return bus.name.empty() ? "serial bus" : "bus " + bus.name;
}

void station_row(std::string& o, const AuditReport& r, const BusFindings& bus,
                 const StationSummary& s) {
  o += "<tr>";
  std::string station = station_key(r, bus, s.station);
  if (!s.device.empty()) station += " (" + s.device.text() + ")";
  cell(o, station);
  count_cell(o, s.requests);
  count_cell(o, s.responses);
  count_cell(o, s.bad_checks);
  count_cell(o, s.timeouts);
  count_cell(o, s.exceptions);
  for (const double v : {s.latency.p50, s.latency.p95, s.latency.max}) {
    o += "<td class=\"n\">";
    o += s.latency.count > 0 ? ms_text(v) : "-";
    o += "</td>";
  }
  o += "</tr>\n";
}

// The last row: the damaged frames no station can be named for (a damaged frame's station
// byte may be the damage), with the addresses they claimed, and the noise.
void unknown_station_row(std::string& o, const BusReport& b) {
  const UnknownStation& unknown = b.unknown_station;
  if (unknown.damaged_frames == 0 && b.bytes.noise_bytes == 0) return;
  std::string label = "unknown (claimed " + claimed_addresses(unknown) + "; ";
  append_uint(label, b.bytes.noise_bytes);
  label += " noise bytes)";
  o += "<tr class=\"unknown-station\">";
  cell(o, label);
  o += "<td class=\"n\">-</td><td class=\"n\">-</td>";
  count_cell(o, unknown.damaged_frames);
  o += "<td class=\"n\">-</td><td class=\"n\">-</td><td class=\"n\">-</td>"
       "<td class=\"n\">-</td><td class=\"n\">-</td></tr>\n";
}

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
    if (e.dialect == Dialect::Hybrid) {
      line = "hybrid error reply (0xFF)";
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

double longest_poll_period(const BusReport& bus) {
  double longest = 0;
  for (const PollPeriod& p : bus.timing.poll_periods) {
    if (p.period.intervals > 0) longest = std::max(longest, p.period.mean);
  }
  return longest;
}

void poll_table(std::string& o, const AuditReport& r, const BusReport& b) {
  o += "<table><tr>";
  term_heading(o, "station", "station");
  o += "<th>dialect</th><th>function</th><th>start</th><th>count</th><th>intervals</th>";
  term_heading(o, "period ms", "poll period");
  term_heading(o, "jitter ms", "jitter");
  o += "<th>max deviation ms</th></tr>\n";
  for (const PollPeriod& p : b.timing.poll_periods) {
    std::string function;
    append_function(function, p.block.dialect, p.block.function);
    o += "<tr>";
    cell(o, std::to_string(p.block.station));
    cell(o, to_string(p.block.dialect));
    cell(o, function);
    cell(o, block_start_text(r.settings, p.block));
    cell(o, p.block.count ? std::to_string(*p.block.count) : "-");
    count_cell(o, p.period.intervals);
    for (const double v : {p.period.mean, p.period.stddev, p.period.max_deviation}) {
      o += "<td class=\"n\">";
      o += p.period.intervals > 0 ? ms_text(v) : "-";
      o += "</td>";
    }
    o += "</tr>\n";
  }
  o += "</table>\n";
}

// The masters told apart by their poll cycles; two or more are a finding.
void masters_table(std::string& o, const AuditReport& r, const BusReport& b) {
  const std::vector<MasterPlan>& list = b.timing.masters;
  if (list.empty()) return;
  o += report_line("<h4>Masters: %zu</h4>\n", list.size());
  if (list.size() > 1) {
    o += report_line(
        "<p class=\"finding\">%zu masters on one bus: %zu independent poll cycles; "
        "%llu requests sent while another request's reply was due.</p>\n",
        list.size(), list.size(),
        static_cast<unsigned long long>(b.timing.requests_while_reply_due));
  }
  o += "<table><tr>";
  term_heading(o, "master", "master");
  o += "<th>cycle ms</th><th>requests</th><th>share %</th><th>turnaround ms</th>"
       "<th>poll plan</th></tr>\n";
  for (std::size_t i = 0; i < list.size(); ++i) {
    const MasterPlan& m = list[i];
    std::string plan;
    for (const std::size_t k : m.polls) {
      const PollBlock& block = b.timing.poll_periods[k].block;
      if (!plan.empty()) plan += "; ";
      plan += "st ";
      append_uint(plan, block.station);
      plan += ' ';
      append_function(plan, block.dialect, block.function);
      plan += ' ';
      plan += block_start_text(r.settings, block);
      if (block.count) {
        plan += " x";
        append_uint(plan, *block.count);
      }
    }
    o += "<tr>";
    cell(o, std::to_string(i + 1));
    cell(o, m.period > 0 ? ms_text(m.period) : "-");
    count_cell(o, m.requests);
    char share[16];
    std::snprintf(share, sizeof share, "%.1f", m.share * 100.0);
    cell(o, share);
    cell(o, m.turnaround ? ms_text(*m.turnaround) : "-");
    cell(o, plan);
    o += "</tr>\n";
  }
  o += "</table>\n";
}

void silence_list(std::string& o, const AuditReport& r, const BusFindings& bus, const Timeline& t) {
  std::string items;
  std::size_t n = 0;
  for (const PollSilence& s : t.silences) {
    if (s.bus != bus.name || !silence_is_finding(bus.report, s)) continue;
    ++n;
    items += "<li>";
    append_html_escaped(items, time_text(r, s.from) + " .. " + time_text(r, s.to));
    items += report_line(" (%.1f s)</li>", s.to - s.from);
  }
  o += report_line("<h4>Gaps in polling: %zu</h4>\n", n);
  o += "<p class=\"hint\">Stretches with no request longer than twice the longest poll period: "
       "the logger stopped asking.</p>\n";
  if (n > 0) o += "<ul class=\"silences\">" + items + "</ul>\n";
}

}  // namespace

bool silence_is_finding(const BusReport& bus, const PollSilence& s) {
  return s.to - s.from > std::max(Timeline::kMinSilence, 2 * longest_poll_period(bus));
}

void append_html_overview(std::string& o, const AuditReport& r) {
  o += "<ul class=\"inputs\">";
  for (const InputReport& in : r.inputs) {
    std::string line = in.unreadable
                           ? in.path + " NOT READ: " + in.error
                           : in.path + " (" + in.link_type + ", " + std::to_string(in.records) +
                                 " records)" + (in.truncated ? " DAMAGED: " + in.error : "");
    if (in.steps_back > 0) {
      line += "; its clock stepped back " + std::to_string(in.steps_back) +
              " times (first at record " + std::to_string(in.first_step_back_record) + ")";
    }
    cell(o, line, "li");
  }
  o += "</ul>\n";
  if (const std::string span = time_span_text(r); !span.empty()) {
    o += "<p class=\"span\" id=\"time-span\">";
    append_html_escaped(o, span);
    o += "</p>\n";
  }
  std::string live;
  append_live_sources_text(r.live, live);
  if (!live.empty()) cell(o, live, "pre");
  const BusReport t = r.totals();
  o += "<nav class=\"tiles\">";
  const Tile tiles[] = {
      {"frames", "frames", t.bytes.frames, "stations"},
      {"bad_checks", "bad checks", t.bytes.bad_frames, "findings-bad"},
      {"timeouts", "timeouts", t.timeouts, "findings-timeouts"},
      {"unanswered_damaged_requests", "damaged requests left unanswered",
       t.unanswered_damaged_requests, "findings-bad"},
      {"exceptions", "exceptions", t.exceptions, "findings-exceptions"},
      {"noise_bytes", "noise bytes", t.bytes.noise_bytes, "findings-noise"},
      {"gaps", "data-loss gaps", t.gaps.gaps, "findings-gaps"},
  };
  for (const Tile& x : tiles) tile(o, x);
  o += "</nav>\n";
}

namespace {

// The same columns, and words, as the text report's station table.
void station_headings(std::string& o) {
  term_heading(o, "station", "station");
  term_heading(o, "requests", "request");
  term_heading(o, "responses", "response");
  term_heading(o, "bad checks", "bad check");
  term_heading(o, "timeouts", "timeout");
  term_heading(o, "exceptions", "exception");
  term_heading(o, "latency p50 ms", "p50");
  term_heading(o, "p95", "p95");
  o += "<th>max</th>";
}

}  // namespace

void append_html_stations(std::string& o, const AuditReport& r) {
  o += "<section id=\"stations\"><h2>Stations</h2>\n";
  for (const BusFindings& bus : r.buses) {
    o += "<h3>";
    append_html_escaped(o, bus_title(bus));
    o += "</h3>\n<table class=\"stations\"><tr>";
    station_headings(o);
    o += "</tr>\n";
    for (const StationSummary& s : bus.report.stations) station_row(o, r, bus, s);
    unknown_station_row(o, bus.report);
    o += "</table>\n";
  }
  o += "</section>\n";
}

void append_html_polling(std::string& o, const AuditReport& r, const Timeline& t) {
  o += "<section id=\"polling\"><h2>Polling</h2>\n";
  if (!r.settings.has_timestamps) {
    o += "<p>Not measured: the input has no timestamps.</p></section>\n";
    return;
  }
  for (const BusFindings& bus : r.buses) {
    o += "<h3>";
    append_html_escaped(o, bus_title(bus));
    o += "</h3>\n";
    poll_table(o, r, bus.report);
    masters_table(o, r, bus.report);
    silence_list(o, r, bus, t);
  }
  o += "</section>\n";
}

void append_html_latest_values(std::string& o, const AuditReport& r) {
  o += "<section id=\"latest\"><h2>Latest values</h2>\n"
       "<p class=\"hint\">What each station last reported, text registers included.</p>\n";
  for (const BusFindings& bus : r.buses) {
    for (const StationSummary& s : bus.report.stations) {
      if (s.latest_values.empty()) continue;
      o += "<details><summary>station ";
      append_html_escaped(o, station_key(r, bus, s.station));
      if (r.settings.has_timestamps) o += ", as of " + time_text(r, s.last_report_time);
      o += "</summary>\n<table class=\"latest\">";
      for (const LatestValue& v : s.latest_values) {
        o += "<tr>";
        cell(o, to_string(v.dialect));
        cell(o, format_value_address(v.value, v.dialect).view());
        cell(o, latest_value_name(v));
        cell(o, latest_value_text(v));
        o += "</tr>\n";
      }
      o += "</table></details>\n";
    }
  }
  o += "</section>\n";
}

void append_html_inferred(std::string& o, const AuditReport& r) {
  bool any = false;
  for (const BusFindings& bus : r.buses) {
    for (const StationSummary& s : bus.report.stations) any = any || !s.inferred.empty();
  }
  if (!any) return;
  o += "<section id=\"inferred\"><h2>Unmapped registers</h2>\n"
       "<p class=\"hint\">Blocks of words no register map names, their types inferred from "
       "every reply (<code>pvtap audit --draft-map DIR</code> writes them as maps).</p>\n";
  for (const BusFindings& bus : r.buses) {
    for (const StationSummary& s : bus.report.stations) {
      for (const InferredBlock& b : s.inferred) {
        o += "<details><summary>station ";
        append_html_escaped(o, station_key(r, bus, s.station));
        o += ": ";
        append_html_escaped(o, table_name(b.table));
        o += " at ";
        append_html_escaped(o, format_register_address(b.dialect, b.start).view());
        o += ", " + std::to_string(b.count) + " words, " + std::to_string(b.replies) +
             " replies</summary>\n<table class=\"inferred\"><tr>";
        for (const char* head : {"register", "type", "reading", "confidence", "evidence"}) {
          cell(o, head, "th");
        }
        o += "</tr>\n";
        for (const InferredValue& v : b.values) {
          o += "<tr>";
          cell(o, inferred_address(b, v));
          cell(o, inferred_type(v));
          cell(o, inferred_reading(v));
          cell(o, std::to_string(static_cast<int>(v.confidence * 100.0 + 0.5)) + " %");
          cell(o, v.hint.empty() ? v.evidence : v.evidence + "; " + v.hint);
          o += "</tr>\n";
        }
        o += "</table></details>\n";
      }
    }
  }
  o += "</section>\n";
}

void append_html_findings(std::string& o, const AuditReport& r) {
  o += "<section id=\"findings\"><h2>Findings</h2>\n";
  for (std::size_t i = 0; i < r.buses.size(); ++i) bus_findings(o, r, r.buses[i], i == 0);
  o += "</section>\n";
}

}  // namespace pvtap::analyzer
