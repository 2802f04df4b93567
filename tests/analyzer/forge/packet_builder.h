// Builds network packets for generated captures: TCP or UDP in IPv4 or IPv6, wrapped in one
// of the link layers pvtap audit reads.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

namespace pvtap::forge {

using Bytes = std::vector<std::uint8_t>;

// Host: an address (IPv4 in the first 4 bytes) and a port.
struct Host {
  std::array<std::uint8_t, 16> address{};
  bool ipv6 = false;
  std::uint16_t port = 0;
};

Host ipv4_host(std::uint8_t a, std::uint8_t b, std::uint8_t c, std::uint8_t d, std::uint16_t port);
Host ipv6_host(std::uint16_t last_group, std::uint16_t port);  // fd00::last_group

enum class LinkLayer { Ethernet, Sll, Sll2, Raw, Loopback };

// The pcap link type (DLT) of a link layer.
int link_type_of(LinkLayer link);

struct TcpHeader {
  std::uint32_t seq = 0;
  std::uint32_t ack = 0;
  std::uint8_t flags = 0x10;  // ACK
};

inline constexpr std::uint8_t kFin = 0x01;
inline constexpr std::uint8_t kSyn = 0x02;
inline constexpr std::uint8_t kPsh = 0x08;
inline constexpr std::uint8_t kAck = 0x10;

// A whole packet (link header, IP, TCP, payload) with correct IP and TCP checksums.
Bytes tcp_packet(LinkLayer link, const Host& from, const Host& to, const TcpHeader& tcp,
                 std::span<const std::uint8_t> payload);
Bytes udp_packet(LinkLayer link, const Host& from, const Host& to,
                 std::span<const std::uint8_t> payload);
// An ARP request on Ethernet: traffic that is not IP.
Bytes arp_packet();

}  // namespace pvtap::forge
