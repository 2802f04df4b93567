// SolarmanV5Flow: a TCP flow to a logger stick, its V5 frames read per direction and the RTU
// frame inside each put on the bus the stick's serial names.
#pragma once

#include <array>
#include <cstdint>
#include <span>

#include "gateway/bus_provider.h"
#include "pvtap/carriers/solarman_v5_reader.h"
#include "pvtap/framing/bus_chunk.h"

namespace pvtap::analyzer {

class SolarmanV5Flow {
 public:
  explicit SolarmanV5Flow(BusProvider& buses) : buses_(buses) {}

  void data(Direction d, std::span<const std::uint8_t> bytes, double time);
  void gap(Direction d, std::uint64_t lost, double time);
  // End of the flow: pending bytes are decided, both turns end.
  void finish(double time);

  solarman_v5::Totals totals() const;

 private:
  solarman_v5::SolarmanV5Reader& reader(Direction d) {
    return readers_[d == Direction::ToSlave ? 0 : 1];
  }
  void on_events(Direction d, std::span<const solarman_v5::Event> events, double time);
  BusSession& bus_for(std::uint32_t serial);

  BusProvider& buses_;
  std::array<solarman_v5::SolarmanV5Reader, 2> readers_;
  BusSession* bus_ = nullptr;  // the bus of the serial last seen
  std::uint32_t serial_ = 0;
};

}  // namespace pvtap::analyzer
