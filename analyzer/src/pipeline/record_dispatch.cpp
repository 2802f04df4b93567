// The pipeline's handling of one capture record, by the kind of input its link type makes it.
#include "pipeline/pipeline.h"
#include "pvtap/capture/exported_pdu_reader.h"
#include "pvtap/capture/exported_pdu_tags.h"
#include "pvtap/capture/network_packet.h"
#include "pvtap/capture/rtac_record.h"

namespace pvtap::analyzer {

void Pipeline::record(const CapturedPacket& packet) {
  switch (kind_) {
    case InputKind::Network:
      on_network_packet(packet);
      return;
    case InputKind::ExportedPdu:
      on_exported_pdu(packet);
      return;
    case InputKind::Serial:
      on_serial_record(packet);
      return;
    case InputKind::RtacSerial:
      on_rtac_record(packet);
      return;
  }
}

void Pipeline::on_serial_record(const CapturedPacket& packet) {
  BusSession& bus = serial_bus(InputKind::Serial);
  bus.feed(BusChunk{packet.bytes, packet.time, Direction::Unknown});
  // The capture's snap length cut the record: its tail is lost.
  if (packet.length_on_wire > packet.bytes.size()) {
    bus.data_lost(Direction::Unknown, packet.time, packet.length_on_wire - packet.bytes.size());
  }
}

void Pipeline::on_rtac_record(const CapturedPacket& packet) {
  const auto record = rtac_serial_record(packet.bytes);
  if (!record) {
    ++skipped_.malformed;
    return;
  }
  BusSession& bus = serial_bus(InputKind::RtacSerial);
  if (record->data_lost_before) bus.data_lost(Direction::Unknown, packet.time, std::nullopt);
  bus.feed(BusChunk{record->bytes, packet.time, Direction::Unknown});
}

void Pipeline::on_network_packet(const CapturedPacket& packet) {
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

void Pipeline::on_exported_pdu(const CapturedPacket& packet) {
  const auto record = exported_pdu_record(packet.bytes);
  if (!record) {
    ++skipped_.malformed;
    return;
  }
  if (record->dissector != exported_pdu::kDissectorName) {
    ++skipped_.foreign_pdus;
    return;
  }
  // Half duplex: the session ends a side's turn when the other side speaks.
  serial_bus(InputKind::ExportedPdu).feed(BusChunk{record->pdu, packet.time, record->direction});
}

}  // namespace pvtap::analyzer
