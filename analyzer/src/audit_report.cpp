#include "audit_report.h"

#include <map>
#include <utility>

namespace pvtap::analyzer {

BusReport AuditReport::totals() const {
  BusReport t;
  std::map<std::pair<Dialect, std::uint8_t>, std::uint64_t> codes;
  for (const BusFindings& bus : buses) {
    const BusReport& r = bus.report;
    t.counters() += r.counters();
    for (const ExceptionTally& e : r.exception_codes) codes[{e.dialect, e.code}] += e.count;
  }
  for (const auto& [key, count] : codes) {
    t.exception_codes.push_back(ExceptionTally{key.first, key.second, count});
  }
  return t;
}

}  // namespace pvtap::analyzer
