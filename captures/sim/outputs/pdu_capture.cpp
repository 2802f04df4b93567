#include "outputs/capture_outputs.h"
#include "pvtap/pcap/exported_pdu_writer.h"

namespace pvtap::sim {

std::string write_pdu_capture(const BusTimeline& timeline, const std::string& path) {
  // The capture library's writer is the one definition of pvtap's link-type-252 records.
  ExportedPduWriter writer;
  if (!writer.open(path)) return writer.error();
  for (const BusEvent& e : timeline.events) {
    // The record's time is the frame's last byte (dissector/README.md). Nobody sends noise,
    // so its records carry no direction.
    const double time = static_cast<double>(e.end) / 1e6;
    if (e.kind == BusEvent::Kind::Noise) {
      writer.write_noise(time, Direction::Unknown, e.bytes);
    } else {
      writer.write_frame(time, e.role, e.bytes);
    }
  }
  return writer.close() ? std::string{} : writer.error();
}

}  // namespace pvtap::sim
