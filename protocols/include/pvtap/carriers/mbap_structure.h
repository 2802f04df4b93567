// The structure check that recognises Modbus/TCP without its port.
#pragma once

#include <cstdint>
#include <optional>
#include <span>

namespace pvtap {

// MbapHeader: the four header fields as read, believable or not.
struct MbapHeader {
  std::uint16_t transaction = 0;
  std::uint16_t protocol_id = 0;
  std::uint16_t length = 0;
  std::uint8_t unit = 0;
};

// The header at the start of `bytes`; nullopt when fewer than 7 bytes are there.
std::optional<MbapHeader> read_mbap_header(std::span<const std::uint8_t> bytes);

// Protocol id 0 and a length that fits an ADU.
bool plausible_mbap_header(const MbapHeader& h);

// Whether `bytes` is one or more whole ADUs end to end, each with a plausible header and a
// function code byte that is not 0: what a client's or a gateway's send looks like. A run of
// random bytes passes by chance with odds under 2^-16 per header (two zero bytes at a fixed
// place, and a length that ends exactly where the next header or the piece does).
bool whole_mbap_adus(std::span<const std::uint8_t> bytes);

}  // namespace pvtap
