// GatewayTraffic: TCP and UDP flows of serial-to-TCP gateways turned into bus byte streams.
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <tuple>
#include <vector>

#include "carriers/bus_provider.h"
#include "pvtap/pcap/network_packet.h"
#include "pvtap/session/bus_session.h"
#include "report/network_stats.h"

namespace pvtap::analyzer {

// GatewayOptions: which flows are gateway traffic.
struct GatewayOptions {
  std::vector<std::uint16_t> ports;  // empty: recognize the protocol on any port
  DialectSet dialects = DialectSet::all();
  double hole_wait = 2.0;      // seconds a TCP hole may stay open before it counts as lost
  double reply_timeout = 1.0;  // seconds a Modbus/TCP request waits for its reply (--timeout)
};

class GatewayTraffic {
 public:
  // A flow found to be a gateway's gets its bus from `buses`: one bus per slave-side endpoint.
  GatewayTraffic(GatewayOptions options, BusProvider& buses);
  ~GatewayTraffic();
  GatewayTraffic(const GatewayTraffic&) = delete;
  GatewayTraffic& operator=(const GatewayTraffic&) = delete;

  void on_segment(const Segment& segment, double time);
  // Live input: nothing arrived until `now`; holes and silent flows whose time has come are
  // given up, as a segment arriving at `now` would have them.
  void idle(double now);
  // When idle() can next give something up: the earliest hole deadline or silent flow's end;
  // nullopt when only more segments can.
  std::optional<double> next_deadline() const;
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
  // Gives up TCP holes that waited too long and closes flows silent for long; `live`: and
  // the carriers' held requests whose wait ran out (see Connection::idle).
  void expire_old_state(double now, bool live);

  GatewayOptions options_;
  BusProvider& buses_;
  std::map<FlowKey, std::unique_ptr<Connection>> flows_;
  // Packets of one flow come in runs: the last flow found is tried first.
  Connection* last_flow_ = nullptr;
  FlowKey last_key_{};
  NetworkStats closed_;  // stats of connections already closed
  double last_expiry_ = 0;
};

}  // namespace pvtap::analyzer
