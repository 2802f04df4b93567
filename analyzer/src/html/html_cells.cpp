#include "html/html_cells.h"

#include <cstdio>

#include "formatting/number_text.h"
#include "html/html_text.h"
#include "report/report_line.h"

namespace pvtap::analyzer::html_cells {

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

void cell(std::string& o, std::string_view text, const char* tag) {
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

std::string id_attr(bool first, const char* id) {
  return first ? std::string(" id=\"") + id + "\"" : std::string();
}

void title_attribute(std::string& o, const GlossaryTerm* term) {
  if (term == nullptr) return;
  o += " title=\"";
  append_html_escaped(o, term->meaning);
  o += '"';
}

void term_heading(std::string& o, std::string_view label, std::string_view term) {
  o += "<th";
  title_attribute(o, glossary_term(term));
  o += '>';
  append_html_escaped(o, label);
  o += "</th>";
}

std::string bus_title(const BusFindings& bus) {
  return bus.name.empty() ? "serial bus" : "bus " + bus.name;
}

}  // namespace pvtap::analyzer::html_cells
