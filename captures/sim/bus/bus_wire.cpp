#include "bus/bus_wire.h"

#include <cmath>
#include <utility>

namespace pvtap::sim {

Micros BusWire::char_time(std::size_t bytes) const {
  // 10 bits per character: start, 8 data, stop.
  return static_cast<Micros>(std::llround(static_cast<double>(bytes) * 1e7 / baud_));
}

Micros BusWire::put(BusEvent event, Micros at) {
  event.start = at;
  event.end = at + char_time(event.bytes.size());
  const Micros end = event.end;
  events_.push_back(std::move(event));
  return end;
}

Micros BusWire::put_noise(Micros at, SimRandom& random) {
  BusEvent noise;
  noise.kind = BusEvent::Kind::Noise;
  noise.role = Role::Response;
  noise.fault = "noise";
  // High bytes (0xA0-0xFE): no function code, and above the stations of the usual buses,
  // so the noise is not mistaken for the start of a frame.
  const auto n = random.between(3, 12);
  while (noise.bytes.size() < static_cast<std::size_t>(n)) {
    const auto b = static_cast<std::uint8_t>(random.between(0xA0, 0xFE));
    noise.bytes.push_back(b);
  }
  return put(std::move(noise), at);
}

// A reader can delimit a damaged frame only where both its ends are pinned, so damage goes
// only where the start is: a request right after a frame (never noise), a reply (which follows
// its own request) never after noise from the slave side either, as a gateway's reply stream
// has no request in between. What follows pins the end: the master's timeout after a request,
// a pause after a reply. Asked before the poll's request is on the bus.
bool BusWire::may_damage(Role role) const {
  if (role == Role::Request)
    return !events_.empty() && events_.back().kind == BusEvent::Kind::Frame;
  for (auto it = events_.rbegin(); it != events_.rend(); ++it)
    if (it->role == Role::Response) return it->kind == BusEvent::Kind::Frame;
  return true;
}

}  // namespace pvtap::sim
