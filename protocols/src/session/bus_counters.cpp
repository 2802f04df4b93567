// operator+= of the counter sets (ReassemblerTotals, BusCounters, UnknownStation): the one
// place they add up.
#include <algorithm>
#include <cstddef>
#include <cstdint>

#include "pvtap/framing/stream_reassembler.h"
#include "pvtap/session/bus_report.h"

namespace pvtap {
namespace {

// Every field of a counter set is a 64-bit counter, so its size counts its fields: a counter
// added to a struct and not added up below fails one of these.
template <typename T>
constexpr bool holds_counters(std::size_t n) {
  return sizeof(T) == n * sizeof(std::uint64_t);
}
static_assert(holds_counters<ReassemblerTotals>(6), "add the new counter up below");
static_assert(holds_counters<RoleCounts>(2), "add the new counter up below");
static_assert(holds_counters<GapTally>(3), "add the new counter up below");
static_assert(holds_counters<LineErrorTally>(4), "add the new counter up below");
static_assert(holds_counters<BusCounters>(6 + 2 + kDialectCount * 2 + 1 + 1 + 2 + 4 + 16 + 3 + 4),
              "add the new counter up below");

RoleCounts& operator+=(RoleCounts& a, const RoleCounts& b) {
  a.requests += b.requests;
  a.responses += b.responses;
  return a;
}

GapTally& operator+=(GapTally& a, const GapTally& b) {
  a.gaps += b.gaps;
  a.lost_bytes += b.lost_bytes;
  a.gaps_of_unknown_size += b.gaps_of_unknown_size;
  return a;
}

template <typename T, std::size_t N>
void add_each(std::array<T, N>& a, const std::array<T, N>& b) {
  for (std::size_t i = 0; i < N; ++i) a[i] += b[i];
}

}  // namespace

ReassemblerTotals& ReassemblerTotals::operator+=(const ReassemblerTotals& o) {
  bytes_in += o.bytes_in;
  frame_bytes += o.frame_bytes;
  noise_bytes += o.noise_bytes;
  frames += o.frames;
  bad_frames += o.bad_frames;
  noise_runs += o.noise_runs;
  return *this;
}

LineErrorTally& LineErrorTally::operator+=(const LineErrorTally& o) {
  framing_errors += o.framing_errors;
  parity_errors += o.parity_errors;
  breaks += o.breaks;
  driver_glitches += o.driver_glitches;
  return *this;
}

BusCounters& BusCounters::operator+=(const BusCounters& o) {
  bytes += o.bytes;
  requests += o.requests;
  responses += o.responses;
  add_each(by_dialect, o.by_dialect);
  malformed_frames += o.malformed_frames;
  timeouts += o.timeouts;
  add_each(timeouts_by_reason, o.timeouts_by_reason);
  damaged_replies += o.damaged_replies;
  unanswered_damaged_requests += o.unanswered_damaged_requests;
  unanswered_at_end += o.unanswered_at_end;
  unanswered_after_loss += o.unanswered_after_loss;
  transactions += o.transactions;
  unsolicited += o.unsolicited;
  late_replies += o.late_replies;
  duplicates += o.duplicates;
  address_conflicts += o.address_conflicts;
  echoes += o.echoes;
  collisions += o.collisions;
  lost_in_collision += o.lost_in_collision;
  count_mismatches += o.count_mismatches;
  role_corrections += o.role_corrections;
  dialect_changes += o.dialect_changes;
  quantity_problems += o.quantity_problems;
  forbidden_broadcasts += o.forbidden_broadcasts;
  write_count_problems += o.write_count_problems;
  exceptions += o.exceptions;
  gateway_timeouts += o.gateway_timeouts;
  gaps += o.gaps;
  line_errors += o.line_errors;
  return *this;
}

UnknownStation& UnknownStation::operator+=(const UnknownStation& o) {
  damaged_frames += o.damaged_frames;
  unanswered_damaged_requests += o.unanswered_damaged_requests;
  for (const ClaimedStation& c : o.claimed) {
    const auto at = std::lower_bound(
        claimed.begin(), claimed.end(), c.station,
        [](const ClaimedStation& a, std::uint8_t station) { return a.station < station; });
    if (at != claimed.end() && at->station == c.station) {
      at->frames += c.frames;
    } else {
      claimed.insert(at, c);
    }
  }
  return *this;
}

}  // namespace pvtap
