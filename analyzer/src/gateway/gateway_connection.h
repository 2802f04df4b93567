// One TCP or UDP flow between a master and a gateway: its two directions, the probe that
// decides whether it carries inverter traffic, and the feeding of its bus.
#pragma once

#include <cstdint>
#include <span>

#include "gateway/flow_probe.h"
#include "gateway/flow_streams.h"
#include "gateway/gateway_traffic.h"

namespace pvtap::analyzer {

struct GatewayTraffic::Connection final : FlowBytes {
  enum class State { Probing, Bus, Ignored };

  Connection(Transport t, const Endpoint& slave_side, State initial, const GatewayOptions& o,
             BusProvider& bus_provider);

  void on_segment(const Segment& s, double time);
  void data(Direction d, std::span<const std::uint8_t> bytes, double time) override;
  void gap(Direction d, std::uint64_t lost, double time) override;
  void finish(double time);
  void add_stats(NetworkStats& into) const;
  void feed_bus(Direction d, std::span<const std::uint8_t> bytes, double time);
  void become_bus();
  void become_ignored();

  State state;
  BusProvider& buses;  // where the flow gets its bus once it is found to be a gateway's
  BusSession* bus = nullptr;
  FlowProbe probe;
  FlowStreams streams;
  std::uint64_t ignored_bytes = 0;
  double last_seen = 0;
};

}  // namespace pvtap::analyzer
