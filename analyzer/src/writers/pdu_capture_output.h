// PduCaptureOutput: --write: every serial frame and noise run of every bus into a pcap of link
// type 252 (exported PDUs) for Wireshark with pvtap's plugin, and for pvtap audit to give the
// same verdicts again.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

#include "events/event_writer.h"
#include "pvtap/pcap/exported_pdu_writer.h"

namespace pvtap::analyzer {

class PduCaptureOutput : public EventWriter {
 public:
  // Creates the file; false with error() set when it cannot be written. `flush_each_record`
  // for live captures: an abrupt end then loses nothing, and a reader sees frames at once.
  // Every record carries its own bounds and times, and `run` (with the event's bus) goes with
  // the first record of a bus and wherever the bus changes.
  bool open(const std::string& path, bool flush_each_record, const RunFacts& run);
  // The run's clock last read `time`: requests still waiting then were judged by it. A file
  // without a record needs no end (a quiet bus leaves the file as it was).
  void end_of_input(double time) {
    if (file_.records() > 0) file_.write_end(time);
  }
  bool close();
  const std::string& error() const { return file_.error(); }
  std::uint64_t records() const { return file_.records(); }

  void frame(const EventContext& c, const SessionFrame& f) override {
    // A Modbus/TCP frame has no CRC: as a serial record it would read back as noise, and a
    // CRC added here was never on the wire. The capture itself is its record (invmbap).
    if (f.check.carried) return;
    const RecordFacts facts{RecordKind::Frame, f.direction, f.start_time, f.end_time, {}};
    file_.write_record(facts, run_for(c.bus),
                       f.role == Role::Request ? Direction::ToSlave : Direction::FromSlave,
                       f.bytes);
  }
  void noise(const EventContext& c, const SessionNoise& n) override {
    const RecordFacts facts{
        RecordKind::Noise, n.direction, n.noise.start_time, n.noise.end_time, {}};
    file_.write_record(facts, run_for(c.bus), n.direction, n.noise.bytes);
  }
  void timeout(const EventContext&, const SessionTimeout&) override {}
  void gap(const EventContext& c, const SessionGap& g) override {
    file_.write_loss(g.time, g.direction, g.lost_bytes, run_for(c.bus));
  }

 private:
  // The run's tag goes with a bus's first record and wherever the bus changes: a reader takes
  // a record without it to be on the bus of the one before.
  const RunFacts* run_for(std::string_view bus) {
    if (written_any_ && bus == bus_) return nullptr;
    written_any_ = true;
    bus_.assign(bus);
    run_.bus = bus_;
    return &run_;
  }

  ExportedPduWriter file_;
  RunFacts run_;
  std::string bus_;  // of the last record written
  bool written_any_ = false;
};

}  // namespace pvtap::analyzer
