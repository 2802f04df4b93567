// Appending numbers, hex and quoted strings to an output buffer without temporary strings.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <string_view>

namespace pvtap::analyzer {

// One report line from a printf format, newline included (reports are written once, so
// formatting speed does not matter there).
std::string report_line(const char* format, ...) __attribute__((format(printf, 1, 2)));

void append_uint(std::string& out, std::uint64_t value);
void append_int(std::string& out, std::int64_t value);
// Fixed-point with `decimals` digits after the point ("52.3"); always a valid JSON number.
void append_fixed(std::string& out, double value, int decimals);
// Lowercase hex digits with no separator ("01030000000ac5cd").
void append_hex(std::string& out, std::span<const std::uint8_t> bytes);
// Lowercase hex with a space between bytes ("01 03 00").
void append_spaced_hex(std::string& out, std::span<const std::uint8_t> bytes);
// A JSON string literal with quotes and escapes.
void append_json_string(std::string& out, std::string_view text);
// The next member's name of a JSON object already open: `,"name":`.
void append_json_key(std::string& out, std::string_view name);
// `,"name":123`.
void append_json_count(std::string& out, std::string_view name, std::uint64_t value);
// A CSV field, quoted when it holds a comma, quote or line break (RFC 4180).
void append_csv_field(std::string& out, std::string_view text);
// "0x1F".
void append_hex_byte(std::string& out, std::uint8_t value);
// UTC time of day with microseconds ("10:00:00.012345"), or with the date in front.
void append_time_of_day(std::string& out, double epoch_seconds);
void append_utc_date_time(std::string& out, double epoch_seconds);

}  // namespace pvtap::analyzer
