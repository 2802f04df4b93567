// Words for what the core found about one frame or value, shared by every output format.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "pvtap/registers/register_decoder.h"
#include "pvtap/session/bus_session.h"

namespace pvtap::analyzer {

// Every warning a decoded value can carry, in the order the outputs list them.
inline constexpr ValueWarning kAllValueWarnings[] = {
    ValueWarning::NotInMap,         ValueWarning::Incomplete,       ValueWarning::LowPartOver9999,
    ValueWarning::UnknownEnumValue, ValueWarning::UnnamedBitSet,    ValueWarning::InvalidBcd,
    ValueWarning::InvalidDate,      ValueWarning::NonPrintableText, ValueWarning::NoWrittenAddress,
    ValueWarning::NotFinite,        ValueWarning::NoScaleFactor,
};

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

// How the two devices at one address answer, for an address conflict finding: "its first
// replies came 25.3 ms after their request (median), the other ones 41.2 ms (mean)".
std::string answering_patterns(const StationSummary& s);

// ReadingKind: how a value's reading is written: a number (scaled numbers and BCD; the raw
// word of enums, bits, raw registers and words outside the map), a text (text registers,
// year-month, device numbers) or nothing (part of it is outside the frame).
enum class ReadingKind { Number, Text, None };
ReadingKind reading_kind(const DecodedValue& v);
// The reading of a value whose reading_kind is Number, as a JSON number ("52.3", "3").
void append_value_number(std::string& out, const DecodedValue& v);

// "battery voltage 52.3 V" (or "0x1099 0x00AB" for a word outside the map).
void append_value_words(std::string& out, const DecodedValue& v, Dialect d);

// A station's newest value (LatestValue): its name, or for one no map names its table
// ("holding register", "coil"); its reading ("0x00E6 (230)" for an unmapped word, "on" or
// "off" for a bit).
std::string latest_value_name(const LatestValue& v);
std::string latest_value_text(const LatestValue& v);

// An inferred value (register_inference.h): the address of its first word ("0x0836"), its
// type ("float32 high word first", "u16 counter", "text, 8 words"), its reading
// ("235.1 (230.2..235.3)", "\"PVTAP-BAT\"").
std::string inferred_address(const InferredBlock& b, const InferredValue& v);
std::string inferred_type(const InferredValue& v);
std::string inferred_reading(const InferredValue& v);
// "read holding registers (0x03)"
std::string function_text(Dialect d, std::uint8_t function);

// The function as text: "read holding registers (0x03)".
void append_function(std::string& out, Dialect d, std::uint8_t function);

}  // namespace pvtap::analyzer
