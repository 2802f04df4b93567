#include "report/report_line.h"

#include <cstdarg>
#include <cstdio>

namespace pvtap::analyzer {

std::string report_line(const char* format, ...) {
  char buf[512];
  va_list args;
  va_start(args, format);
  std::vsnprintf(buf, sizeof buf, format, args);
  va_end(args);
  return std::string(buf) + "\n";
}

}  // namespace pvtap::analyzer
