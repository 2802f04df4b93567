// The laid-out bus as logic channels: each channel its idle level and the samples at which it
// toggles (the bus as the RS485 receiver sees it, the master's TX and RX, a DE per talker).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "logic/logic_layout.h"

namespace pvtap::sim {

struct ChannelSignal {
  std::string name;
  bool initial = true;                 // the level at sample 0
  std::vector<std::uint64_t> toggles;  // sample indexes where the level flips, ascending
};

struct LogicSignals {
  double sample_rate = 0;
  std::uint64_t samples = 0;
  std::int64_t start_unix = 0;  // seconds; the archive's entries carry it, not the clock's time
  std::vector<ChannelSignal> channels;
};

LogicSignals logic_signals(const LogicLayout& layout, const LogicOptions& options,
                           std::uint64_t seed);

}  // namespace pvtap::sim
