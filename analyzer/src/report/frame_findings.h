// Words for what the core found about one frame or value, shared by every output format.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "pvtap/registers/register_decoder.h"
#include "pvtap/session/bus_session.h"

namespace pvtap::analyzer {

// The findings of a frame as short phrases ("unsolicited reply", "exception 0x02: ...").
// `out` is cleared first and reused, so a frame without findings costs nothing.
void collect_issues(const SessionFrame& f, std::vector<std::string>& out);

// Why a request went unanswered, as a key: "no_reply", "next_request_first",
// "carrier_no_reply" (a logger stick's code 05), "input_ended"
// (the input stopped before the timeout ran out) or "data_lost" (the reply may be in a gap).
std::string_view unanswered_reason(const SessionTimeout& t);

// What the timeouts of a bus were, for an operator: "none", or "3 good requests their station
// did not answer within --timeout: 2 met silence until the timeout ran out, 1 was cut short by
// the master's next request" (only the kinds that happened). Text and HTML reports alike.
std::string timeouts_explained(const BusReport& b);

// A register value as a JSON object: {"register":"0x1006","name":"battery voltage",
// "value":52.3,"unit":"V"}, with "text" for readings that are more than a number and
// "warnings" when the decoder had doubts.
void append_value_json(std::string& out, const DecodedValue& v, Dialect d);
// The same in parts: the part that depends only on the register
// ({"register":"0x1006","name":"battery voltage","value":), the unit part (,"unit":"V" or
// nothing), and the rest of the object after the reading's value.
void append_value_json_head(std::string& out, const DecodedValue& v, Dialect d);
void append_value_json_unit(std::string& out, const DecodedValue& v);
void append_value_json_reading(std::string& out, const DecodedValue& v);
void append_value_json_tail(std::string& out, const DecodedValue& v);

// ReadingKind: how a value's reading is written: a number (scaled numbers and BCD; the raw
// word of enums, bits, raw registers and words outside the map), a text (text registers,
// year-month, device numbers) or nothing (part of it is outside the frame).
enum class ReadingKind { Number, Text, None };
ReadingKind reading_kind(const DecodedValue& v);
// The reading of a value whose reading_kind is Number, as a JSON number ("52.3", "3").
void append_value_number(std::string& out, const DecodedValue& v);

// "battery voltage 52.3 V" (or "0x1099 0x00AB" for a word outside the map).
void append_value_words(std::string& out, const DecodedValue& v, Dialect d);

// The function as text: "read holding registers (0x03)".
void append_function(std::string& out, Dialect d, std::uint8_t function);

}  // namespace pvtap::analyzer
