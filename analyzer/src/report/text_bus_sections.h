// The text report's sections of one bus: its stations, findings, latency, polling, masters,
// timing, latest values and inferred blocks.
#pragma once

#include <string>

#include "report/audit_report.h"

namespace pvtap::analyzer {

// All that the text report says of one bus below its heading and its serial line.
void append_bus_sections_text(const AuditReport& report, const BusFindings& bus, std::string& o);

}  // namespace pvtap::analyzer
