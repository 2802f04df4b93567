// BusTally: the counters and examples of a BusReport, filled frame by frame: the event counts
// by the one EventTally, the stations by the StationTally, and what only the report keeps (per
// dialect, examples).
#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <span>
#include <utility>
#include <vector>

#include "pvtap/session/bus_report.h"
#include "pvtap/session/bus_session.h"
#include "pvtap/session/event_tally.h"
#include "session/station_tally.h"

namespace pvtap::detail {

class BusTally {
 public:
  void add_frame(const SessionFrame& f);
  void add_timeout(const SessionTimeout& t);
  void add_gap(const SessionGap& g);
  void add_noise(const SessionNoise& n) { events_.add(n); }
  void add_line_error(const SessionLineError& e) { events_.add(e); }
  void add_driver_glitch(const SessionDriverGlitch& g) { events_.add(g); }
  void add_transaction(const Transaction& t);
  const EventTally& events() const { return events_; }
  // What EventTally does not count (requests, echoes, ...), as fill() writes them.
  const BusCounters& counters() const { return counts_; }

  // Writes the counters and examples into `r` (byte totals, timing and values come from
  // elsewhere: its bytes are zero here).
  void fill(BusReport& r) const;
  // The per-station counters, for the stations that exist, and the unknown station.
  void fill_stations(BusReport& r) const { stations_.fill(r); }

 private:
  void count_exception(const SessionFrame& f);
  static FrameExample example_of(const SessionFrame& f);

  StationTally stations_;
  EventTally events_;
  BusCounters counts_;  // what EventTally does not count
  std::vector<FrameExample> bad_check_examples_;
  std::vector<TimeoutExample> timeout_examples_;
  std::vector<FrameExample> unsolicited_examples_;
  std::map<std::pair<Dialect, std::uint8_t>, std::uint64_t> exception_codes_;
};

}  // namespace pvtap::detail
