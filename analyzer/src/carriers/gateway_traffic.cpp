#include "carriers/gateway_traffic.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include "carriers/endpoint_match.h"
#include "carriers/gateway_connection.h"

namespace pvtap::analyzer {
namespace {

// How often (capture seconds) holes are checked for their age.
constexpr double kExpiryInterval = 0.25;
// A flow silent this long is closed, so that a long capture full of short flows (DNS over
// UDP never says goodbye) does not keep them all; a later packet opens it again.
constexpr double kIdleFlow = 120.0;

// When a flow silent since `last_seen` is closed; compared with the same value that
// next_deadline() gives, so that a wake at it always acts.
double idle_flow_end(double last_seen) {
  return std::nextafter(last_seen + kIdleFlow, std::numeric_limits<double>::infinity());
}

bool listed(const std::vector<std::uint16_t>& ports, std::uint16_t port) {
  return std::find(ports.begin(), ports.end(), port) != ports.end();
}

// The gateway's side of a new flow: the one on a --port; else the side a TCP handshake was
// addressed to; else the lower port (gateways listen on fixed low ports, clients use high
// ephemeral ones). nullopt when --port is given and neither side is on it.
std::optional<Endpoint> slave_side(const Segment& s, const std::vector<std::uint16_t>& ports) {
  if (!ports.empty()) {
    if (listed(ports, s.destination.port)) return s.destination;
    if (listed(ports, s.source.port)) return s.source;
    return std::nullopt;
  }
  if (s.transport == Transport::Tcp && (s.flags & tcp_flag::kSyn) != 0) {
    return (s.flags & tcp_flag::kAck) != 0 ? s.source : s.destination;
  }
  return s.source.port < s.destination.port ? s.source : s.destination;
}

}  // namespace

GatewayTraffic::GatewayTraffic(GatewayOptions options, BusProvider& buses)
    : options_(std::move(options)), buses_(buses) {}

GatewayTraffic::~GatewayTraffic() = default;

GatewayTraffic::FlowKey GatewayTraffic::key_of(const Segment& s) {
  const bool source_first = s.source < s.destination;
  return FlowKey{s.transport, source_first ? s.source : s.destination,
                 source_first ? s.destination : s.source};
}

bool GatewayTraffic::in_last_flow(const Segment& s) const {
  const auto same = same_endpoint;
  const Endpoint& low = std::get<1>(last_key_);
  const Endpoint& high = std::get<2>(last_key_);
  return s.transport == std::get<0>(last_key_) &&
         ((same(s.source, low) && same(s.destination, high)) ||
          (same(s.source, high) && same(s.destination, low)));
}

GatewayTraffic::Connection* GatewayTraffic::find_or_open(const Segment& s) {
  const bool syn = (s.flags & tcp_flag::kSyn) != 0;
  // Packets of one flow come in runs: no key is built for them.
  if (last_flow_ != nullptr && !syn && in_last_flow(s)) return last_flow_;
  const FlowKey key = key_of(s);
  auto it = flows_.find(key);
  const bool syn_only = s.transport == Transport::Tcp &&
                        (s.flags & (tcp_flag::kSyn | tcp_flag::kAck)) == tcp_flag::kSyn;
  if (it != flows_.end() && syn_only &&
      it->second->streams.stream(Direction::ToSlave).stats().delivered_bytes > 0) {
    close(it, 0.0);  // the same ports reused for a new connection
    it = flows_.end();
  }
  if (it != flows_.end()) {
    last_flow_ = it->second.get();
    last_key_ = key;
    return last_flow_;
  }
  // Flows are opened by data or a handshake; a stray ACK or FIN of a closed flow opens none.
  const bool opens = !s.payload.empty() || (s.flags & tcp_flag::kSyn) != 0 || s.payload_on_wire > 0;
  if (!opens) return nullptr;
  const std::optional<Endpoint> slave = slave_side(s, options_.ports);
  // A flow on a --port is still probed: its first bytes say whether a logger stick wraps it.
  const bool listed = !options_.ports.empty();
  const Endpoint side = slave ? *slave : s.destination;
  auto connection =
      std::make_unique<Connection>(s.transport, side, slave.has_value(), listed, options_, buses_);
  last_flow_ = flows_.emplace(key, std::move(connection)).first->second.get();
  last_key_ = key;
  return last_flow_;
}

void GatewayTraffic::on_segment(const Segment& segment, double time) {
  if (time - last_expiry_ >= kExpiryInterval) expire_old_state(time, false);
  Connection* c = find_or_open(segment);
  if (c == nullptr) return;
  c->on_segment(segment, time);
  if (c->streams.ended()) close(flows_.find(key_of(segment)), time);
}

void GatewayTraffic::close(std::map<FlowKey, std::unique_ptr<Connection>>::iterator it,
                           double time) {
  Connection& c = *it->second;
  c.finish(time);
  c.add_stats(closed_);
  if (last_flow_ == &c) last_flow_ = nullptr;
  flows_.erase(it);
}

void GatewayTraffic::expire_old_state(double now, bool live) {
  last_expiry_ = now;
  for (auto it = flows_.begin(); it != flows_.end();) {
    Connection& c = *it->second;
    // A file's flows move their carriers' time with their own bytes only, so that one flow's
    // packets do not change when another's held requests go on.
    if (live) {
      c.idle(now);
    } else {
      c.streams.expire(now);
    }
    const auto next = std::next(it);
    if (now >= idle_flow_end(c.last_seen)) close(it, now);
    it = next;
  }
}

void GatewayTraffic::idle(double now) {
  const std::optional<double> due = next_deadline();
  if (due && now >= *due) expire_old_state(now, true);
}

std::optional<double> GatewayTraffic::next_deadline() const {
  std::optional<double> earliest;
  for (const auto& entry : flows_) {
    const Connection& c = *entry.second;
    double due = idle_flow_end(c.last_seen);
    if (const std::optional<double> held = c.next_deadline()) due = std::min(due, *held);
    if (!earliest || due < *earliest) earliest = due;
  }
  return earliest;
}

void GatewayTraffic::finish(double time) {
  while (!flows_.empty()) close(flows_.begin(), time);
}

NetworkStats GatewayTraffic::stats() const {
  NetworkStats s = closed_;
  for (const auto& entry : flows_) entry.second->add_stats(s);
  return s;
}

}  // namespace pvtap::analyzer
