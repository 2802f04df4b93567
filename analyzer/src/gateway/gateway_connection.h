// One TCP or UDP flow between a master and a gateway: its two directions, the probe that
// decides whether it carries inverter traffic, and the feeding of its bus.
#pragma once

#include <cstdint>
#include <optional>
#include <span>

#include "gateway/endpoint_match.h"
#include "gateway/flow_probe.h"
#include "gateway/gateway_traffic.h"
#include "gateway/tcp_stream.h"

namespace pvtap::analyzer {

struct GatewayTraffic::Connection {
  // DirectionSink: where one TCP direction's ordered bytes go.
  struct DirectionSink : TcpStreamSink {
    DirectionSink(Connection& c, Direction d) : connection(c), direction(d) {}
    void on_stream_data(std::span<const std::uint8_t> bytes, double time) override {
      connection.data(direction, bytes, time);
    }
    void on_stream_gap(std::uint64_t lost, double time) override {
      connection.gap(direction, lost, time);
    }
    Connection& connection;
    Direction direction;
  };

  enum class State { Probing, Bus, Ignored };

  Connection(Transport t, const Endpoint& slave_side, State initial, const GatewayOptions& o,
             BusProvider& bus_provider);

  // Direction of a segment sent from `source`.
  Direction direction_from(const Endpoint& source) const {
    return same_endpoint(source, slave) ? Direction::FromSlave : Direction::ToSlave;
  }
  TcpDirectionStream& stream(Direction d) {
    return d == Direction::ToSlave ? to_slave_stream : from_slave_stream;
  }

  void on_segment(const Segment& s, double time);
  void data(Direction d, std::span<const std::uint8_t> bytes, double time);
  void gap(Direction d, std::uint64_t lost, double time);
  void finish(double time);
  bool closed() const { return reset || (fin_to_slave && fin_from_slave); }
  void add_stats(NetworkStats& into) const;
  void feed_bus(Direction d, std::span<const std::uint8_t> bytes, double time);
  void become_bus();
  void become_ignored();

  Transport transport;
  Endpoint slave;
  State state;
  BusProvider& buses;  // where the flow gets its bus once it is found to be a gateway's
  BusSession* bus = nullptr;
  FlowProbe probe;
  DirectionSink to_slave_sink;
  DirectionSink from_slave_sink;
  TcpDirectionStream to_slave_stream;
  TcpDirectionStream from_slave_stream;
  std::uint64_t ignored_bytes = 0;
  double last_seen = 0;
  bool fin_to_slave = false;
  bool fin_from_slave = false;
  bool reset = false;
};

}  // namespace pvtap::analyzer
