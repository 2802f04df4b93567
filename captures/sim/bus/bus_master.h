// BusMaster: plays a data logger polling every inverter of the bus in rounds, faults
// included; the result is the timeline of bus bytes.
#pragma once

#include <optional>
#include <vector>

#include "bus/bus_event.h"
#include "bus/bus_wire.h"
#include "bus/inverter.h"
#include "bus/poll_blocks.h"
#include "command/sim_config.h"
#include "faults/fault_plan.h"
#include "sim_random.h"

namespace pvtap::sim {

class BusMaster {
 public:
  explicit BusMaster(const SimConfig& config);
  BusTimeline run();

 private:
  // Sends one request and its reply (or the lack of one); returns when the bus is free.
  Micros poll(Inverter& inv, const PollBlock& block, Micros at);
  // A run of damaged requests for one block: the slave ignores each one, the master waits out
  // its timeout and, kDamagedRetryPercent of the time, retries the block only to have the line
  // damage it again (at most kMaxDamagedRun in a row).
  Micros send_damaged_requests(const Inverter& inv, const PollBlock& block, Micros at);
  // The reply to a request (the bus is free at the returned time).
  Micros answer(Inverter& inv, const PollBlock& block, std::optional<FaultKind> fault,
                TimeoutTruth request);
  std::optional<FaultKind> pick_fault(Dialect d);
  // The fault, or none where its damage could not be pinned (see BusWire::may_damage).
  std::optional<FaultKind> placed(std::optional<FaultKind> fault) const;
  Micros timeout_after(Micros request_end);
  void close_on_a_good_frame(Micros at);
  void set_aside_unexpired_timeouts();

  static constexpr unsigned kDamagedRetryPercent = 30;
  static constexpr unsigned kMaxDamagedRun = 4;
  static constexpr std::int64_t kPinningPauseMs = 100;  // silence after a damaged reply
  // Silence before the request that pins a reply damaged in its data only: less than a USB
  // adapter's latency timer, so both can reach a capture in one chunk.
  static constexpr std::int64_t kCloseRequestMs = 8;

  SimConfig config_;
  SimRandom random_;
  std::vector<Inverter> inverters_;
  BusWire wire_;
  BusTimeline timeline_;  // the ground truth; its events stay on wire_ until the run ends
  bool closing_ = false;  // the last poll of a run: no faults
  // The next request pins the end of the damaged reply before it, so it may not be damaged.
  bool next_request_pins_ = false;
};

}  // namespace pvtap::sim
