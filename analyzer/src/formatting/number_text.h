// Numbers, hex and UTC times appended to an output buffer without temporary strings: the
// hot path of every output format.
#pragma once

#include <cstdint>
#include <span>
#include <string>

namespace pvtap::analyzer {

void append_uint(std::string& out, std::uint64_t value);
void append_int(std::string& out, std::int64_t value);

// Fixed-point with `decimals` digits after the point ("52.3"); always a valid JSON number.
void append_fixed(std::string& out, double value, int decimals);

// Lowercase hex digits with no separator ("01030000000ac5cd").
void append_hex(std::string& out, std::span<const std::uint8_t> bytes);

// Lowercase hex with a space between bytes ("01 03 00").
void append_spaced_hex(std::string& out, std::span<const std::uint8_t> bytes);

// "0x1F".
void append_hex_byte(std::string& out, std::uint8_t value);

// UTC time of day with microseconds ("10:00:00.012345"), or with the date in front.
void append_time_of_day(std::string& out, double epoch_seconds);
void append_utc_date_time(std::string& out, double epoch_seconds);

}  // namespace pvtap::analyzer
