#include "carriers/gateway_connection.h"

#include <algorithm>

namespace pvtap::analyzer {

GatewayTraffic::Connection::Connection(Transport t, const Endpoint& slave_side, State initial,
                                       bool listed, const GatewayOptions& o,
                                       BusProvider& bus_provider)
    : state(initial),
      buses(bus_provider),
      probe(o.dialects, listed),
      v5(bus_provider, o.reply_timeout),
      streams(t, slave_side, o.hole_wait, *this),
      reply_timeout(o.reply_timeout) {
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
    case State::Mbap:
      feed_bus(d, bytes, time);
      return;
    case State::SolarmanV5:
      v5.data(d, bytes, time);
      return;
    case State::Ignored:
      ignored_bytes += bytes.size();
      return;
    case State::Probing:
      break;
  }
  const FlowProbe::Verdict v = probe.add_data(d, bytes, time);
  if (v == FlowProbe::Verdict::Bus) become_bus();
  if (v == FlowProbe::Verdict::Mbap) become_mbap();
  if (v == FlowProbe::Verdict::SolarmanV5) become_v5();
  if (v == FlowProbe::Verdict::NotBus) become_ignored();
}

void GatewayTraffic::Connection::gap(Direction d, std::uint64_t lost, double time) {
  if (state == State::Bus || state == State::Mbap) {
    if (mbap) mbap->data_lost(d, time);
    bus->data_lost(d, time, lost);
  } else if (state == State::SolarmanV5) {
    v5.gap(d, lost, time);
  } else if (state == State::Probing) {
    probe.add_gap(d, lost, time);
  }
}

void GatewayTraffic::Connection::feed_bus(Direction d, std::span<const std::uint8_t> bytes,
                                          double time) {
  if (mbap) {
    mbap->feed(d, bytes, time);
    return;
  }
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
  replay_probe();
}

void GatewayTraffic::Connection::become_mbap() {
  // The bus is named after the gateway endpoint, as a serial gateway's is.
  bus = &buses.gateway_bus(streams.slave().to_string());
  state = State::Mbap;
  mbap = std::make_unique<MbapFlow>(*bus, reply_timeout);
  replay_probe();
}

void GatewayTraffic::Connection::replay_probe() {
  for (const FlowProbe::Item& item : probe.items()) {
    if (item.gap) {
      gap(item.direction, item.lost, item.time);
    } else {
      feed_bus(item.direction, item.bytes, item.time);
    }
  }
  probe.clear();
}

void GatewayTraffic::Connection::become_v5() {
  state = State::SolarmanV5;
  for (const FlowProbe::Item& item : probe.items()) {
    if (item.gap) {
      v5.gap(item.direction, item.lost, item.time);
    } else {
      v5.data(item.direction, item.bytes, item.time);
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
    switch (probe.final_verdict()) {
      case FlowProbe::Verdict::Bus:
        become_bus();
        break;
      case FlowProbe::Verdict::Mbap:
        become_mbap();
        break;
      default:
        become_ignored();
    }
  }
  if (state == State::Mbap) mbap->finish(time);
  if (state == State::Bus) {
    bus->end_turn(Direction::ToSlave);
    bus->end_turn(Direction::FromSlave);
  }
  if (state == State::SolarmanV5) v5.finish(time);
}

void GatewayTraffic::Connection::add_stats(NetworkStats& into) const {
  const bool analyzed = state != State::Ignored && state != State::Probing;
  if (analyzed) ++into.flows_analyzed;
  if (state == State::Ignored) ++into.flows_ignored;
  into.ignored_bytes += ignored_bytes;
  streams.add_stats(into, analyzed);
  if (state == State::SolarmanV5) {
    ++into.v5_flows;
    into.v5 += v5.totals();
    std::vector<std::string>& said = into.v5_finding_examples;
    for (const std::string& e : v5.finding_examples()) {
      if (said.size() >= NetworkStats::kMaxExamples) break;
      // Each connection of a client with a wrong serial is refused alike: said once.
      if (std::find(said.begin(), said.end(), e) == said.end()) said.push_back(e);
    }
  }
  if (!mbap) return;
  const MbapTotals t = mbap->totals();
  ++into.mbap_flows;
  into.mbap_adus += t.adus;
  into.mbap_carrier_bytes += t.carrier_bytes;
  into.mbap_findings += t.findings;
  into.mbap_skipped_bytes += t.skipped_bytes;
  for (const MbapFinding& f : mbap->finding_examples()) {
    if (into.mbap_finding_examples.size() >= NetworkStats::kMaxExamples) break;
    into.mbap_finding_examples.push_back(streams.slave().to_string() + ": " + describe(f));
  }
}

}  // namespace pvtap::analyzer
