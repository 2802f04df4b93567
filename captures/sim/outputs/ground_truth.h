// Writes the ground truth of a simulated bus as JSON: every frame and noise run with its
// time, the faults injected, the timeouts, the register values, and the totals.
#pragma once

#include <string>

#include "bus/bus_event.h"
#include "command/sim_config.h"
#include "lan/lan_exchanges.h"

namespace pvtap::sim {

// Returns an error text, empty on success. `lan`: the LAN carrier the run was written as (its
// counts and frames go in beside the bus's), or none.
std::string write_ground_truth(const BusTimeline& timeline, const SimConfig& config,
                               const std::string& path, const LanTruth* lan = nullptr);

}  // namespace pvtap::sim
