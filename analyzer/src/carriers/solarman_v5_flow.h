// SolarmanV5Flow: a TCP flow to a logger stick, its V5 frames read per direction, paired by
// the sequence byte the stick echoes, and the RTU frame inside each put on the bus of the
// stick's serial.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "carriers/bus_provider.h"
#include "carriers/flow_carrier.h"
#include "pvtap/carriers/solarman_v5_pairing.h"
#include "pvtap/carriers/solarman_v5_reader.h"
#include "pvtap/framing/bus_chunk.h"

namespace pvtap::analyzer {

class SolarmanV5Flow final : public FlowCarrier, solarman_v5::ReleaseSink {
 public:
  static constexpr std::size_t kMaxExamples = 5;

  // `timeout`: the matcher's; a request waits that long for the response of its sequence.
  SolarmanV5Flow(BusProvider& buses, double timeout) : buses_(buses), pairing_(timeout, *this) {}

  void data(Direction d, std::span<const std::uint8_t> bytes, double time) override;
  void gap(Direction d, std::uint64_t lost, double time) override;
  // End of the flow: pending bytes are decided, held requests handed on, both turns end.
  void finish(double time) override;
  // Held requests whose wait ran out go on their bus (SolarmanV5Pairing::next_deadline).
  void idle(double now) override { pairing_.idle(now); }
  std::optional<double> next_deadline() const override { return pairing_.next_deadline(); }
  void add_stats(NetworkStats& into) const override;

  solarman_v5::Totals totals() const;
  // The stick's codes said plainly (refusals, codes of no known meaning), the first few
  // different ones.
  const std::vector<std::string>& finding_examples() const { return examples_; }

 private:
  solarman_v5::SolarmanV5Reader& reader(Direction d) {
    return readers_[d == Direction::ToSlave ? 0 : 1];
  }
  void on_events(std::span<const solarman_v5::Event> events, double time);
  void release(const solarman_v5::Release& r) override;
  void example(std::string text);
  BusSession& bus_for(std::uint32_t serial);

  BusProvider& buses_;
  std::array<solarman_v5::SolarmanV5Reader, 2> readers_;
  solarman_v5::SolarmanV5Pairing pairing_;
  BusSession* bus_ = nullptr;  // the bus of the serial last seen
  std::uint32_t serial_ = 0;
  std::vector<std::string> examples_;
};

}  // namespace pvtap::analyzer
