#include "session/station_tally.h"

#include "pvtap/codec/function_codes.h"
#include "pvtap/session/device_naming.h"
#include "pvtap/session/event_tally.h"
#include "pvtap/session/station_rule.h"

namespace pvtap::detail {
namespace {

constexpr std::uint8_t kBroadcastAddress = 0xFF;

}  // namespace

StationSummary& StationTally::station(std::uint8_t s) {
  std::unique_ptr<StationSummary>& slot = stations_[s];
  if (!slot) {
    slot = std::make_unique<StationSummary>();
    slot->station = s;
  }
  return *slot;
}

void StationTally::count_unknown(std::uint8_t claimed) {
  ++unknown_frames_;
  ++claimed_[claimed];
}

void StationTally::count_frame(StationSummary& s, const SessionFrame& f) {
  RoleCounts& by_dialect = s.by_dialect[static_cast<std::size_t>(f.dialect)];
  if (f.role == Role::Request) {
    ++s.requests;
    ++by_dialect.requests;
  } else {
    ++s.responses;
    ++by_dialect.responses;
  }
  if (!f.check.ok) ++s.bad_checks;
  if (f.unsolicited) ++s.unsolicited;
  if (f.duplicate) ++s.duplicates;
  if (f.address_conflict) {
    ++s.address_conflicts;
    if (f.conflict_after) {
      s.address_conflict_latency += (*f.conflict_after - s.address_conflict_latency) /
                                    static_cast<double>(s.address_conflicts);
    }
  }
  if (f.count_mismatch) ++s.count_mismatches;
  if (f.dialect_changed_from) ++s.dialect_changes;
  // Only two Modbus functions name a device: the call is skipped for the rest (and for
  // Hybrid's 0x11, which shares a code with report server ID).
  if (f.frame != nullptr && modbus_family(f.dialect) &&
      (f.frame->function == fc::kEncapsulatedInterface ||
       f.frame->function == fc::kReportServerId)) {
    learn_device_name(s.device, f);
  }
  if (gateway_timeout(f)) {
    ++s.timeouts;
  } else if (exception_code(f)) {
    ++s.exceptions;
  }
}

void StationTally::count_request(std::optional<std::uint8_t> owner, std::uint8_t claimed,
                                 Dialect d) {
  if (!owner) {
    count_unknown(claimed);
    return;
  }
  StationSummary& s = station(*owner);
  ++s.requests;
  ++s.by_dialect[static_cast<std::size_t>(d)].requests;
  ++s.bad_checks;
}

void StationTally::add_frame(const SessionFrame& f) {
  if (f.frame == nullptr) return;
  if (f.station) {
    count_frame(station(*f.station), f);
  } else if (f.role != Role::Request) {
    count_unknown(f.frame->station);
  }
  // A damaged request is counted when its reply or its timeout says whose it is.
}

void StationTally::add_transaction(const Transaction& t) {
  if (!t.reply_check_ok) {
    if (const auto s = transaction_station(t)) ++station(*s).damaged_replies;
  }
  if (t.request_check_ok || last_settled_request_ == t.request_id) return;
  last_settled_request_ = t.request_id;
  count_request(answered_request_station(t), t.broadcast ? kBroadcastAddress : t.station,
                t.dialect);
}

void StationTally::add_timeout(const SessionTimeout& t) {
  if (t.timeout.request_check_ok) {
    if (t.kind == UnansweredKind::Timeout && t.station) ++station(*t.station).timeouts;
    return;
  }
  count_request(t.station, t.timeout.station, t.timeout.dialect);
  if (t.kind == UnansweredKind::DamagedRequest && !t.station) ++unknown_unanswered_;
}

void StationTally::fill(BusReport& r) const {
  r.stations.clear();
  for (const auto& s : stations_) {
    if (s) r.stations.push_back(*s);
  }
  UnknownStation& u = r.unknown_station;
  u = UnknownStation{};
  u.damaged_frames = unknown_frames_;
  u.unanswered_damaged_requests = unknown_unanswered_;
  for (std::size_t a = 0; a < claimed_.size(); ++a) {
    if (claimed_[a] > 0)
      u.claimed.push_back(ClaimedStation{static_cast<std::uint8_t>(a), claimed_[a]});
  }
}

}  // namespace pvtap::detail
