// The HTML report's tables: overview tiles, stations, latest values and inferred blocks
// (polling and findings in html_polling_section.cpp and html_findings_section.cpp).
#include "html/html_sections.h"

#include "formatting/number_text.h"
#include "html/html_cells.h"
#include "html/html_text.h"
#include "pvtap/registers/register_format.h"
#include "report/frame_findings.h"
#include "report/glossary.h"
#include "report/report_writers.h"

namespace pvtap::analyzer {
namespace {

using namespace html_cells;

// Tile: one health counter of the overview, linking to where it is explained.
struct Tile {
  const char* key;  // the summary field it shows
  const char* label;
  std::uint64_t value;
  const char* section;
};

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

}  // namespace

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

}  // namespace pvtap::analyzer
