#include "bus/poll_blocks.h"

#include "dialects/inverter_dialect.h"

namespace pvtap::sim {

std::span<const PollBlock> poll_blocks(Dialect dialect) {
  // Plain Modbus devices poll their own blocks.
  const InverterDialect* inverter = inverter_dialect(dialect);
  return inverter != nullptr ? inverter->poll_blocks : std::span<const PollBlock>{};
}

}  // namespace pvtap::sim
