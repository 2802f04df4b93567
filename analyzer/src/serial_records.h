// The records of serial-line captures: raw bus bytes, with or without a device's header.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string_view>

#include "pvtap/stream_reassembler.h"

namespace pvtap::analyzer {

// SerialRecord: the bus bytes of one capture record and what the capture says around them.
struct SerialRecord {
  std::span<const std::uint8_t> bytes;
  Direction direction = Direction::Unknown;
  bool data_lost_before = false;  // the capturing device reports lost data here
};

// RTAC serial (link type 250): a 12-byte header (seconds and microseconds, event type,
// control lines, footer) before the line data. nullopt when the header is cut short.
std::optional<SerialRecord> rtac_serial_record(std::span<const std::uint8_t> record);

// ExportedPdu: one record of link type 252 (Wireshark's exported PDUs): tags, then the PDU.
struct ExportedPdu {
  std::string_view dissector;  // EXP_PDU_TAG_DISSECTOR_NAME, trailing NULs removed
  Direction direction = Direction::Unknown;
  std::span<const std::uint8_t> pdu;
};

// Reads the tag list of a 252 record; nullopt when it is cut short or has no end tag.
std::optional<ExportedPdu> exported_pdu_record(std::span<const std::uint8_t> record);

}  // namespace pvtap::analyzer
