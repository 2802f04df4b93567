// Inverter: one simulated inverter on the bus: its plant, its registers and its replies.
#pragma once

#include <cstdint>
#include <optional>

#include "bus/bus_event.h"
#include "bus/poll_blocks.h"
#include "faults/fault_plan.h"
#include "plant/plant_model.h"
#include "plant/register_image.h"
#include "sim_random.h"

namespace pvtap::sim {

class Inverter {
 public:
  // `seed`, `start`: the run's, from which the plant's own course follows.
  Inverter(std::uint8_t station, Dialect dialect, std::uint64_t seed, Micros start);

  std::uint8_t station() const { return station_; }
  Dialect dialect() const { return dialect_; }
  const PlantState& plant() const { return plant_.state(); }

  // The reply to a read of `block` whose request ended at `request_end`, with the values the
  // plant had then, shaped by the fault (an error reply, a count one short).
  BusEvent reply(const PollBlock& block, std::optional<FaultKind> fault, Micros request_end,
                 SimRandom& random);

 private:
  std::uint8_t station_;
  Dialect dialect_;
  PlantModel plant_;
  RegisterImage image_;
};

}  // namespace pvtap::sim
