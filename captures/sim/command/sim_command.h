// The pvtap-sim command line: what to simulate and where to write it.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "command/lan_options.h"
#include "command/sim_config.h"
#include "logic/logic_options.h"

namespace pvtap::sim {

// SimOutputs: the files (and device) a run writes; empty strings are skipped.
struct SimOutputs {
  std::string pdu, gateway, chunked, truth, device;
  unsigned read_delay_ms = 0;  // --chunked: how late the sniffer may read a USB transfer
  // A 4-wire bus: the requests' pair and the replies' pair, each through an adapter of its own
  // (two USER0 captures), or played onto two devices. Empty, or two paths.
  std::vector<std::string> duplex, duplex_devices;
  LanOutputs lan;
  LogicOptions logic;  // --sr: the bus as a logic analyzer samples it
};

struct SimCommand {
  SimConfig config;
  SimOutputs outputs;
};

// Parses argv; nullopt with `exit_code` set when the run should stop (help or a usage error).
std::optional<SimCommand> parse_sim_command(int argc, char** argv, int& exit_code);

}  // namespace pvtap::sim
