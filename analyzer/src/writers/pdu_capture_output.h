// PduCaptureOutput: --write: every serial frame and noise run of every bus into a pcap of link
// type 252 (exported PDUs) for Wireshark with pvtap's plugin.
#pragma once

#include <cstdint>
#include <string>

#include "events/event_writer.h"
#include "pvtap/capture/exported_pdu_writer.h"

namespace pvtap::analyzer {

class PduCaptureOutput : public EventWriter {
 public:
  // Creates the file; false with error() set when it cannot be written. `flush_each_record`
  // for live captures: an abrupt end then loses nothing, and a reader sees frames at once.
  bool open(const std::string& path, bool flush_each_record);
  bool close();
  const std::string& error() const { return file_.error(); }
  std::uint64_t records() const { return file_.records(); }

  void frame(const EventContext&, const SessionFrame& f) override {
    // A Modbus/TCP frame has no CRC: as a serial record it would read back as noise, and a
    // CRC added here was never on the wire. The capture itself is its record (invmbap).
    if (f.check.carried) return;
    file_.write_frame(f.end_time, f.role, f.bytes);
  }
  void noise(const EventContext&, const SessionNoise& n) override {
    file_.write_noise(n.noise.end_time, n.direction, n.noise.bytes);
  }
  void timeout(const EventContext&, const SessionTimeout&) override {}
  void gap(const EventContext&, const SessionGap&) override {}

 private:
  ExportedPduWriter file_;
};

}  // namespace pvtap::analyzer
