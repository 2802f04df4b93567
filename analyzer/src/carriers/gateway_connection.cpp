#include "carriers/gateway_connection.h"

#include <algorithm>

namespace pvtap::analyzer {

GatewayTraffic::Connection::Connection(Transport t, const Endpoint& slave_side, bool probed,
                                       bool listed, const GatewayOptions& o,
                                       BusProvider& bus_provider)
    : streams(t, slave_side, o.hole_wait, *this),
      buses_(bus_provider),
      reply_timeout_(o.reply_timeout),
      probe_(o.dialects, listed) {
  if (!probed) decide(FlowProbe::Verdict::NotBus);
}

void GatewayTraffic::Connection::on_segment(const Segment& s, double time) {
  last_seen = time;
  streams.on_segment(s, time);
}

void GatewayTraffic::Connection::data(Direction d, std::span<const std::uint8_t> bytes,
                                      double time) {
  if (carrier_) {
    carrier_->data(d, bytes, time);
    return;
  }
  const FlowProbe::Verdict v = probe_.add_data(d, bytes, time);
  if (v != FlowProbe::Verdict::Undecided) decide(v);
}

void GatewayTraffic::Connection::gap(Direction d, std::uint64_t lost, double time) {
  if (carrier_) {
    carrier_->gap(d, lost, time);
  } else {
    probe_.add_gap(d, lost, time);
  }
}

void GatewayTraffic::Connection::decide(FlowProbe::Verdict verdict) {
  carrier_ = make_carrier(verdict, CarrierContext{streams, buses_, reply_timeout_}, probe_.bytes());
  if (carrier_->analyzed()) {
    for (const FlowProbe::Item& item : probe_.items()) {
      if (item.gap) {
        carrier_->gap(item.direction, item.lost, item.time);
      } else {
        carrier_->data(item.direction, item.bytes, item.time);
      }
    }
  }
  probe_.clear();
}

void GatewayTraffic::Connection::finish(double time) {
  streams.flush(time);
  if (!carrier_) {
    // At the end a single good frame (or MBAP piece) is enough.
    decide(probe_.final_verdict());
  }
  carrier_->finish(time);
}

void GatewayTraffic::Connection::idle(double now) {
  streams.expire(now);
  if (carrier_) carrier_->idle(now);
}

std::optional<double> GatewayTraffic::Connection::next_deadline() const {
  std::optional<double> due = streams.hole_deadline();
  if (const std::optional<double> carried = carrier_ ? carrier_->next_deadline() : std::nullopt) {
    due = due ? std::min(*due, *carried) : carried;
  }
  return due;
}

void GatewayTraffic::Connection::add_stats(NetworkStats& into) const {
  // A flow still probing counts neither as analyzed nor as ignored.
  const bool analyzed = carrier_ && carrier_->analyzed();
  if (carrier_) carrier_->add_stats(into);
  streams.add_stats(into, analyzed);
}

}  // namespace pvtap::analyzer
