// BusMaster: plays a data logger polling every inverter of the bus in rounds and the
// inverters answering, faults included; the result is the timeline of bus bytes.
#pragma once

#include <optional>
#include <vector>

#include "bus_event.h"
#include "plant_model.h"
#include "poll_blocks.h"
#include "register_image.h"
#include "sim_config.h"
#include "sim_random.h"

namespace pvtap::sim {

class BusMaster {
 public:
  explicit BusMaster(const SimConfig& config);
  BusTimeline run();

 private:
  struct Inverter {
    std::uint8_t station;
    Dialect dialect;
    PlantModel plant;
    RegisterImage image;
  };

  // Sends one request and its reply (or the lack of one); returns when the bus is free.
  Micros poll(Inverter& inv, const PollBlock& block, Micros at);
  std::optional<FaultKind> pick_fault(Dialect d);
  Micros put(BusEvent event, Micros at);
  Micros put_noise(Micros at);
  Micros char_time(std::size_t bytes) const;
  void set_aside_unexpired_timeouts();

  SimConfig config_;
  SimRandom random_;
  std::vector<Inverter> inverters_;
  BusTimeline timeline_;
};

}  // namespace pvtap::sim
