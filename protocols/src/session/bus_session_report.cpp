// The report of a bus session: its totals, whether its times can be judged, and the stations.
#include <string>

#include "pvtap/session/bus_session.h"
#include "session/bus_session_impl.h"

namespace pvtap {

ReassemblerTotals BusSession::Impl::totals() const {
  ReassemblerTotals sum = carried;
  for (const auto& s : streams) {
    if (s) sum += s->reassembler.totals();
  }
  return sum;
}

TimestampQuality BusSession::Impl::timestamp_quality() const {
  if (!options.has_timestamps)
    return {false, "the input has no timestamps (a plain byte dump)", ""};
  if (carried.frames > 0) {
    return {false,
            "the frames came whole in Modbus/TCP ADUs: their times are the LAN side's (client "
            "and gateway), not the serial bus's; latency is the gateway's answer time",
            ""};
  }
  for (const auto& s : streams) {
    if (!s || s->reassembler.timing_trusted()) continue;
    const bool declared = options.reassembler.timestamps == TimestampTrust::Untrusted;
    if (declared && !options.timestamp_note.empty()) {
      return {false, std::string(options.timestamp_note), ""};
    }
    return {false, std::string(s->reassembler.timing_reason()), ""};
  }
  return {true, "", options.timestamp_source};
}

const EventTally& BusSession::tally() const {
  return impl_->tally.events();
}

ReassemblerTotals BusSession::totals() const {
  return impl_->totals();
}

BusSharing BusSession::Impl::sharing(const TimingReport& timing) const {
  BusSharing s;
  const BusCounters& c = tally.counters();
  s.masters = !timing.masters.empty() ? timing.masters.size() : c.requests > 0 ? 1 : 0;
  s.echoes = c.echoes;
  // The traces of a collision on a bus of one master are line damage (CollisionTally). A
  // second master shows by its cycle, or, on a bus too busy for cycles to show, by requests
  // sent while another's reply was due (name_collisions).
  s.collisions = collisions.collisions();
  s.lost_in_collision = collisions.lost_requests();
  return s;
}

BusSharing BusSession::sharing() const {
  return impl_->sharing(impl_->times.report(impl_->timestamp_quality()));
}

BusReport BusSession::report() const {
  const Impl& m = *impl_;
  BusReport r;
  m.tally.fill(r);
  r.bytes = m.totals();
  r.has_timestamps = m.options.has_timestamps;
  r.first_time = m.times.first();
  r.last_time = m.times.last();
  r.timing = m.times.report(m.timestamp_quality());
  const BusSharing shared = m.sharing(r.timing);
  // Without timestamps (or a cycle) no master is told apart: the requests are one master's.
  if (r.timing.masters.empty() && shared.masters == 1)
    r.timing.masters.push_back(MasterPlan{0, {}, r.requests, 1.0, std::nullopt});
  r.collisions = shared.collisions;
  r.lost_in_collision = shared.lost_in_collision;
  m.tally.fill_stations(r);
  const auto readings = m.replies.latest();
  const auto inferred = m.replies.inferred();
  for (StationSummary& s : r.stations) {
    for (const StationLatency& l : r.timing.latency_by_station) {
      if (l.station == s.station) s.latency = l.latency;
    }
    if (const auto blocks = inferred.find(s.station); blocks != inferred.end()) {
      s.inferred = blocks->second;
    }
    if (const SunSpecChain* chain = m.decoder.sunspec_chain(s.station)) s.sunspec = *chain;
    const auto it = readings.find(s.station);
    if (it == readings.end()) continue;
    s.last_report_time = it->second.last_time;
    s.latest_values = it->second.values;
  }
  return r;
}

}  // namespace pvtap
