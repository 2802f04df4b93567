#include "report/audit_report.h"

#include <algorithm>
#include <map>
#include <utility>

namespace pvtap::analyzer {

BusReport AuditReport::totals() const {
  BusReport t;
  std::map<std::pair<Dialect, std::uint8_t>, std::uint64_t> codes;
  for (const BusFindings& bus : buses) {
    const BusReport& r = bus.report;
    t.bytes.bytes_in += r.bytes.bytes_in;
    t.bytes.frame_bytes += r.bytes.frame_bytes;
    t.bytes.noise_bytes += r.bytes.noise_bytes;
    t.bytes.frames += r.bytes.frames;
    t.bytes.bad_frames += r.bytes.bad_frames;
    t.bytes.noise_runs += r.bytes.noise_runs;
    t.requests += r.requests;
    t.responses += r.responses;
    for (std::size_t d = 0; d < t.by_dialect.size(); ++d) {
      t.by_dialect[d].requests += r.by_dialect[d].requests;
      t.by_dialect[d].responses += r.by_dialect[d].responses;
    }
    t.malformed_frames += r.malformed_frames;
    t.timeouts += r.timeouts;
    t.timeouts_by_reason[0] += r.timeouts_by_reason[0];
    t.timeouts_by_reason[1] += r.timeouts_by_reason[1];
    t.damaged_replies += r.damaged_replies;
    t.unanswered_damaged_requests += r.unanswered_damaged_requests;
    t.unanswered_at_end += r.unanswered_at_end;
    t.unanswered_after_loss += r.unanswered_after_loss;
    t.transactions += r.transactions;
    t.unsolicited += r.unsolicited;
    t.late_replies += r.late_replies;
    t.duplicates += r.duplicates;
    t.count_mismatches += r.count_mismatches;
    t.role_corrections += r.role_corrections;
    t.exceptions += r.exceptions;
    for (const ExceptionTally& e : r.exception_codes) codes[{e.dialect, e.code}] += e.count;
    t.gaps.gaps += r.gaps.gaps;
    t.gaps.lost_bytes += r.gaps.lost_bytes;
    t.gaps.gaps_of_unknown_size += r.gaps.gaps_of_unknown_size;
  }
  for (const auto& [key, count] : codes) {
    t.exception_codes.push_back(ExceptionTally{key.first, key.second, count});
  }
  return t;
}

bool has_findings(const AuditReport& report) {
  const BusReport t = report.totals();
  return t.bytes.bad_frames > 0 || t.timeouts > 0 || t.exceptions > 0;
}

std::optional<TimeSpan> AuditReport::time_span() const {
  std::optional<TimeSpan> span;
  for (const BusFindings& b : buses) {
    if (b.report.bytes.bytes_in == 0) continue;
    if (!span) span = TimeSpan{b.report.first_time, b.report.last_time};
    span->first = std::min(span->first, b.report.first_time);
    span->last = std::max(span->last, b.report.last_time);
  }
  if (!settings.has_timestamps) return std::nullopt;
  return span;
}

}  // namespace pvtap::analyzer
