// The cells, headings and small texts that the HTML report's sections share.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

#include "report/audit_report.h"
#include "report/glossary.h"

namespace pvtap::analyzer::html_cells {

// Milliseconds with one decimal ("12.5").
std::string ms_text(double seconds);
// A time as the report writes times (--utc, relative to the start ...).
std::string time_text(const AuditReport& r, double time);
// <td>text</td> (or another tag), the text escaped.
void cell(std::string& o, std::string_view text, const char* tag = "td");
// A right-aligned number cell.
void count_cell(std::string& o, std::uint64_t n);
// The tiles link to the first bus's findings: ids are given once.
std::string id_attr(bool first, const char* id);
// A title (the browser's tooltip) with the glossary's meaning of what a heading or tile names.
void title_attribute(std::string& o, const GlossaryTerm* term);
// A table heading that names a glossary term: its meaning is the heading's tooltip.
void term_heading(std::string& o, std::string_view label, std::string_view term);
// "serial bus" or "bus NAME".
std::string bus_title(const BusFindings& bus);

}  // namespace pvtap::analyzer::html_cells
