// SimConfig: what one simulator run plays — the bus, its inverters, its faults, its clock.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "bus/bus_event.h"
#include "faults/fault_plan.h"
#include "pvtap/codec/dialect.h"

namespace pvtap::sim {

struct SimConfig {
  std::uint64_t seed = 1;
  std::vector<Dialect> dialects{kDefaultDialect};  // station i speaks dialects[i % size]
  unsigned inverters = 3;                          // 0: a bus of plain Modbus devices only
  std::uint8_t first_station = 1;
  Micros start = 1'782'036'000'000'000;  // 2026-06-21 10:00:00 UTC
  double duration_s = 60.0;
  double period_s = 5.0;   // one poll round of every inverter per period
  double timeout_s = 1.0;  // how long the master waits for a reply
  unsigned baud = 9600;
  FaultPlan faults;
  // Plain Modbus devices beside the inverters, polled after them in every round.
  std::optional<std::uint8_t> meter_station;
  bool meter_low_first = false;                 // the meter sends each float's low word first
  std::optional<std::uint8_t> battery_station;  // a home battery of plain Modbus registers
  std::optional<std::uint8_t> sunspec_station;  // a string inverter answering SunSpec models
  std::optional<std::uint8_t> io_module_station;
  std::optional<std::uint8_t> test_server_station;  // a Modbus library's test suite server
  // A shared bus: a second master (a meter reader, a BMS, a second logger) with a poll plan and
  // period of its own (0: period_s x 1.37); a second device answering to one inverter's
  // address; the tap's adapter echoing every request.
  unsigned masters = 1;
  double second_period_s = 0;
  std::optional<std::uint8_t> address_conflict;
  bool echo = false;
};

}  // namespace pvtap::sim
