// The command line of the LAN carriers (--v5, --mbap): their options and what they allow.
#pragma once

#include <CLI/CLI.hpp>
#include <string>

#include "command/sim_config.h"
#include "lan/mbap_session.h"
#include "lan/v5_session.h"

namespace pvtap::sim {

// LanOutputs: the LAN carrier a run writes, if any (one at most, alone: see lan_problem).
struct LanOutputs {
  std::string v5, mbap;
  std::string v5_faults = "none", mbap_faults = "none";
  V5Options v5_options;
  MbapOptions mbap_options;
};

void add_lan_options(CLI::App& app, LanOutputs& lan);

// After parsing: the carriers' faults read, and an error text when the run cannot be carried
// (empty when it can). `bus_outputs`: whether a bus carrier or device was asked for too.
std::string finish_lan_options(LanOutputs& lan, const SimConfig& config, bool bus_outputs);

}  // namespace pvtap::sim
