// Pipeline: a run's buses fed from any source: capture records of any link type pvtap reads,
// plain byte dumps, live serial taps or a live interface. It does not know whether its source
// is a file or a device: sources hand it records or chunks with their times, and every event
// of every bus goes to the EventWriter it was given. At the end it reports what it found.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "carriers/gateway_traffic.h"
#include "events/event_writer.h"
#include "pipeline/bus_set.h"
#include "pipeline/input_records.h"
#include "pipeline/protocol_choices.h"
#include "pvtap/pcap/capture_file.h"
#include "pvtap/pcap/link_types.h"
#include "pvtap/session/bus_session.h"
#include "pvtap/session/timestamping.h"
#include "report/audit_report.h"

namespace pvtap::analyzer {

// PipelineSettings: what shapes every bus of a run.
struct PipelineSettings {
  DialectSet dialects = DialectSet::all();
  std::uint32_t baud = 9600;
  double timeout = 1.0;        // seconds a request waits for its reply
  double gateway_gap_ms = 50;  // see ReassemblerOptions::boundary_gap
  std::vector<std::uint16_t> ports;
  bool decode_values = true;          // per-frame values for the output (not for --summary-only)
  bool infer_registers = true;        // the report's inferred blocks (every report shows them)
  bool has_timestamps = true;         // false for plain dumps
  bool from_recording_start = false;  // a logic recording's sample clock, no wall clock
  GslIdReading gsl_ids = GslIdReading::Decimal;  // for the report's wording
  ProtocolChoices given;
};

// The bus of a capture of serial records or a plain dump, which names no device.
inline constexpr const char* kSerialBusName = "serial";

// A gateway flow gets its bus from the pipeline (BusProvider): one bus per gateway endpoint.
class Pipeline : private BusProvider {
 public:
  // Every event goes to `events`, after its bus has counted it.
  Pipeline(const PipelineSettings& settings, const RegisterDecoder& decoder, EventWriter& events);

  // Records of the next input have this link type; `batched_serial`: its serial records are
  // read chunks (timestamps batched), not one character each; `direction`: who sent the bytes
  // of its serial records (one pair of a 4-wire bus), Unknown on a 2-wire bus.
  void begin_input(int link_type, bool batched_serial, Direction direction = Direction::Unknown);
  // True until the one serial bus exists: only the first serial input decides its timing, so
  // later inputs need not be probed for it.
  bool serial_timing_open() const { return buses_.find("") == nullptr; }
  void record(const CapturedPacket& packet);
  // A plain dump of bus bytes follows (--raw): its bus is reported even when it is empty.
  void begin_raw_input();
  // Bus bytes without time (--raw).
  void raw_bytes(std::span<const std::uint8_t> bytes);
  // A bus fed by its source directly (a serial tap).
  BusSession& add_bus(const std::string& name, const BusSessionOptions& options);
  BusSessionOptions bus_options(InputKind kind) const;

  // Live sources: every bus and every gateway flow has been silent until `now`.
  void idle(double now);
  // When the buses or the gateway flows can next decide something while silent (see
  // BusSession::next_deadline and GatewayTraffic::next_deadline).
  std::optional<double> next_deadline() const;
  // End of input at `time`: every byte decided, every waiting request judged.
  void finish(double time);

  // The buses, for what they counted so far (tally(), counts(), totals()).
  const BusSet& buses() const { return buses_; }
  // The report of what was found; the caller adds its inputs, --write and live sources.
  AuditReport report() const;

 private:
  BusSession& serial_bus(InputKind kind);
  void exported_pdu(const SerialBytes& serial);
  void decided_record(const SerialBytes& serial, const RecordFacts& facts);
  BusSession& written_bus(const std::optional<RunFacts>& run);
  BusSessionOptions session_options_for(Timestamping timestamping) const;
  BusSession& gateway_bus(const std::string& name) override;
  BusSession& logger_bus(const std::string& name) override;

  PipelineSettings settings_;
  BusSet buses_;
  GatewayTraffic gateway_;
  InputRecords input_;
  // The bus of the last record of pvtap's own capture, and its name.
  BusSession* written_bus_ = nullptr;
  std::string written_bus_name_;
};

}  // namespace pvtap::analyzer
