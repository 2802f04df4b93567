// The records of serial-line captures that carry a device's header before the bus bytes.
#pragma once

#include <cstdint>
#include <optional>
#include <span>

namespace pvtap {

// SerialRecord: the bus bytes of one capture record and what the capture says around them.
struct SerialRecord {
  std::span<const std::uint8_t> bytes;
  bool data_lost_before = false;  // the capturing device reports lost data here
};

// RTAC serial (link type 250): a 12-byte header (seconds and microseconds, event type,
// control lines, footer) before the line data. nullopt when the header is cut short.
std::optional<SerialRecord> rtac_serial_record(std::span<const std::uint8_t> record);

}  // namespace pvtap
