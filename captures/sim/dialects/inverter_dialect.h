// What a simulated inverter does in its dialect: the blocks a master polls, its registers from
// the plant's state, the shape of its replies. One record per dialect a simulated inverter
// speaks (dialects/<name>_inverter.cpp); the bus and the command find it by the dialect.
#pragma once

#include <cstdint>
#include <span>

#include "bus/poll_blocks.h"
#include "plant/plant_model.h"
#include "plant/register_image.h"
#include "pvtap/codec/frame.h"

namespace pvtap::sim {

struct InverterDialect {
  Dialect dialect;
  std::span<const PollBlock> poll_blocks;  // a poll round, in order (PROTOCOLS.md's blocks)
  // The plant's state written into the registers of the dialect's map, by the map's keys.
  void (*fill_registers)(const PlantModel& plant, RegisterImage& image);
  // What a read reply carries besides its words (set already): a start, a byte count, a
  // device number.
  void (*shape_read_reply)(Frame& reply, const PollBlock& block, DeviceNumber device);
  // Its error reply, or null when its errors are exception replies to the request
  // (function | 0x80 and a code, bus/frame_shapes.cpp).
  Frame (*error_reply)(std::uint8_t station, DeviceNumber device);
  // Whether a station that cannot answer stays silent: the dialect has no error reply.
  bool errors_are_silence;
  std::uint8_t last_station;  // the highest address its station field holds
};

// The record of `d`, or null when no simulated inverter speaks it (plain Modbus devices poll
// and answer by their own code, devices/).
const InverterDialect* inverter_dialect(Dialect d);

}  // namespace pvtap::sim
