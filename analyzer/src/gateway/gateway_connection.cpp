#include "gateway/gateway_connection.h"

namespace pvtap::analyzer {

GatewayTraffic::Connection::Connection(Transport t, const Endpoint& slave_side, State initial,
                                       const GatewayOptions& o, BusProvider& bus_provider)
    : state(initial),
      buses(bus_provider),
      probe(o.dialects),
      streams(t, slave_side, o.hole_wait, *this) {
  if (state == State::Bus) become_bus();
}

void GatewayTraffic::Connection::on_segment(const Segment& s, double time) {
  last_seen = time;
  streams.on_segment(s, time);
}

void GatewayTraffic::Connection::data(Direction d, std::span<const std::uint8_t> bytes,
                                      double time) {
  switch (state) {
    case State::Bus:
      feed_bus(d, bytes, time);
      return;
    case State::Ignored:
      ignored_bytes += bytes.size();
      return;
    case State::Probing:
      break;
  }
  const FlowProbe::Verdict v = probe.add_data(d, bytes, time);
  if (v == FlowProbe::Verdict::Bus) become_bus();
  if (v == FlowProbe::Verdict::NotBus) become_ignored();
}

void GatewayTraffic::Connection::gap(Direction d, std::uint64_t lost, double time) {
  if (state == State::Bus) {
    bus->data_lost(d, time, lost);
  } else if (state == State::Probing) {
    probe.add_gap(d, lost, time);
  }
}

void GatewayTraffic::Connection::feed_bus(Direction d, std::span<const std::uint8_t> bytes,
                                          double time) {
  // The other side's turn is not over while some of its bytes are still missing (a hole
  // waiting for a retransmission).
  bus->feed(BusChunk{bytes, time, d, streams.other_complete(d)});
}

void GatewayTraffic::Connection::become_bus() {
  state = State::Bus;
  bus = &buses.gateway_bus(streams.slave().to_string());
  // A new connection starts new streams: nothing of the previous one may join its bytes.
  bus->restart(Direction::ToSlave);
  bus->restart(Direction::FromSlave);
  for (const FlowProbe::Item& item : probe.items()) {
    if (item.gap) {
      bus->data_lost(item.direction, item.time, item.lost);
    } else {
      feed_bus(item.direction, item.bytes, item.time);
    }
  }
  probe.clear();
}

void GatewayTraffic::Connection::become_ignored() {
  state = State::Ignored;
  ignored_bytes += probe.bytes();
  probe.clear();
}

void GatewayTraffic::Connection::finish(double time) {
  streams.flush(time);
  if (state == State::Probing) {
    if (probe.final_verdict() == FlowProbe::Verdict::Bus) {
      become_bus();
    } else {
      become_ignored();
    }
  }
  if (state == State::Bus) {
    bus->end_turn(Direction::ToSlave);
    bus->end_turn(Direction::FromSlave);
  }
}

void GatewayTraffic::Connection::add_stats(NetworkStats& into) const {
  if (state == State::Bus) ++into.flows_analyzed;
  if (state == State::Ignored) ++into.flows_ignored;
  into.ignored_bytes += ignored_bytes;
  streams.add_stats(into, state == State::Bus);
}

}  // namespace pvtap::analyzer
