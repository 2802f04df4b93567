// BusMaster: plays a data logger polling every inverter of the bus in rounds, then the plain
// Modbus devices beside them (a meter, an IO module), faults included; the result is the
// timeline of bus bytes. On a shared bus (--masters 2) a second master polls a plan of its own
// at a period of its own, and where the two masters' exchanges meet on the line they collide
// (bus_wire.cpp says how; shared_bus.cpp plays the second master and the consequences).
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

  // One poll of a master's round: an inverter's block or a device's request.
  struct PollStep {
    Inverter* inverter = nullptr;
    PollBlock block;
    ModbusDevice* device = nullptr;
    Frame request;
  };
  // A master's place in its plan: its round, the polls of that round, and when it sends next.
  struct PollCursor {
    std::uint8_t master = 1;
    double period_s = 0;
    unsigned round = 0;
    Micros round_start = 0;
    Micros at = 0;
    std::size_t next = 0;
    std::vector<PollStep> steps;
    bool done = false;
  };
  std::vector<PollStep> round_steps(const PollCursor& cursor);
  void begin_round(PollCursor& cursor, Micros stop);
  // The cursor's next poll, sent at cursor.at; returns when that master may send again.
  Micros poll_step(const PollCursor& cursor);
  // shared_bus.cpp: the second master's poll (no faults of its own), the second device that
  // answers to the conflicting address, and what a collision leaves of both exchanges.
  std::vector<PollStep> second_round_steps();
  Micros second_poll(Inverter& inv, const PollBlock& block, Micros at);
  Micros conflicting_reply(const PollBlock& block, Micros request_end, Micros free,
                           SimRandom& random, std::int64_t turnaround_min_ms,
                           std::int64_t turnaround_max_ms);
  Micros settle_collision(std::size_t first, Micros free, PollCursor& other);
  void forget_truth_of(const DestroyedExchange& exchange, Micros request_end);
  void describe_shared_bus();
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

  static constexpr double kSecondPeriodFactor = 1.37;
  static constexpr std::int64_t kSecondTurnaroundMinMs = 5, kSecondTurnaroundMaxMs = 15;
  static constexpr std::int64_t kTurnaroundMinMs = 20, kTurnaroundMaxMs = 60;

  SimConfig config_;
  SimRandom random_;
  SimRandom second_random_;  // the second master's chance: the first keeps its own draws
  std::vector<Inverter> inverters_;
  std::vector<std::unique_ptr<ModbusDevice>> devices_;  // polled after the inverters
  std::optional<Inverter> impostor_;  // --address-conflict: the second device at that address
  BusWire wire_;
  BusTimeline timeline_;  // the ground truth; its events stay on wire_ until the run ends
  bool closing_ = false;  // the last poll of a run: no faults
  // The next request pins the end of the damaged reply before it, so it may not be damaged.
  bool next_request_pins_ = false;
};

}  // namespace pvtap::sim
