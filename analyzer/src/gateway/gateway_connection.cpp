#include "gateway/gateway_connection.h"

namespace pvtap::analyzer {
namespace {

Direction other(Direction d) {
  return d == Direction::ToSlave ? Direction::FromSlave : Direction::ToSlave;
}

}  // namespace

GatewayTraffic::Connection::Connection(Transport t, const Endpoint& slave_side, State initial,
                                       const GatewayOptions& o, BusProvider& bus_provider)
    : transport(t),
      slave(slave_side),
      state(initial),
      buses(bus_provider),
      probe(o.dialects),
      to_slave_sink(*this, Direction::ToSlave),
      from_slave_sink(*this, Direction::FromSlave),
      to_slave_stream(to_slave_sink, TcpDirectionStream::Limits{o.hole_wait, 1 << 20}),
      from_slave_stream(from_slave_sink, TcpDirectionStream::Limits{o.hole_wait, 1 << 20}) {
  if (state == State::Bus) become_bus();
}

void GatewayTraffic::Connection::on_segment(const Segment& s, double time) {
  last_seen = time;
  const Direction d = direction_from(s.source);
  if (transport == Transport::Udp) {
    if (!s.payload.empty()) data(d, s.payload, time);
    if (s.payload_on_wire > s.payload.size()) gap(d, s.payload_on_wire - s.payload.size(), time);
    return;
  }
  const bool syn = (s.flags & tcp_flag::kSyn) != 0;
  const bool fin = (s.flags & tcp_flag::kFin) != 0;
  if ((s.flags & tcp_flag::kAck) != 0) stream(other(d)).on_peer_ack(s.ack, time);
  stream(d).on_segment(s.seq, s.payload, s.payload_on_wire, syn, fin, time);
  if (fin) (d == Direction::ToSlave ? fin_to_slave : fin_from_slave) = true;
  if ((s.flags & tcp_flag::kRst) != 0) reset = true;
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
  const bool other_complete = transport == Transport::Udp || !stream(other(d)).has_hole();
  bus->feed(BusChunk{bytes, time, d, other_complete});
}

void GatewayTraffic::Connection::become_bus() {
  state = State::Bus;
  bus = &buses.gateway_bus(slave.to_string());
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
  to_slave_stream.flush(time);
  from_slave_stream.flush(time);
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
  for (const TcpDirectionStream* s : {&to_slave_stream, &from_slave_stream}) {
    into.retransmitted_bytes += s->stats().retransmitted_bytes;
    into.out_of_order_segments += s->stats().out_of_order_segments;
    if (state == State::Bus) {
      into.lost_bytes += s->stats().lost_bytes;
      into.gaps += s->stats().gaps;
    }
  }
}

}  // namespace pvtap::analyzer
