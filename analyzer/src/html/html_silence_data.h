// The timing histograms' data: each judged bus's silences in their buckets, for the page's
// script (the chart data's "silences").
#pragma once

#include "formatting/json_writer.h"
#include "report/audit_report.h"

namespace pvtap::analyzer {

// A bus whose timing was judged carries the histograms; only those buses are charted, in the
// order of report.buses.
bool has_silence_histograms(const BusReport& bus);

// The member "silences":[{"bus":..,"t15_ms":..,"t35_ms":..,"char_ms":..,"inner":{"edges_ms":
// [..],"counts":[..]},"between":{..}},...]
void write_silence_data_json(JsonWriter& w, const AuditReport& r);

}  // namespace pvtap::analyzer
