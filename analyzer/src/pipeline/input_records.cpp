// InputRecords: one capture record, by the kind of input its link type makes it.
#include "pipeline/input_records.h"

#include "pvtap/pcap/exported_pdu_reader.h"
#include "pvtap/pcap/exported_pdu_tags.h"
#include "pvtap/pcap/rtac_record.h"

namespace pvtap::analyzer {
namespace {

SerialBytes serial_record(const CapturedPacket& packet, Direction direction) {
  SerialBytes serial;
  serial.chunk = BusChunk{packet.bytes, packet.time, direction};
  if (packet.length_on_wire > packet.bytes.size()) {
    serial.lost_after = packet.length_on_wire - packet.bytes.size();
  }
  return serial;
}

}  // namespace

void InputRecords::begin(int link_type, bool batched_serial, bool serial_timing_open,
                         Direction direction) {
  link_type_ = link_type;
  serial_direction_ = direction;
  kind_ = input_kind_of(link_type).value_or(InputKind::Serial);
  if (kind_ == InputKind::Serial && serial_timing_open) batched_serial_ = batched_serial;
  network_ = network_ || kind_ == InputKind::Network;
}

Timestamping InputRecords::timestamping_of(InputKind kind, bool has_timestamps) const {
  if (!has_timestamps) return Timestamping::PlainDump;
  switch (kind) {
    case InputKind::Network:
      return Timestamping::GatewaySegments;
    case InputKind::ExportedPdu:
      return Timestamping::ExportedPdus;
    case InputKind::Serial:
      return batched_serial_ ? Timestamping::SerialBatches : Timestamping::SerialCharacters;
    case InputKind::RtacSerial:
      break;
  }
  return Timestamping::SerialCharacters;
}

std::optional<SerialBytes> InputRecords::serial_bytes(const CapturedPacket& packet) {
  switch (kind_) {
    case InputKind::Network:
      break;
    case InputKind::ExportedPdu:
      return exported_pdu(packet);
    case InputKind::Serial:
      return serial_record(packet, serial_direction_);
    case InputKind::RtacSerial:
      return rtac_record(packet);
  }
  return std::nullopt;
}

std::optional<SerialBytes> InputRecords::rtac_record(const CapturedPacket& packet) {
  const auto record = rtac_serial_record(packet.bytes);
  if (!record) {
    ++skipped_.malformed;
    return std::nullopt;
  }
  SerialBytes serial;
  serial.kind = InputKind::RtacSerial;
  serial.lost_before = record->data_lost_before;
  serial.chunk = BusChunk{record->bytes, packet.time, serial_direction_};
  return serial;
}

bool InputRecords::network_packet(const CapturedPacket& packet, Segment& segment) {
  switch (decode_network_packet(link_type_, packet.bytes, segment)) {
    case PacketVerdict::Segment:
      return true;
    case PacketVerdict::NotIp:
      ++skipped_.not_ip;
      break;
    case PacketVerdict::OtherIp:
      ++skipped_.other_ip;
      break;
    case PacketVerdict::Fragment:
      ++skipped_.fragments;
      break;
    case PacketVerdict::Malformed:
      ++skipped_.malformed;
      break;
  }
  return false;
}

std::optional<SerialBytes> InputRecords::exported_pdu(const CapturedPacket& packet) {
  const auto record = exported_pdu_record(packet.bytes);
  if (!record) {
    ++skipped_.malformed;
    return std::nullopt;
  }
  // pvtap's marks of a moment carry text, never bus bytes: only their record tag counts.
  const bool event = record->dissector == exported_pdu::kEventDissectorName;
  if ((record->dissector != exported_pdu::kDissectorName && !event) ||
      (event && record->pvtap_record.empty())) {
    ++skipped_.foreign_pdus;
    return std::nullopt;
  }
  // Half duplex: the session ends a side's turn when the other side speaks.
  SerialBytes serial;
  serial.kind = InputKind::ExportedPdu;
  serial.chunk = BusChunk{event ? std::span<const std::uint8_t>{} : record->pdu, packet.time,
                          record->direction};
  serial.decided = record->pvtap_record;
  serial.run = record->pvtap_run;
  return serial;
}

}  // namespace pvtap::analyzer
