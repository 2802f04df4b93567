// BusWire: the simulated RS485 line: events back to back at its baud rate, in time order.
#pragma once

#include <cstddef>
#include <optional>
#include <utility>
#include <vector>

#include "bus/bus_event.h"
#include "sim_random.h"

namespace pvtap::sim {

// Overlap: two transmissions of different masters' exchanges that were on the line at once.
struct Overlap {
  Micros start = 0, end = 0;  // from the first one's first byte to the last one's last
  BusEvent older, fresh;      // the two destroyed transmissions, as they were sent
};

class BusWire {
 public:
  explicit BusWire(unsigned baud, bool echo = false) : baud_(baud), echo_(echo) {}

  // The events put from now on belong to a new exchange of `master`.
  void begin_exchange(std::uint8_t master) {
    master_ = master;
    ++exchange_;
  }
  // Puts the event on the line from `at` on; returns when its last byte ends. With an echoing
  // adapter a request is followed back to back by its copy, and the return is the copy's end.
  Micros put(BusEvent event, Micros at);
  // Puts a run of noise from the slave side; returns when it ends.
  Micros put_noise(Micros at, SimRandom& random);

  // Whether a damaged frame of this role, put on the line next, could be delimited by a
  // reader (see the definition).
  bool may_damage(Role role) const;

  // The first pair of transmissions, one of the exchange put from event `first` on and one of
  // another master's, that overlapped on the line: both are destroyed (see the definition for
  // the physics), with what followed them in their exchanges, and the garbage the line carried
  // takes their place. nullopt when the exchange met nothing.
  std::optional<Overlap> collide(std::size_t first);
  // Events in time order (a shared bus puts its masters' exchanges as they are decided).
  void sort_by_time();

  const std::vector<BusEvent>& events() const { return events_; }
  std::vector<BusEvent> take_events() { return std::move(events_); }

 private:
  Micros char_time(std::size_t bytes) const;

  unsigned baud_;
  bool echo_ = false;
  std::uint8_t master_ = 1;
  std::uint32_t exchange_ = 0;
  std::vector<BusEvent> events_;
};

}  // namespace pvtap::sim
