// The bodies of Hybrid frames: fixed requests, and replies that open with the device number
// (private).
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "codec/wire_fields.h"

namespace pvtap::detail {

// Fill in the frame they are given (station, function, dialect and role set): passing a Frame
// by value copies its disengaged optionals, which g++ 14 reports as a read of uninitialized
// memory.
ParseStatus parse_hybrid_request(std::span<const std::uint8_t> bytes, Frame& f);
ParseStatus parse_hybrid_reply(std::span<const std::uint8_t> bytes, Frame& f);

// Appends what a reply's byte count counts: the device number, then its echo or words.
void encode_hybrid_reply_body(const Frame& f, std::vector<std::uint8_t>& body);

}  // namespace pvtap::detail
