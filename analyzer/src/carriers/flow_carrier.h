// FlowCarrier: what a gateway flow's ordered bytes become once its probe has decided, one
// implementation per carrier, chosen once by the verdict.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>

#include "carriers/bus_provider.h"
#include "carriers/flow_streams.h"
#include "pvtap/carriers/flow_probe.h"
#include "report/network_stats.h"

namespace pvtap::analyzer {

// Bytes in (FlowBytes: data and gaps per direction, in stream order), bus events out. A
// carrier is fed the probe's held bytes first, then the flow's own, exactly once each.
class FlowCarrier : public FlowBytes {
 public:
  virtual ~FlowCarrier() = default;

  // End of the flow: bytes still held are decided, both turns end.
  virtual void finish(double time) = 0;
  // A live capture: nothing arrived until `now`; what has waited long enough goes on.
  virtual void idle(double now) { static_cast<void>(now); }
  // When idle() can next decide something; nullopt when only more bytes can.
  virtual std::optional<double> next_deadline() const { return std::nullopt; }
  // Whether the flow's bytes were analyzed (its losses count as the bus's).
  virtual bool analyzed() const { return true; }
  // Its counts: flows analyzed or ignored, and what its carrier found.
  virtual void add_stats(NetworkStats& into) const = 0;
};

// What a decided flow needs: its streams (whose holes a bare bus's turns wait for), where its
// bus comes from, and the matcher's reply timeout.
struct CarrierContext {
  const FlowStreams& streams;
  BusProvider& buses;
  double reply_timeout;
};

// The carrier for a probe's verdict (Undecided and NotBus: the flow is ignored; its
// `ignored_bytes` are the probe's, already seen).
std::unique_ptr<FlowCarrier> make_carrier(FlowProbe::Verdict verdict, const CarrierContext& c,
                                          std::uint64_t ignored_bytes);

}  // namespace pvtap::analyzer
