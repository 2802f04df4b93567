// The register blocks a master reads from each dialect, as PROTOCOLS.md documents them.
#pragma once

#include <cstdint>
#include <span>

#include "pvtap/codec/dialect.h"

namespace pvtap::sim {

// PollBlock: one read request of a poll round.
struct PollBlock {
  std::uint8_t function = 0;
  std::uint16_t start = 0;  // written address (GSL: the decimal ID, which is the wire address)
  std::uint16_t count = 0;
  bool first_round_only = false;  // identification and settings, read once at start-up
};

std::span<const PollBlock> poll_blocks(Dialect dialect);

}  // namespace pvtap::sim
