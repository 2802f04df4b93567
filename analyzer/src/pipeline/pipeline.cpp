#include "pipeline/pipeline.h"

#include <algorithm>

#include "pvtap/pcap/exported_pdu_reader.h"
#include "pvtap/session/timestamping.h"
#include "pvtap/statistics/bus_timing.h"

namespace pvtap::analyzer {
namespace {

void feed(BusSession& bus, const SerialBytes& serial) {
  const double time = serial.chunk.time;
  const Direction direction = serial.chunk.direction;
  if (serial.lost_before) bus.data_lost(direction, time, std::nullopt);
  bus.feed(serial.chunk);
  if (serial.lost_after > 0) bus.data_lost(direction, time, serial.lost_after);
}

}  // namespace

Pipeline::Pipeline(const PipelineSettings& settings, const RegisterDecoder& decoder,
                   EventWriter& events)
    : settings_(settings),
      buses_(decoder, events, settings.from_recording_start),
      gateway_(GatewayOptions{settings.ports, settings.dialects, 2.0, settings.timeout}, *this) {}

void Pipeline::begin_input(int link_type, bool batched_serial, Direction direction) {
  input_.begin(link_type, batched_serial, serial_timing_open(), direction);
}

void Pipeline::record(const CapturedPacket& packet) {
  if (input_.is_network()) {
    Segment segment;
    if (input_.network_packet(packet, segment)) gateway_.on_segment(segment, packet.time);
  } else if (const std::optional<SerialBytes> serial = input_.serial_bytes(packet)) {
    if (const std::optional<RecordFacts> decided = record_facts(serial->decided)) {
      decided_record(*serial, *decided);
    } else if (serial->kind == InputKind::ExportedPdu) {
      exported_pdu(*serial);
    } else {
      feed(serial_bus(serial->kind), *serial);
    }
  }
}

// A record for pvtap's dissector without pvtap's tags (an older version, the simulator, another
// writer): by its format one frame or one noise run, stamped at its last byte. Its ends are
// pinned, so that noise between two frames stays its own run and a damaged frame does not wait
// for bytes of its direction; its start is taken one character time per byte before its end.
void Pipeline::exported_pdu(const SerialBytes& serial) {
  const BusChunk& c = serial.chunk;
  const double start =
      c.time - static_cast<double>(c.bytes.size()) * BusTiming(settings_.baud).char_time;
  BusSession& bus = serial_bus(serial.kind);
  if (serial.lost_before) bus.data_lost(c.direction, c.time, std::nullopt);
  bus.feed_decided(DecidedPiece{c.bytes, start, c.time, c.direction, false});
  if (serial.lost_after > 0) bus.data_lost(c.direction, c.time, serial.lost_after);
}

// A record of pvtap's own capture: a frame or noise run on its bus, as its run decided it.
void Pipeline::decided_record(const SerialBytes& serial, const RecordFacts& facts) {
  if (facts.kind == RecordKind::End) {
    // What the writing run's clock judged at its end, this run judges too.
    buses_.idle(facts.end_time);
    return;
  }
  // The run's tag comes with the first record of a bus and wherever the bus changes; a record
  // without it is on the bus of the record before.
  if (const std::optional<RunFacts> run = run_facts(serial.run)) {
    if (written_bus_ == nullptr || run->bus != written_bus_name_) {
      written_bus_name_.assign(run->bus);
      written_bus_ = &written_bus(run);
    }
  } else if (written_bus_ == nullptr) {
    written_bus_ = &written_bus(std::nullopt);
  }
  if (facts.kind == RecordKind::Loss) {
    written_bus_->data_lost(facts.stream, facts.end_time, facts.lost_bytes);
    return;
  }
  if (serial.lost_before) written_bus_->data_lost(facts.stream, facts.end_time, std::nullopt);
  written_bus_->feed_decided(DecidedPiece{serial.chunk.bytes, facts.start_time, facts.end_time,
                                          facts.stream, facts.kind == RecordKind::Noise});
  if (serial.lost_after > 0) {
    written_bus_->data_lost(facts.stream, facts.end_time, serial.lost_after);
  }
}

// The bus a record of pvtap's own capture names, made with the settings of the run that wrote
// it where the command line gave none.
BusSession& Pipeline::written_bus(const std::optional<RunFacts>& run) {
  if (BusSession* bus = buses_.find(written_bus_name_)) return *bus;
  if (run) {
    if (!settings_.given.dialects) settings_.dialects = run->dialects;
    if (!settings_.given.baud) settings_.baud = run->baud;
    if (!settings_.given.timeout) settings_.timeout = run->timeout;
  }
  return buses_.add(written_bus_name_, bus_options(InputKind::ExportedPdu));
}

BusSessionOptions Pipeline::bus_options(InputKind kind) const {
  return session_options_for(input_.timestamping_of(kind, settings_.has_timestamps));
}

BusSessionOptions Pipeline::session_options_for(Timestamping timestamping) const {
  BusSessionOptions o;
  o.reassembler.dialects = settings_.dialects;
  o.reassembler.baud = settings_.baud;
  o.matcher.timeout = settings_.timeout;
  o.decode_values = settings_.decode_values;
  o.infer_registers = settings_.infer_registers;
  apply_timestamping(TimestampFacts{timestamping, settings_.gateway_gap_ms / 1000.0, {}}, o);
  return o;
}

BusSession& Pipeline::add_bus(const std::string& name, const BusSessionOptions& options) {
  return buses_.add(name, options);
}

BusSession& Pipeline::gateway_bus(const std::string& name) {
  return buses_.find_or_add(name, bus_options(InputKind::Network));
}

BusSession& Pipeline::logger_bus(const std::string& name) {
  return buses_.find_or_add(name, session_options_for(Timestamping::LoggerStickFrames));
}

// A capture of serial records or a plain dump names no device: its one bus is "serial", as
// the report calls it, so that every event and value row says its bus.
BusSession& Pipeline::serial_bus(InputKind kind) {
  if (BusSession* bus = buses_.find(kSerialBusName)) return *bus;
  return buses_.add(kSerialBusName, bus_options(kind));
}

void Pipeline::begin_raw_input() {
  serial_bus(InputKind::Serial);
}

void Pipeline::raw_bytes(std::span<const std::uint8_t> bytes) {
  serial_bus(InputKind::Serial).feed(BusChunk{bytes, 0.0, Direction::Unknown});
}

void Pipeline::idle(double now) {
  // Bytes a hole held back reach their bus first, so that the bus judges them at `now` too.
  gateway_.idle(now);
  buses_.idle(now);
}

std::optional<double> Pipeline::next_deadline() const {
  const std::optional<double> buses = buses_.next_deadline();
  const std::optional<double> flows = gateway_.next_deadline();
  if (buses && flows) return std::min(*buses, *flows);
  return buses ? buses : flows;
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
  r.settings.all_dialects = settings_.dialects == DialectSet::all();
  r.settings.ports_given = !settings_.ports.empty();
  r.buses = buses_.findings();
  r.network = input_.network();
  r.flows = gateway_.stats();
  r.skipped = input_.skipped();
  r.latency = buses_.tally().latency().summary();
  return r;
}

}  // namespace pvtap::analyzer
