// One TCP or UDP flow between a master and a gateway: its two directions, the probe that
// decides what carries the bus in it, and then that carrier.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <span>

#include "carriers/flow_carrier.h"
#include "carriers/flow_streams.h"
#include "carriers/gateway_traffic.h"
#include "pvtap/carriers/flow_probe.h"

namespace pvtap::analyzer {

struct GatewayTraffic::Connection final : FlowBytes {
  // `probed`: the flow may be a gateway's (its first bytes are probed); else it is ignored.
  // `listed`: the flow is on a --port (bus traffic: bare, wrapped in V5, or Modbus/TCP).
  Connection(Transport t, const Endpoint& slave_side, bool probed, bool listed,
             const GatewayOptions& o, BusProvider& bus_provider);

  void on_segment(const Segment& s, double time);
  // The ordered bytes of either direction: to the probe until it decides, then the carrier.
  void data(Direction d, std::span<const std::uint8_t> bytes, double time) override;
  void gap(Direction d, std::uint64_t lost, double time) override;
  void finish(double time);
  // A live capture: holes and held requests whose time has come are given up.
  void idle(double now);
  std::optional<double> next_deadline() const;
  void add_stats(NetworkStats& into) const;

  FlowStreams streams;
  double last_seen = 0;

 private:
  // The probe's verdict chooses the carrier once; the bytes it held are replayed to it once.
  void decide(FlowProbe::Verdict verdict);

  BusProvider& buses_;  // where the flow gets its bus once it is found to be a gateway's
  double reply_timeout_;
  FlowProbe probe_;
  std::unique_ptr<FlowCarrier> carrier_;  // null while probing
};

}  // namespace pvtap::analyzer
