// Changes one byte of an encoded reply so that its check fails but its length stays readable.
#pragma once

#include <cstdint>
#include <vector>

#include "pvtap/dialect.h"
#include "sim_random.h"

namespace pvtap::sim {

void corrupt_one_byte(std::vector<std::uint8_t>& bytes, Dialect dialect, SimRandom& random);

}  // namespace pvtap::sim
