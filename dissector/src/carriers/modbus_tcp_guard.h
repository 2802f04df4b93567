// Tells Modbus/TCP (MBAP) traffic apart, which Wireshark's own mbtcp dissector decodes and the
// heuristics must never claim.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>

namespace pvtap::dissector {

// The registered Modbus/TCP port.
inline constexpr std::uint32_t kModbusTcpPort = 502;

// Whether a TCP payload of `total` bytes, of which `prefix` is the start, is Modbus/TCP: a
// port is 502, or the payload is a run of whole MBAP ADUs (transaction id, protocol id 0, a
// length of 2 to 254 that ends exactly on the next ADU or the payload's end; where the prefix
// ends first, its ADUs so far).
bool looks_like_modbus_tcp(std::span<const std::uint8_t> prefix, std::size_t total,
                           std::uint32_t src_port, std::uint32_t dst_port);

}  // namespace pvtap::dissector
