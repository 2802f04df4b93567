// BusHealth: the counters of one bus that MQTT publishes every interval, counted from the
// same events the other outputs get by the core's EventTally, and their JSON.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "pvtap/session/bus_session.h"
#include "pvtap/session/event_tally.h"
#include "pvtap/statistics/distribution_summary.h"
#include "report/live_report.h"

namespace pvtap::analyzer {

struct BusHealth {
  EventTally events;  // since the start, by the report's rules
  // The serial driver's counters of a tap, when it keeps them (TIOCGICOUNT; not a pty).
  std::optional<LineErrorCounts> line_errors;
  DistributionAccumulator latency_interval;  // since the last publication

  template <typename Event>
  void count(const Event& e) {
    events.add(e);
  }
  void count(const SessionFrame& f);
  void start_interval() { latency_interval = DistributionAccumulator{}; }
};

// HealthContext: what the health line says besides the bus's counters.
struct HealthContext {
  double now = 0;
  double interval = 0;
  std::string_view bus;  // empty for the single bus of a serial tap
  std::size_t stations = 0;
  std::size_t stations_answering = 0;
  std::size_t poll_blocks = 0;
  std::size_t poll_blocks_missing = 0;  // not seen for three of their periods
  std::uint64_t events_queued = 0;      // waiting for the broker
  std::uint64_t events_dropped = 0;     // the queue was full
  BusSharing sharing;                   // masters, collisions and echoes, as the report has them
};

// The names of the health counters, in the order of the JSON (Home Assistant's diagnostic
// sensors are made from this list).
struct HealthField {
  std::string_view key;
  std::string_view name;
  std::string_view unit;  // empty for counts
  bool counter;           // only grows (total_increasing)
};
extern const HealthField kHealthFields[22];

// {"ts":...,"interval_s":10,"frames":...,"latency_p50_ms":...,...,"line_errors":{...},
// "bus":"..."}; latency fields are null while no reply was timed, line_errors where the
// driver does not count them.
void append_health_json(std::string& out, const BusHealth& h, const HealthContext& c);

}  // namespace pvtap::analyzer
