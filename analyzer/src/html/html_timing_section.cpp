// The bus timing section: the text report's timing lines with a chart container per judged
// bus (silence-chart-N, N counting the judged buses as the chart data lists them).
#include "html/html_sections.h"

#include <cstdio>

#include "formatting/number_text.h"
#include "html/html_chart_data.h"
#include "html/html_text.h"
#include "report/report_line.h"

namespace pvtap::analyzer {
namespace {

// A verdict with the summary's key, so that a reader (or a test) can find the number.
void verdict(std::string& o, const char* key, const char* text, std::uint64_t count) {
  o += "<li>";
  o += text;
  o += ": <span class=\"n\" data-key=\"";
  o += key;
  o += "\">";
  append_uint(o, count);
  o += "</span></li>";
}

void judged_bus(std::string& o, const BusGapReport& g, std::size_t chart) {
  char limits[64];
  std::snprintf(limits, sizeof limits, "<p>t1.5 = %.3f ms, t3.5 = %.3f ms", g.t15 * 1e3,
                g.t35 * 1e3);
  o += limits;
  if (!g.timestamp_source.empty()) {
    o += "; timed by ";
    append_html_escaped(o, g.timestamp_source);
  }
  o += "</p>\n<ul class=\"verdicts\">";
  verdict(o, "t15_violations", "RTU frames with a silence over t1.5 inside", g.inner_gap_t15.count);
  verdict(o, "t35_violations", "RTU frames starting less than t3.5 after the previous one",
          g.spacing_t35.count);
  o += "</ul>\n";
  o += report_line("<div id=\"silence-chart-%zu\" class=\"chart\"></div>\n", chart);
}

}  // namespace

void append_html_bus_timing(std::string& o, const AuditReport& r) {
  o += "<section id=\"timing\"><h2>Bus timing</h2>\n"
       "<p class=\"hint\">Where characters carry their own times (a logic analyzer): each RTU "
       "frame's largest silence inside, against t1.5, and each silence between RTU frames, "
       "against t3.5, in buckets a quarter octave of character times wide.</p>\n";
  std::size_t charts = 0;
  for (const BusFindings& bus : r.buses) {
    o += "<div class=\"bus-timing\"><h3>";
    append_html_escaped(o, bus.name.empty() ? "serial bus" : "bus " + bus.name);
    o += "</h3>\n";
    if (bus.serial) {
      std::string line;
      append_serial_line_text(*bus.serial, line);
      o += "<pre class=\"serial-line\">";
      append_html_escaped(o, line);
      o += "</pre>\n";
    }
    const BusGapReport& g = bus.report.timing.bus;
    if (has_silence_histograms(bus.report)) {
      judged_bus(o, g, charts++);
    } else {
      o += "<p>Not judged: ";
      append_html_escaped(o, g.not_measurable_reason);
      o += "</p>\n";
    }
    o += "</div>\n";
  }
  o += "</section>\n";
}

}  // namespace pvtap::analyzer
