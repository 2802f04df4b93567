// Wording shared by the text report's audit-wide sections and its sections of one bus.
#pragma once

#include <cstdint>
#include <cstdio>
#include <string>

#include "pvtap/statistics/timing_statistics.h"
#include "report/audit_report.h"
#include "report/report_line.h"

namespace pvtap::analyzer::text_wording {

inline unsigned long long u(std::uint64_t v) {
  return static_cast<unsigned long long>(v);
}

inline double ms(double seconds) {
  return seconds * 1e3;
}

inline std::string distribution_text(const DistributionSummary& d) {
  if (d.count == 0) return "n=0  none measured";
  char buf[256];
  std::snprintf(buf, sizeof buf,
                "n=%llu  min %.1f  mean %.1f  p50 %.1f  p95 %.1f  p99 %.1f  max %.1f", u(d.count),
                ms(d.min), ms(d.mean), ms(d.p50), ms(d.p95), ms(d.p99), ms(d.max));
  return buf;
}

inline std::string when(const AuditReport& r, double time) {
  std::string out;
  append_report_time(out, r.settings, time);
  return out;
}


// A list of examples shorter than the count it stands for says how many it shows.
inline void examples_shown(std::size_t shown, std::uint64_t total, std::string& o) {
  if (shown > 0 && shown < total) {
    o += report_line("  %llu of %llu shown:", u(shown), u(total));
  }
}

}  // namespace pvtap::analyzer::text_wording
