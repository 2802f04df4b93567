// CSV fields appended to an output buffer (RFC 4180 quoting).
#pragma once

#include <string>
#include <string_view>

namespace pvtap::analyzer {

// A CSV field, quoted when it holds a comma, quote or line break (RFC 4180).
void append_csv_field(std::string& out, std::string_view text);

}  // namespace pvtap::analyzer
