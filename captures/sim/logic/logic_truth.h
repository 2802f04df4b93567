// What the ground truth says of a logic session: its line, the glitch bytes drivers emitted,
// each talker's driver turnaround and the timing violations planted.
#pragma once

#include "lan/lan_exchanges.h"
#include "logic/logic_layout.h"
#include "logic/logic_signals.h"

namespace pvtap::sim {

LanTruth logic_truth(const LogicLayout& layout, const LogicSignals& signals,
                     const LogicOptions& options, unsigned baud);

}  // namespace pvtap::sim
