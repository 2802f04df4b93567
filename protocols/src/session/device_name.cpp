#include "pvtap/session/bus_report.h"

namespace pvtap {

std::string DeviceName::text() const {
  std::string out;
  for (const std::string* part : {&vendor, &product, &revision}) {
    if (part->empty()) continue;
    if (!out.empty()) out += ' ';
    out += *part;
  }
  return out.empty() ? server_id : out;
}

}  // namespace pvtap
