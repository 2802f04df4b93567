// The frames the simulated master and inverters exchange, as typed core Frames; their bytes
// always come from the core's encode_frame.
#pragma once

#include <cstdint>

#include "bus/bus_event.h"
#include "bus/poll_blocks.h"
#include "pvtap/codec/frame.h"

namespace pvtap::sim {

Frame read_request(Dialect d, std::uint8_t station, const PollBlock& block);
// A read reply carrying `words` (fewer than asked for when a fault says so).
Frame read_reply(Dialect d, std::uint8_t station, const PollBlock& block, const WordList& words,
                 DeviceNumber device);
// GSL exception (code 0x02 or 0x06) or Hybrid 0xFF error reply; ASCII has none.
Frame error_reply(Dialect d, std::uint8_t station, const PollBlock& block, DeviceNumber device,
                  std::uint8_t gsl_code);

// The bus event of a frame, its bytes from the core's encoder.
BusEvent frame_event(const Frame& frame);

}  // namespace pvtap::sim
