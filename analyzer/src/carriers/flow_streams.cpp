// FlowStreams: segments to ordered bytes, per direction.
#include "carriers/flow_streams.h"

#include <algorithm>

#include "carriers/endpoint_match.h"

namespace pvtap::analyzer {
namespace {

Direction other(Direction d) {
  return d == Direction::ToSlave ? Direction::FromSlave : Direction::ToSlave;
}

}  // namespace

FlowStreams::Side::Side(FlowBytes& to, Direction d, double hole_wait)
    : target(to), direction(d), stream(*this, TcpDirectionStream::Limits{hole_wait, 1 << 20}) {}

FlowStreams::FlowStreams(Transport transport, const Endpoint& slave, double hole_wait,
                         FlowBytes& bytes)
    : transport_(transport),
      slave_(slave),
      to_slave_(bytes, Direction::ToSlave, hole_wait),
      from_slave_(bytes, Direction::FromSlave, hole_wait) {}

void FlowStreams::on_segment(const Segment& s, double time) {
  const Direction d = same_endpoint(s.source, slave_) ? Direction::FromSlave : Direction::ToSlave;
  if (transport_ == Transport::Udp) {
    if (!s.payload.empty()) side(d).on_stream_data(s.payload, time);
    if (s.payload_on_wire > s.payload.size()) {
      side(d).on_stream_gap(s.payload_on_wire - s.payload.size(), time);
    }
    return;
  }
  const bool syn = (s.flags & tcp_flag::kSyn) != 0;
  const bool fin = (s.flags & tcp_flag::kFin) != 0;
  if ((s.flags & tcp_flag::kAck) != 0) side(other(d)).stream.on_peer_ack(s.ack, time);
  side(d).stream.on_segment(s.seq, s.payload, s.payload_on_wire, syn, fin, time);
  if (fin) side(d).fin = true;
  if ((s.flags & tcp_flag::kRst) != 0) reset_ = true;
}

void FlowStreams::expire(double now) {
  to_slave_.stream.expire(now);
  from_slave_.stream.expire(now);
}

std::optional<double> FlowStreams::hole_deadline() const {
  const std::optional<double> to = to_slave_.stream.hole_deadline();
  const std::optional<double> from = from_slave_.stream.hole_deadline();
  if (to && from) return std::min(*to, *from);
  return to ? to : from;
}

void FlowStreams::flush(double time) {
  to_slave_.stream.flush(time);
  from_slave_.stream.flush(time);
}

void FlowStreams::add_stats(NetworkStats& into, bool analyzed) const {
  for (const TcpDirectionStream* s : {&to_slave_.stream, &from_slave_.stream}) {
    into.retransmitted_bytes += s->stats().retransmitted_bytes;
    into.out_of_order_segments += s->stats().out_of_order_segments;
    if (analyzed) {
      into.lost_bytes += s->stats().lost_bytes;
      into.gaps += s->stats().gaps;
    }
  }
}

}  // namespace pvtap::analyzer
