// What a Modbus device says of itself: read device identification (0x2B/0x0E) and report
// server ID (0x11) replies, read without copying.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string_view>

#include "pvtap/codec/frame.h"

namespace pvtap {

// DeviceObject: one object of a device identification reply; `value` points into the frame.
struct DeviceObject {
  std::uint8_t id = 0;
  std::string_view value;
};

// DeviceIdentification: a parsed 0x2B/0x0E reply. Objects 0x00-0x02 are the vendor name,
// product code and revision (the basic category every such device has).
struct DeviceIdentification {
  static constexpr std::size_t kMaxObjects = 64;  // 256-byte ADU, two bytes per empty object

  std::uint8_t read_code = 0;   // 1 basic, 2 regular, 3 extended, 4 one object
  std::uint8_t conformity = 0;  // the device's conformity level
  bool more_follows = false;    // 0xFF: ask again from next_object
  std::uint8_t next_object = 0;
  std::array<DeviceObject, kMaxObjects> objects{};
  std::size_t object_count = 0;

  // The value of object `id`, or empty.
  std::string_view object(std::uint8_t id) const;
  std::string_view vendor() const { return object(0x00); }
  std::string_view product() const { return object(0x01); }
  std::string_view revision() const { return object(0x02); }
};

// The identification a good 0x2B/0x0E reply carries; nullopt for any other frame, or when
// its object list overruns the frame. The views live as long as `reply`.
std::optional<DeviceIdentification> read_device_identification(const Frame& reply);

// The name (standard object name, "vendor name") of a device identification object.
std::string_view device_object_name(std::uint8_t id);

// ServerId: a report server ID (0x11) reply. The layout after the byte count is the
// device's own: by the specification a server ID, a run indicator (0x00 off, 0xFF on) and
// device data. `text` is the longest run of printable characters, which names most devices.
struct ServerId {
  std::optional<bool> running;  // from the first 0x00/0xFF byte after the first byte
  std::string_view text;
};

std::optional<ServerId> read_server_id(const Frame& reply);

}  // namespace pvtap
