// The HTML report's page: head with the inlined style, the sections, the chart data and the
// inlined scripts. Nothing refers to anything outside the file.
#include <string>

#include "html/html_assets.h"
#include "html/html_chart_data.h"
#include "html/html_report.h"
#include "html/html_sections.h"
#include "html/html_text.h"

namespace pvtap::analyzer {
namespace {

void append_head(std::string& o, const AuditReport& r) {
  const char* title = r.live.active() ? "pvtap sniff report" : "pvtap audit report";
  o += "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n";
  o += "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n";
  // Nothing may load from elsewhere: the page is read from disk, often with no network.
  o += "<meta http-equiv=\"Content-Security-Policy\" content=\"default-src 'none'; "
       "script-src 'unsafe-inline'; style-src 'unsafe-inline'; img-src data:\">\n";
  o += "<title>";
  o += title;
  if (!r.inputs.empty()) {
    o += ": ";
    append_html_escaped(o, r.inputs.front().path);
  }
  o += "</title>\n<style>\n";
  o += html_assets::dygraph_css;
  o += "\n";
  o += html_assets::page_css;
  o += "\n</style>\n</head>\n<body>\n<header><h1>";
  o += title;
  o += "</h1>\n";
}

void append_chart_sections(std::string& o) {
  o += "<section id=\"timeline\"><h2>Timeline</h2>\n"
       "<p class=\"hint\">One lane per station (and one per bus for noise and data loss). "
       "Drag to zoom, double-click to zoom out; every chart below follows.</p>\n"
       "<div id=\"timeline-legend\" class=\"legend\"></div>"
       "<div id=\"timeline-chart\" class=\"chart tall\"></div>"
       "<div id=\"timeline-tooltip\" class=\"tooltip\"></div></section>\n";
  o += "<section id=\"load\"><h2>Bus load</h2>"
       "<div id=\"load-chart\" class=\"chart\"></div></section>\n";
  o += "<section id=\"latency\"><h2>Latency over time</h2>"
       "<div id=\"latency-chart\" class=\"chart\"></div>"
       "<h3>Latency histogram</h3><div id=\"histogram-chart\" class=\"chart\"></div></section>\n";
  o += "<section id=\"values\"><h2>Register values</h2>"
       "<div id=\"value-charts\"></div></section>\n";
}

void append_scripts(std::string& o, const AuditReport& r, const Timeline& t,
                    const HtmlOptions& options) {
  std::string json;
  append_chart_data_json(json, r, t, options);
  o += "<script type=\"application/json\" id=\"pvtap-data\">";
  append_script_safe_json(o, json);
  o += "</script>\n<script>\n";
  o += html_assets::dygraph_js;
  o += "\n</script>\n<script>\n";
  o += html_assets::dygraph_sync_js;
  o += "\n</script>\n<script>\n";
  o += html_assets::page_js;
  o += "\n</script>\n";
}

}  // namespace

void write_html_report(const AuditReport& report, const Timeline& timeline,
                       const HtmlOptions& options, OutputStream& out) {
  std::string& o = out.buffer();
  append_head(o, report);
  append_html_overview(o, report);
  o += "</header>\n<main>\n";
  append_html_stations(o, report);
  append_chart_sections(o);
  append_html_polling(o, report, timeline);
  append_html_bus_timing(o, report);
  append_html_findings(o, report);
  append_html_latest_values(o, report);
  append_html_inferred(o, report);
  o += "</main>\n";
  append_scripts(o, report, timeline, options);
  o += "</body>\n</html>\n";
  out.done();
}

}  // namespace pvtap::analyzer
