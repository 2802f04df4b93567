// InputRecords: the records of the input being read, by its link type: what each brings (bus
// bytes or a gateway flow's segment), what was skipped, and how its bytes reach pvtap.
#pragma once

#include <cstdint>
#include <optional>

#include "pvtap/framing/bus_chunk.h"
#include "pvtap/pcap/capture_file.h"
#include "pvtap/pcap/link_types.h"
#include "pvtap/pcap/network_packet.h"
#include "pvtap/pcap/pvtap_record_facts.h"
#include "pvtap/session/timestamping.h"
#include "report/audit_report.h"

namespace pvtap::analyzer {

// SerialBytes: what a record brings the one serial bus.
struct SerialBytes {
  InputKind kind = InputKind::Serial;  // decides the bus's timing when this record makes it
  bool lost_before = false;            // bytes of unknown count were lost before these
  BusChunk chunk;
  std::uint64_t lost_after = 0;  // the record's tail, cut by the capture's snap length
  // A record pvtap wrote: the values of its tags (exported_pdu_reader.h) with its bounds and
  // times as the run that wrote it decided them, and that run's settings and bus; empty in
  // files of older versions and of other writers.
  std::span<const std::uint8_t> decided;
  std::span<const std::uint8_t> run;
};

class InputRecords {
 public:
  // Records of the next input have this link type; `batched_serial`: its serial records are
  // read chunks (timestamps batched), not one character each. Only the input that makes the
  // serial bus decides how it reads its timestamps (`serial_timing_open`).
  // `direction`: who sent the bytes of its serial records (Unknown on a 2-wire tap).
  void begin(int link_type, bool batched_serial, bool serial_timing_open,
             Direction direction = Direction::Unknown);
  // Records of IP packets: a segment of a TCP/UDP flow is read into `segment` (spans point
  // into the record); false when the record was skipped, and counted. The segment is the
  // caller's, so that the audit's hot path copies none.
  bool is_network() const { return kind_ == InputKind::Network; }
  bool network_packet(const CapturedPacket& packet, Segment& segment);
  // Records of the serial bus: its bytes; nullopt when the record was skipped, and counted.
  std::optional<SerialBytes> serial_bytes(const CapturedPacket& packet);
  // How the bytes of that kind of input reach pvtap, for what their timestamps prove.
  Timestamping timestamping_of(InputKind kind, bool has_timestamps) const;

  // An input of IP packets was read.
  bool network() const { return network_; }
  const SkippedRecords& skipped() const { return skipped_; }

 private:
  std::optional<SerialBytes> exported_pdu(const CapturedPacket& packet);
  std::optional<SerialBytes> rtac_record(const CapturedPacket& packet);

  int link_type_ = -1;
  InputKind kind_ = InputKind::Serial;
  bool batched_serial_ = false;
  Direction serial_direction_ = Direction::Unknown;
  bool network_ = false;
  SkippedRecords skipped_;
};

}  // namespace pvtap::analyzer
