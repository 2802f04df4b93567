// The frames of the public Modbus function codes that GSL does not use (private).
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "codec/wire_fields.h"
#include "pvtap/codec/frame_codec.h"

namespace pvtap::detail {

// Parses the body of a plain Modbus frame into `f` (station, function, dialect and role set).
ParseStatus parse_modbus_request(std::span<const std::uint8_t> bytes, Frame& f);
ParseStatus parse_modbus_reply(std::span<const std::uint8_t> bytes, Frame& f);

// Appends the body (between function code and CRC) of such a frame; false if its fields do
// not fit its function.
bool encode_modbus_body(const Frame& f, std::vector<std::uint8_t>& out);

}  // namespace pvtap::detail
