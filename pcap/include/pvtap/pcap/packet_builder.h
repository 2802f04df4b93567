// Builds network packets for generated captures (simulator, test captures, benchmarks): TCP
// or UDP in IPv4 or IPv6 with correct checksums, wrapped in one of the link layers pvtap
// audit reads; the writing side of network_packet.h.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "pvtap/pcap/network_packet.h"

namespace pvtap {

using PacketBytes = std::vector<std::uint8_t>;

Endpoint ipv4_endpoint(std::uint8_t a, std::uint8_t b, std::uint8_t c, std::uint8_t d,
                       std::uint16_t port);
Endpoint ipv6_endpoint(std::uint16_t last_group, std::uint16_t port);  // fd00::last_group

enum class LinkLayer { Ethernet, Sll, Sll2, Raw, Loopback };

// The pcap link type (DLT) of a link layer.
int link_type_of(LinkLayer link);

using MacAddress = std::array<std::uint8_t, 6>;

// Route: the two ends of a packet; the MAC addresses are used by Ethernet and the cooked
// captures' source address.
struct Route {
  Endpoint from;
  Endpoint to;
  MacAddress from_mac{0x02, 0, 0, 0, 0, 0x01};
  MacAddress to_mac{0x02, 0, 0, 0, 0, 0x02};
};

struct TcpHeader {
  std::uint32_t seq = 0;
  std::uint32_t ack = 0;
  std::uint8_t flags = tcp_flag::kAck;
  std::uint16_t window = 65535;
  std::uint16_t ip_id = 0x1234;  // IPv4 identification
};

// A whole packet (link header, IP, TCP, payload) with correct IP and TCP checksums.
PacketBytes tcp_packet(LinkLayer link, const Route& route, const TcpHeader& tcp,
                       std::span<const std::uint8_t> payload);
PacketBytes udp_packet(LinkLayer link, const Route& route, std::span<const std::uint8_t> payload);
// An ARP request on Ethernet: traffic that is not IP.
PacketBytes arp_packet();

}  // namespace pvtap
