// The event line formats on stdout: one EventWriter per --format.
#pragma once

#include <memory>

#include "events/event_writer.h"
#include "formatting/output_stream.h"

namespace pvtap::analyzer {

enum class OutputFormat { Text, Jsonl, Csv };

std::unique_ptr<EventWriter> make_text_event_writer(OutputStream& out);
std::unique_ptr<EventWriter> make_jsonl_event_writer(OutputStream& out);
std::unique_ptr<EventWriter> make_csv_event_writer(OutputStream& out);

}  // namespace pvtap::analyzer
