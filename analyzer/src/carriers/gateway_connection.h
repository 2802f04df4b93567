// One TCP or UDP flow between a master and a gateway: its two directions, the probe that
// decides whether it carries inverter traffic (serial frames or Modbus/TCP ADUs), and the
// feeding of its bus.
#pragma once

#include <cstdint>
#include <memory>
#include <span>

#include "carriers/flow_streams.h"
#include "carriers/gateway_traffic.h"
#include "carriers/solarman_v5_flow.h"
#include "pvtap/carriers/flow_probe.h"
#include "pvtap/carriers/mbap_flow.h"

namespace pvtap::analyzer {

struct GatewayTraffic::Connection final : FlowBytes {
  // Bus: serial frames as the gateway passes them on; Mbap: Modbus/TCP ADUs, whose unit id
  // and PDU are the frames; SolarmanV5: a logger stick's V5 frames around RTU frames.
  enum class State { Probing, Bus, Mbap, SolarmanV5, Ignored };

  // `listed`: the flow is on a --port (bus traffic: bare, wrapped in V5, or Modbus/TCP).
  Connection(Transport t, const Endpoint& slave_side, State initial, bool listed,
             const GatewayOptions& o, BusProvider& bus_provider);

  void on_segment(const Segment& s, double time);
  void data(Direction d, std::span<const std::uint8_t> bytes, double time) override;
  void gap(Direction d, std::uint64_t lost, double time) override;
  void finish(double time);
  void add_stats(NetworkStats& into) const;
  void feed_bus(Direction d, std::span<const std::uint8_t> bytes, double time);
  void become_bus();
  void become_mbap();
  void become_v5();
  void become_ignored();
  void replay_probe();

  State state;
  BusProvider& buses;  // where the flow gets its bus once it is found to be a gateway's
  BusSession* bus = nullptr;
  FlowProbe probe;
  SolarmanV5Flow v5;
  FlowStreams streams;
  std::unique_ptr<MbapFlow> mbap;
  double reply_timeout;
  std::uint64_t ignored_bytes = 0;
  double last_seen = 0;
};

}  // namespace pvtap::analyzer
