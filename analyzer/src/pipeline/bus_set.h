// BusSet: the buses of a run, one BusSession each (one per gateway endpoint, one per serial
// tap, one for a serial capture), and the sinks that tag their events with the bus's name.
#pragma once

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "events/event_writer.h"
#include "pvtap/session/bus_session.h"
#include "pvtap/session/event_tally.h"
#include "report/audit_report.h"

namespace pvtap::analyzer {

class BusSet {
 public:
  // Every bus's events go to `events`; `from_recording_start`: their times count from a logic
  // recording's start.
  BusSet(const RegisterDecoder& decoder, EventWriter& events, bool from_recording_start);
  ~BusSet();
  BusSet(const BusSet&) = delete;
  BusSet& operator=(const BusSet&) = delete;

  // The bus of that name; nullptr before add().
  BusSession* find(const std::string& name);
  const BusSession* find(const std::string& name) const;
  BusSession& add(const std::string& name, const BusSessionOptions& options);
  BusSession& find_or_add(const std::string& name, const BusSessionOptions& options);

  // The bus has been silent until `now` on every bus (live capture).
  void idle(double now);
  void finish();
  std::optional<double> next_deadline() const;  // the earliest over every bus
  std::vector<BusFindings> findings() const;
  ReassemblerTotals totals() const;  // over every bus
  EventTally tally() const;          // the buses' event tallies merged
  EventCounts counts() const;        // their counts alone, added up (no latency to merge)

 private:
  struct Bus;
  const RegisterDecoder& decoder_;
  EventWriter& events_;
  bool from_recording_start_;
  std::vector<std::unique_ptr<Bus>> buses_;
  std::map<std::string, Bus*> by_name_;
};

}  // namespace pvtap::analyzer
