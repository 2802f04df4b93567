// Display text for decoded register values (allocates; for output, not the hot path).
#pragma once

#include <string>
#include <string_view>

#include "pvtap/registers/register_decoder.h"

namespace pvtap {

// The value as a person reads it: "52.3 V", "single phase, 3.0 kW", "2005-10", an enum text,
// the names of the set bits, the text of a text register, "31 inverter, serial 103".
std::string format_value(const DecodedValue& v);
void append_value_text(std::string& out, const DecodedValue& v);

// The number the value's text shows: the scaled value at the register's decimals, read back
// (2206 x 0.1 is 220.6, not 220.60000000000002), so that a number compared with what a person
// reads matches it. The value itself where no map entry gives decimals.
double value_as_shown(const DecodedValue& v);
// Digits after the point a number value is shown with: its map entry's, or more when its scale
// factor register gives more (10^-3: 3). `v.def` must be set.
unsigned shown_decimals(const DecodedValue& v);

// The value's address as the reference writes it ("0x1006", "0x0020", "1056"); a GSL wire
// address with no decimal reading (hex IDs) is shown as hex.
RegisterAddressText format_value_address(const DecodedValue& v, Dialect d);

// A short description of one warning ("low part above 9999 in a decimal pair").
std::string_view describe(ValueWarning w);

}  // namespace pvtap
