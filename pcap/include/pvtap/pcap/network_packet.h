// Decoding of captured network packets down to one TCP or UDP segment.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>

namespace pvtap {

// Endpoint: an IPv4 or IPv6 address and a port.
struct Endpoint {
  std::array<std::uint8_t, 16> address{};  // IPv4 uses the first 4 bytes
  std::uint8_t ip_version = 4;
  std::uint16_t port = 0;

  bool operator==(const Endpoint&) const = default;
  auto operator<=>(const Endpoint&) const = default;
  std::string to_string() const;  // "192.168.1.10:4001", "[fe80::1]:4001"
};

enum class Transport : std::uint8_t { Tcp, Udp };

// TCP flags pvtap reads and writes.
namespace tcp_flag {
inline constexpr std::uint8_t kFin = 0x01;
inline constexpr std::uint8_t kSyn = 0x02;
inline constexpr std::uint8_t kRst = 0x04;
inline constexpr std::uint8_t kPsh = 0x08;
inline constexpr std::uint8_t kAck = 0x10;
}  // namespace tcp_flag

// Segment: one TCP or UDP segment; `payload` points into the packet.
struct Segment {
  Transport transport = Transport::Tcp;
  Endpoint source;
  Endpoint destination;
  std::uint32_t seq = 0;
  std::uint32_t ack = 0;
  std::uint8_t flags = 0;
  std::span<const std::uint8_t> payload;  // the captured part
  std::uint32_t payload_on_wire = 0;      // its length on the wire (snap length may cut it)
};

// PacketVerdict: what a packet turned out to be.
enum class PacketVerdict : std::uint8_t {
  Segment,    // a TCP or UDP segment
  NotIp,      // ARP, other EtherTypes, other address families
  OtherIp,    // IP but neither TCP nor UDP (ICMP, ...)
  Fragment,   // an IP fragment (reassembly of IP fragments is not done)
  Malformed,  // headers cut short or inconsistent
};

// Decodes a packet of a network link type (see link_types.h) into a segment.
PacketVerdict decode_network_packet(int link_type, std::span<const std::uint8_t> packet,
                                    Segment& out);

}  // namespace pvtap
