// The parts of the HTML report that are tables and text, rendered from AuditReport (the
// numbers the text report prints, from the same fields).
#pragma once

#include <string>

#include "html/timeline.h"
#include "report/audit_report.h"

namespace pvtap::analyzer {

void append_html_overview(std::string& o, const AuditReport& r);
void append_html_stations(std::string& o, const AuditReport& r);
void append_html_polling(std::string& o, const AuditReport& r, const Timeline& t);
void append_html_findings(std::string& o, const AuditReport& r);
// What each station last reported: the text report's "latest values".
void append_html_latest_values(std::string& o, const AuditReport& r);
// A table per polled block with words no map names: their inferred types.
void append_html_inferred(std::string& o, const AuditReport& r);
// Per bus, its serial line where one was measured, the t1.5 and t3.5 verdicts, and where
// timing is judged the place of its silence histogram.
void append_html_bus_timing(std::string& o, const AuditReport& r);

// A poll silence is a finding when it lasts more than twice the bus's longest poll period
// (or kMinSilence when no block was polled twice).
bool silence_is_finding(const BusReport& bus, const PollSilence& s);

}  // namespace pvtap::analyzer
