// AuditRun's buses: one BusSession per gateway (or one for a serial capture), and where their
// events go: latency statistics, the --write file and the chosen output format.
#include "audit_bus.h"
#include "pvtap/carrier_timing.h"

namespace pvtap::analyzer {

BusSessionOptions AuditRun::session_options(InputKind kind) const {
  BusSessionOptions o;
  o.reassembler.dialects = options_.dialects;
  o.reassembler.baud = options_.baud;
  o.matcher.timeout = options_.timeout;
  o.decode_values = !options_.summary_only;
  CarrierTiming carrier{Carrier::SerialCharacters, options_.gateway_gap_ms / 1000.0, {}};
  if (kind == InputKind::Network) carrier.carrier = Carrier::GatewaySegments;
  if (kind == InputKind::Serial && batched_serial_records_)
    carrier.carrier = Carrier::SerialBatches;
  if (kind == InputKind::ExportedPdu) carrier.carrier = Carrier::ExportedPdus;
  if (!options_.raw_dumps.empty()) carrier.carrier = Carrier::PlainDump;
  apply_carrier_timing(carrier, o);
  return o;
}

AuditRun::Bus& AuditRun::bus_named(const std::string& name, InputKind kind) {
  const auto it = bus_by_name_.find(name);
  if (it != bus_by_name_.end()) return *it->second;
  return add_bus(name, session_options(kind));
}

AuditRun::Bus& AuditRun::add_bus(const std::string& name, const BusSessionOptions& options) {
  buses_.push_back(std::make_unique<Bus>(*this, name, options, decoder_));
  bus_by_name_[name] = buses_.back().get();
  return *buses_.back();
}

BusSession& AuditRun::gateway_bus(const Endpoint& slave_side) {
  return bus_named(slave_side.to_string(), InputKind::Network).session;
}

BusSession& AuditRun::serial_bus(InputKind kind) {
  return bus_named("", kind).session;
}

void AuditRun::on_frame(const EventContext& c, const SessionFrame& f) {
  ++frames_seen_;
  if (f.latency) {
    latency_.add(*f.latency);
    last_latency_ = f.latency;
  }
  if (writer_) writer_->write_frame(f.end_time, f.role, f.bytes);
  if (events_) events_->frame(c, f);
}

void AuditRun::on_noise(const EventContext& c, const SessionNoise& n) {
  if (writer_) writer_->write_noise(n.noise.end_time, n.direction, n.noise.bytes);
  if (events_) events_->noise(c, n);
}

void AuditRun::finish_all(double time) {
  gateway_.finish(time);
  for (auto& bus : buses_) bus->session.finish();
}

AuditReport AuditRun::build_report() const {
  AuditReport r;
  r.settings.baud = options_.baud;
  r.settings.timeout = options_.timeout;
  r.settings.has_timestamps = options_.raw_dumps.empty();
  r.settings.gsl_ids = options_.gsl_ids;
  r.inputs = inputs_;
  for (const auto& bus : buses_) {
    r.buses.push_back(BusFindings{bus->output.name(), bus->session.report()});
  }
  r.network = network_;
  r.flows = gateway_.stats();
  r.skipped = skipped_;
  r.latency = latency_.summary();
  r.written_records = writer_ ? writer_->records() : 0;
  r.live = live_;
  return r;
}

bool AuditRun::has_findings(const AuditReport& report) const {
  const BusReport t = report.totals();
  return t.bytes.bad_frames > 0 || t.timeouts > 0 || t.exceptions > 0;
}

}  // namespace pvtap::analyzer
