// Plays the bus onto a serial device or pty in real time: each event at its moment, each byte
// one character time after the one before, as a UART at that baud would send it.
#pragma once

#include <string>
#include <vector>

#include "bus/bus_event.h"

namespace pvtap::sim {

// Returns an error text, empty on success.
std::string pace_onto_device(const BusTimeline& timeline, const std::string& device, unsigned baud);

// A 4-wire bus: the master's requests onto `devices[0]`, the slaves' replies and the noise
// onto `devices[1]`, on one clock.
std::string pace_onto_duplex(const BusTimeline& timeline, const std::vector<std::string>& devices,
                             unsigned baud);

}  // namespace pvtap::sim
