// The end-of-run report: as text for people, as one JSON line for jq.
#pragma once

#include "formatting/json_writer.h"
#include "formatting/output_stream.h"
#include "report/audit_report.h"

namespace pvtap::analyzer {

// The jsonl summary line: {"type":"summary","bytes":...,"stations":{...},...}.
void write_json_summary(const AuditReport& report, OutputStream& out);

// The text report: totals, findings with examples, latency, polling, bus timing and the
// latest value of every register per station.
void write_text_report(const AuditReport& report, OutputStream& out);

// The sources of a live capture (serial taps, interface) as report lines / JSON members.
void append_live_sources_text(const LiveSources& live, std::string& o);
void write_live_sources_json(JsonWriter& w, const LiveSources& live);

// Key of a station in the report: "1", or "10.0.0.5:4001/1" when there are several buses.
std::string station_key(const AuditReport& report, const BusFindings& bus, std::uint8_t station);
// The addresses the unknown station's damaged frames claimed: "33, 81, 88", or "none".
std::string claimed_addresses(const UnknownStation& unknown);

}  // namespace pvtap::analyzer
