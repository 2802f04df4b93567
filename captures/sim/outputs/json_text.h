// How the ground truth writes times, numbers and bytes in JSON.
#pragma once

#include <cstdint>
#include <span>
#include <string>

#include "bus/bus_event.h"

namespace pvtap::sim {

std::string seconds(Micros t);  // "1782036000.012345"
std::string number(double v);   // up to ten significant digits
std::string hex(std::span<const std::uint8_t> bytes);

}  // namespace pvtap::sim
