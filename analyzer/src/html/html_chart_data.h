// The data of the HTML report's charts as one JSON object, read by the page's script.
#pragma once

#include <string>

#include "formatting/json_writer.h"
#include "html/html_report.h"
#include "html/timeline.h"
#include "report/audit_report.h"

namespace pvtap::analyzer {

void append_chart_data_json(std::string& o, const AuditReport& r, const Timeline& t,
                            const HtmlOptions& options);

// The timing histograms' data: each judged bus's silences in their buckets (the chart data's
// "silences").
// A bus whose timing was judged carries the histograms; only those buses are charted, in the
// order of report.buses.
bool has_silence_histograms(const BusReport& bus);

// The member "silences":[{"bus":..,"t15_ms":..,"t35_ms":..,"char_ms":..,"inner":{"edges_ms":
// [..],"counts":[..]},"between":{..}},...]
void write_silence_data_json(JsonWriter& w, const AuditReport& r);

}  // namespace pvtap::analyzer
