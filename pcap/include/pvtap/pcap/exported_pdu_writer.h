// ExportedPduWriter: writes frames and noise runs as a pcap of link type 252 (Wireshark's
// exported PDUs), one per record, tagged with the dissector name "pvtap" and the direction,
// so that Wireshark with pvtap's plugin shows the file with no set-up (record format:
// dissector/README.md).
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>

#include "pvtap/codec/dialect.h"
#include "pvtap/framing/bus_chunk.h"
#include "pvtap/pcap/exported_pdu_tags.h"
#include "pvtap/pcap/pcap_writer.h"
#include "pvtap/pcap/pvtap_record_facts.h"

namespace pvtap {

class ExportedPduWriter {
 public:
  // Creates the file; false with error() set when it cannot be written.
  bool open(const std::string& path);
  // A frame: a request goes out as "sent" (master to slave), a response as "received".
  void write_frame(double time, Role role, std::span<const std::uint8_t> frame);
  // A noise run; its direction tag is left out when the direction is unknown.
  void write_noise(double time, Direction direction, std::span<const std::uint8_t> noise);
  // A frame or noise run as a pvtap run decided it, with what a later audit needs to give
  // that run's verdicts (pvtap_record_facts.h): stamped at its last byte, direction tag
  // `direction` (a frame's role, a noise run's stream); the run's tag when `run` is given (a
  // bus name of at most kMaxBusName bytes).
  void write_record(const RecordFacts& facts, const RunFacts* run, Direction direction,
                    std::span<const std::uint8_t> bytes);
  static constexpr std::size_t kMaxBusName = 1024;
  // The run ended at `time`, the last its clock read: a record without bytes.
  void write_end(double time);
  // Capture data of `stream` was lost at `time` (`lost_bytes` when known): a record without
  // bytes.
  void write_loss(double time, Direction stream, std::optional<std::uint64_t> lost_bytes,
                  const RunFacts* run);
  // Live capture: every record reaches the file as it is written, so that a reader (Wireshark
  // on a fifo) sees frames at once and an abrupt end loses nothing. The file header goes out
  // at once too: Wireshark waits for it before it counts down `-a duration` or shows anything.
  void flush_each_record(bool on) {
    flush_each_record_ = on;
    if (on) file_.flush();
  }
  // Flushes and closes; false when writing failed.
  bool close();
  const std::string& error() const { return file_.error(); }
  std::uint64_t records() const { return records_; }

 private:
  PcapWriter file_;
  std::uint64_t records_ = 0;
  bool flush_each_record_ = false;
  void write(double time, Direction direction, std::span<const std::uint8_t> bytes,
             const RecordFacts* facts = nullptr, const RunFacts* run = nullptr,
             std::string_view dissector = exported_pdu::kDissectorName);
  // A record that marks a moment (kEventDissectorName), with `text` saying what it marks.
  void write_event(const RecordFacts& facts, const RunFacts* run, std::string_view text);

  // tags (a bus name included) + the largest frame or noise run, reused
  std::array<std::uint8_t, 8192> record_{};
};

}  // namespace pvtap
