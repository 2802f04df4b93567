// The bus as a stream of single bytes with the time each one finished on the wire, the view
// that byte-oriented carriers (USB adapters, serial-to-TCP gateways) have of it.
#pragma once

#include <cstdint>
#include <vector>

#include "bus/bus_event.h"

namespace pvtap::sim {

struct TimedByte {
  Micros time = 0;
  std::uint8_t value = 0;
  Role side = Role::Request;  // who drove the bus: master (request) or an inverter
};

std::vector<TimedByte> bus_bytes(const BusTimeline& timeline);

}  // namespace pvtap::sim
