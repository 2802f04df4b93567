// The data of the HTML report's charts as one JSON object, read by the page's script.
#pragma once

#include <string>

#include "html/html_report.h"
#include "html/timeline.h"
#include "report/audit_report.h"

namespace pvtap::analyzer {

void append_chart_data_json(std::string& o, const AuditReport& r, const Timeline& t,
                            const HtmlOptions& options);

}  // namespace pvtap::analyzer
