// report_line: one line of the text report from a printf format.
#pragma once

#include <string>

namespace pvtap::analyzer {

// One report line from a printf format, newline included (reports are written once, so
// formatting speed does not matter there).
std::string report_line(const char* format, ...) __attribute__((format(printf, 1, 2)));

}  // namespace pvtap::analyzer
