// GatewayTraffic: TCP and UDP flows of serial-to-TCP gateways turned into bus byte streams.
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <tuple>
#include <vector>

#include "pvtap/capture/network_packet.h"
#include "pvtap/session/bus_session.h"

namespace pvtap::analyzer {

class BusSet;

// GatewayOptions: which flows are gateway traffic.
struct GatewayOptions {
  std::vector<std::uint16_t> ports;  // empty: recognize the protocol on any port
  DialectSet dialects = DialectSet::all();
  double hole_wait = 2.0;  // seconds a TCP hole may stay open before it counts as lost
};

// NetworkStats: what happened to the capture's flows.
struct NetworkStats {
  std::uint64_t flows_analyzed = 0;
  std::uint64_t flows_ignored = 0;  // no inverter frames, or not on --port
  std::uint64_t ignored_bytes = 0;  // payload of ignored flows
  std::uint64_t retransmitted_bytes = 0;
  std::uint64_t out_of_order_segments = 0;
  std::uint64_t lost_bytes = 0;
  std::uint64_t gaps = 0;
};

// BusSource: where a flow found to be a gateway's gets its bus, and how that bus is made.
struct BusSource {
  BusSet& buses;
  const BusSessionOptions& options;
};

class GatewayTraffic {
 public:
  // A flow found to be a gateway's gets its bus from `buses`, made with `bus_options`: one
  // bus per slave-side endpoint, so that reconnections to the same gateway continue it.
  GatewayTraffic(GatewayOptions options, BusSet& buses, BusSessionOptions bus_options);
  ~GatewayTraffic();
  GatewayTraffic(const GatewayTraffic&) = delete;
  GatewayTraffic& operator=(const GatewayTraffic&) = delete;

  void on_segment(const Segment& segment, double time);
  // End of input: holes are lost, flows still being probed are decided.
  void finish(double time);
  NetworkStats stats() const;

  struct Connection;

 private:
  using FlowKey = std::tuple<Transport, Endpoint, Endpoint>;  // lower endpoint first

  static FlowKey key_of(const Segment& s);
  Connection* find_or_open(const Segment& s);
  bool in_last_flow(const Segment& s) const;  // the flow of last_key_, either way round
  void close(std::map<FlowKey, std::unique_ptr<Connection>>::iterator it, double time);
  // Gives up TCP holes that waited too long and closes flows silent for long.
  void expire_old_state(double now);

  GatewayOptions options_;
  BusSet& buses_;
  BusSessionOptions bus_options_;
  std::map<FlowKey, std::unique_ptr<Connection>> flows_;
  // Packets of one flow come in runs: the last flow found is tried first.
  Connection* last_flow_ = nullptr;
  FlowKey last_key_{};
  NetworkStats closed_;  // stats of connections already closed
  double last_expiry_ = 0;
};

}  // namespace pvtap::analyzer
