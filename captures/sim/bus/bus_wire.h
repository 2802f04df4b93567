// BusWire: the simulated RS485 line: events back to back at its baud rate, in time order.
#pragma once

#include <cstddef>
#include <utility>
#include <vector>

#include "bus/bus_event.h"
#include "sim_random.h"

namespace pvtap::sim {

class BusWire {
 public:
  explicit BusWire(unsigned baud) : baud_(baud) {}

  // Puts the event on the line from `at` on; returns when its last byte ends.
  Micros put(BusEvent event, Micros at);
  // Puts a run of noise from the slave side; returns when it ends.
  Micros put_noise(Micros at, SimRandom& random);

  // Whether a damaged frame of this role, put on the line next, could be delimited by a
  // reader (see the definition).
  bool may_damage(Role role) const;

  const std::vector<BusEvent>& events() const { return events_; }
  std::vector<BusEvent> take_events() { return std::move(events_); }

 private:
  Micros char_time(std::size_t bytes) const;

  unsigned baud_;
  std::vector<BusEvent> events_;
};

}  // namespace pvtap::sim
