// The HTML report's bus timing: per bus, its serial line where one was measured, the t1.5 and
// t3.5 verdicts, and where timing is judged the place of its silence histogram.
#pragma once

#include <string>

#include "report/audit_report.h"

namespace pvtap::analyzer {

void append_html_bus_timing(std::string& o, const AuditReport& r);

}  // namespace pvtap::analyzer
