// BusMaster: plays a data logger polling every inverter of the bus in rounds, then the plain
// Modbus devices beside them (a meter, an IO module), faults included; the result is the
// timeline of bus bytes.
#pragma once

#include <memory>
#include <optional>
#include <vector>

#include "bus/bus_event.h"
#include "bus/bus_wire.h"
#include "bus/inverter.h"
#include "bus/poll_blocks.h"
#include "command/sim_config.h"
#include "devices/modbus_device.h"
#include "faults/fault_plan.h"
#include "sim_random.h"

namespace pvtap::sim {

class BusMaster {
 public:
  explicit BusMaster(const SimConfig& config);
  // The meter reads the inverters' output through this object: it stays where it was made.
  BusMaster(const BusMaster&) = delete;
  BusMaster& operator=(const BusMaster&) = delete;
  BusTimeline run();

 private:
  // Sends one request and its reply (or the lack of one); returns when the bus is free.
  Micros poll(Inverter& inv, const PollBlock& block, Micros at);
  // A run of damaged requests for one block: the slave ignores each one, the master waits out
  // its timeout and, kDamagedRetryPercent of the time, retries the block only to have the line
  // damage it again (at most kMaxDamagedRun in a row).
  Micros send_damaged_requests(const Frame& request, Micros at);
  // Puts the reply to a request on the bus, damaged, late, doubled or followed by noise as the
  // fault says (the bus is free at the returned time).
  Micros answer(BusEvent rep, std::optional<FaultKind> fault, TimeoutTruth request);
  // One request to a plain Modbus device and its reply (devices/device_polls.cpp).
  Micros poll_device(ModbusDevice& device, const Frame& request, Micros at);
  // The device's reply as the fault shapes it (an exception, a count one short).
  BusEvent device_reply(ModbusDevice& device, const Frame& request, std::optional<FaultKind> fault,
                        Micros request_end);
  Micros late_reply_from_absent(ModbusDevice& device, const Frame& request, Micros at);
  Micros refused_request(const Frame& request, Micros at);
  void add_devices();
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
  std::vector<std::unique_ptr<ModbusDevice>> devices_;  // polled after the inverters
  BusWire wire_;
  BusTimeline timeline_;  // the ground truth; its events stay on wire_ until the run ends
  bool closing_ = false;  // the last poll of a run: no faults
  // The next request pins the end of the damaged reply before it, so it may not be damaged.
  bool next_request_pins_ = false;
};

}  // namespace pvtap::sim
