// AuditRun's handling of one capture record, by the kind of input its link type makes it.
#include "audit_bus.h"
#include "audit_run.h"
#include "pvtap/capture/exported_pdu_tags.h"
#include "pvtap/capture/network_packet.h"
#include "pvtap/capture/exported_pdu_reader.h"
#include "pvtap/capture/rtac_record.h"

namespace pvtap::analyzer {

void AuditRun::on_record(InputKind kind, const CapturedPacket& packet) {
  switch (kind) {
    case InputKind::Network:
      on_network_packet(packet);
      return;
    case InputKind::ExportedPdu:
      on_exported_pdu(packet);
      return;
    case InputKind::Serial: {
      BusSession& bus = serial_bus(kind);
      bus.feed(BusChunk{packet.bytes, packet.time, Direction::Unknown});
      // The capture's snap length cut the record: its tail is lost.
      if (packet.length_on_wire > packet.bytes.size()) {
        bus.data_lost(Direction::Unknown, packet.time, packet.length_on_wire - packet.bytes.size());
      }
      return;
    }
    case InputKind::RtacSerial: {
      const auto record = rtac_serial_record(packet.bytes);
      if (!record) {
        ++skipped_.malformed;
        return;
      }
      BusSession& bus = serial_bus(kind);
      if (record->data_lost_before) bus.data_lost(Direction::Unknown, packet.time, std::nullopt);
      bus.feed(BusChunk{record->bytes, packet.time, Direction::Unknown});
      return;
    }
  }
}

void AuditRun::on_network_packet(const CapturedPacket& packet) {
  Segment segment;
  switch (decode_network_packet(link_type_, packet.bytes, segment)) {
    case PacketVerdict::Segment:
      gateway_.on_segment(segment, packet.time);
      return;
    case PacketVerdict::NotIp:
      ++skipped_.not_ip;
      return;
    case PacketVerdict::OtherIp:
      ++skipped_.other_ip;
      return;
    case PacketVerdict::Fragment:
      ++skipped_.fragments;
      return;
    case PacketVerdict::Malformed:
      ++skipped_.malformed;
      return;
  }
}

void AuditRun::on_exported_pdu(const CapturedPacket& packet) {
  const auto record = exported_pdu_record(packet.bytes);
  if (!record) {
    ++skipped_.malformed;
    return;
  }
  if (record->dissector != exported_pdu::kDissectorName) {
    ++skipped_.foreign_pdus;
    return;
  }
  feed_directed(serial_bus(InputKind::ExportedPdu), record->direction, record->pdu, packet.time);
}

void AuditRun::feed_directed(BusSession& bus, Direction d, std::span<const std::uint8_t> bytes,
                             double time) {
  bus.feed(BusChunk{bytes, time, d});
}

}  // namespace pvtap::analyzer
