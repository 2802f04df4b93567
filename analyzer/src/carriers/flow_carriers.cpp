// The carriers of a gateway flow: bare serial frames, Modbus/TCP ADUs, a logger stick's
// Solarman V5 frames, or none.
#include <algorithm>
#include <string>

#include "carriers/flow_carrier.h"
#include "carriers/solarman_v5_flow.h"
#include "pvtap/carriers/mbap_flow.h"

namespace pvtap::analyzer {
namespace {

// Serial frames as the gateway passes them on, on the bus named after the gateway endpoint.
class BareBusCarrier final : public FlowCarrier {
 public:
  explicit BareBusCarrier(const CarrierContext& c)
      : streams_(c.streams), bus_(c.buses.gateway_bus(c.streams.slave().to_string())) {
    // A new connection starts new streams: nothing of the previous one may join its bytes.
    bus_.restart(Direction::ToSlave);
    bus_.restart(Direction::FromSlave);
  }
  void data(Direction d, std::span<const std::uint8_t> bytes, double time) override {
    // The other side's turn is not over while some of its bytes are still missing (a hole
    // waiting for a retransmission).
    bus_.feed(BusChunk{bytes, time, d, streams_.other_complete(d)});
  }
  void gap(Direction d, std::uint64_t lost, double time) override { bus_.data_lost(d, time, lost); }
  void finish(double) override {
    bus_.end_turn(Direction::ToSlave);
    bus_.end_turn(Direction::FromSlave);
  }
  void add_stats(NetworkStats& into) const override { ++into.flows_analyzed; }

 private:
  const FlowStreams& streams_;
  BusSession& bus_;
};

// Modbus/TCP: the unit id and PDU of each ADU are the frames, paired by transaction id.
class MbapCarrier final : public FlowCarrier {
 public:
  explicit MbapCarrier(const CarrierContext& c)
      : name_(c.streams.slave().to_string()),
        bus_(c.buses.gateway_bus(name_)),  // named after the gateway endpoint, as a serial one
        flow_(bus_, c.reply_timeout) {}
  void data(Direction d, std::span<const std::uint8_t> bytes, double time) override {
    flow_.feed(d, bytes, time);
  }
  void gap(Direction d, std::uint64_t lost, double time) override {
    flow_.data_lost(d, time);
    bus_.data_lost(d, time, lost);
  }
  void finish(double time) override { flow_.finish(time); }
  void idle(double now) override { flow_.idle(now); }
  std::optional<double> next_deadline() const override { return flow_.next_deadline(); }
  void add_stats(NetworkStats& into) const override;

 private:
  std::string name_;
  BusSession& bus_;
  MbapFlow flow_;
};

void MbapCarrier::add_stats(NetworkStats& into) const {
  ++into.flows_analyzed;
  const MbapTotals t = flow_.totals();
  ++into.mbap_flows;
  into.mbap_adus += t.adus;
  into.mbap_carrier_bytes += t.carrier_bytes;
  into.mbap_findings += t.findings;
  into.mbap_skipped_bytes += t.skipped_bytes;
  for (const MbapFinding& f : flow_.finding_examples()) {
    if (into.mbap_finding_examples.size() >= NetworkStats::kMaxExamples) break;
    into.mbap_finding_examples.push_back(name_ + ": " + describe(f));
  }
}

// Not a gateway's flow: its bytes are counted, nothing more.
class IgnoredCarrier final : public FlowCarrier {
 public:
  explicit IgnoredCarrier(std::uint64_t seen) : bytes_(seen) {}
  void data(Direction, std::span<const std::uint8_t> bytes, double) override {
    bytes_ += bytes.size();
  }
  void gap(Direction, std::uint64_t, double) override {}
  void finish(double) override {}
  bool analyzed() const override { return false; }
  void add_stats(NetworkStats& into) const override {
    ++into.flows_ignored;
    into.ignored_bytes += bytes_;
  }

 private:
  std::uint64_t bytes_;
};

}  // namespace

std::unique_ptr<FlowCarrier> make_carrier(FlowProbe::Verdict verdict, const CarrierContext& c,
                                          std::uint64_t ignored_bytes) {
  switch (verdict) {
    case FlowProbe::Verdict::Bus:
      return std::make_unique<BareBusCarrier>(c);
    case FlowProbe::Verdict::Mbap:
      return std::make_unique<MbapCarrier>(c);
    case FlowProbe::Verdict::SolarmanV5:
      return std::make_unique<SolarmanV5Flow>(c.buses, c.reply_timeout);
    case FlowProbe::Verdict::Undecided:
    case FlowProbe::Verdict::NotBus:
      break;
  }
  return std::make_unique<IgnoredCarrier>(ignored_bytes);
}

}  // namespace pvtap::analyzer
