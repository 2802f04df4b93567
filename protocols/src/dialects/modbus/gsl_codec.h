// The bodies of the frames of GSL's function codes, which plain Modbus shares (private).
#pragma once

#include <cstdint>
#include <span>

#include "codec/wire_fields.h"

namespace pvtap::detail {

// Fill in the frame they are given (station, function, dialect and role set).
ParseStatus parse_gsl_request(std::span<const std::uint8_t> bytes, Frame& f);
ParseStatus parse_gsl_reply(std::span<const std::uint8_t> bytes, Frame& f);

}  // namespace pvtap::detail
