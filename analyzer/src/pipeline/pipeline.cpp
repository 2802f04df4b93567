#include "pipeline/pipeline.h"

#include "pvtap/session/carrier_timing.h"

namespace pvtap::analyzer {

Pipeline::Pipeline(const PipelineSettings& settings, const RegisterDecoder& decoder,
                   EventWriter& events)
    : settings_(settings),
      buses_(decoder, events),
      gateway_(GatewayOptions{settings.ports, settings.dialects, 2.0}, *this) {}

Pipeline::~Pipeline() = default;

void Pipeline::begin_input(int link_type, bool batched_serial) {
  link_type_ = link_type;
  kind_ = input_kind_of(link_type).value_or(InputKind::Serial);
  // The first input decides how the one serial bus reads its timestamps.
  if (kind_ == InputKind::Serial && serial_timing_open()) batched_serial_ = batched_serial;
  network_ = network_ || kind_ == InputKind::Network;
}

BusSessionOptions Pipeline::bus_options(InputKind kind) const {
  BusSessionOptions o;
  o.reassembler.dialects = settings_.dialects;
  o.reassembler.baud = settings_.baud;
  o.matcher.timeout = settings_.timeout;
  o.decode_values = settings_.decode_values;
  apply_carrier_timing(CarrierTiming{carrier_of(kind), settings_.gateway_gap_ms / 1000.0, {}}, o);
  return o;
}

Carrier Pipeline::carrier_of(InputKind kind) const {
  if (!settings_.has_timestamps) return Carrier::PlainDump;
  switch (kind) {
    case InputKind::Network:
      return Carrier::GatewaySegments;
    case InputKind::ExportedPdu:
      return Carrier::ExportedPdus;
    case InputKind::Serial:
      return batched_serial_ ? Carrier::SerialBatches : Carrier::SerialCharacters;
    case InputKind::RtacSerial:
      break;
  }
  return Carrier::SerialCharacters;
}

BusSession& Pipeline::add_bus(const std::string& name, const BusSessionOptions& options) {
  return buses_.add(name, options);
}

BusSession& Pipeline::gateway_bus(const std::string& name) {
  return buses_.find_or_add(name, bus_options(InputKind::Network));
}

BusSession& Pipeline::serial_bus(InputKind kind) {
  if (BusSession* bus = buses_.find("")) return *bus;
  return buses_.add("", bus_options(kind));
}

void Pipeline::begin_raw_input() {
  serial_bus(InputKind::Serial);
}

void Pipeline::raw_bytes(std::span<const std::uint8_t> bytes) {
  serial_bus(InputKind::Serial).feed(BusChunk{bytes, 0.0, Direction::Unknown});
}

void Pipeline::idle(double now) {
  buses_.idle(now);
}

void Pipeline::finish(double time) {
  gateway_.finish(time);
  buses_.finish();
}

AuditReport Pipeline::report() const {
  AuditReport r;
  r.settings.baud = settings_.baud;
  r.settings.timeout = settings_.timeout;
  r.settings.has_timestamps = settings_.has_timestamps;
  r.settings.gsl_ids = settings_.gsl_ids;
  r.buses = buses_.findings();
  r.network = network_;
  r.flows = gateway_.stats();
  r.skipped = skipped_;
  r.latency = tally().latency().summary();
  return r;
}

}  // namespace pvtap::analyzer
