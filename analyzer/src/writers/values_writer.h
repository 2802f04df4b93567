// ValuesWriter: the decoded register values as a time series (--values), one row per value:
// ts, bus, station, dialect, register, key, name, value, unit.
#pragma once

#include <memory>

#include "events/event_writer.h"
#include "formatting/output_stream.h"

namespace pvtap::analyzer {

// ValuesFormat: how --values writes its rows.
enum class ValuesFormat { Csv, Jsonl, Influx };

// Whether a frame's values belong in the time series: a reply with a good check whose words
// were placed by a request with a good check (the core decodes nothing else from replies).
bool frame_feeds_values(const SessionFrame& f);

// csv: a header row, then RFC 4180 rows; jsonl: one object per value; influx: InfluxDB line
// protocol (measurement pvtap, tags bus/station/dialect/key, field value, time in ns), where
// only numeric registers that have a key in their map can go.
std::unique_ptr<EventWriter> make_values_writer(ValuesFormat format, OutputStream& out);

}  // namespace pvtap::analyzer
