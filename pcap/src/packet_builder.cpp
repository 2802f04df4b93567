#include "pvtap/pcap/packet_builder.h"

#include <pcap/pcap.h>

namespace pvtap {
namespace {

void put16(PacketBytes& b, std::uint16_t v) {
  b.push_back(static_cast<std::uint8_t>(v >> 8));
  b.push_back(static_cast<std::uint8_t>(v));
}

void put32(PacketBytes& b, std::uint32_t v) {
  put16(b, static_cast<std::uint16_t>(v >> 16));
  put16(b, static_cast<std::uint16_t>(v));
}

std::uint32_t sum16(std::span<const std::uint8_t> bytes, std::uint32_t sum = 0) {
  for (std::size_t i = 0; i < bytes.size(); i += 2) {
    const std::uint32_t high = bytes[i];
    const std::uint32_t low = i + 1 < bytes.size() ? bytes[i + 1] : 0;
    sum += (high << 8) | low;
  }
  return sum;
}

std::uint16_t fold(std::uint32_t sum) {
  while ((sum >> 16) != 0) sum = (sum & 0xFFFF) + (sum >> 16);
  return static_cast<std::uint16_t>(~sum);
}

// Byte by byte: gcc 12 sees a false out-of-bounds copy in vector::insert of a std::array.
void put_mac(PacketBytes& b, const MacAddress& mac) {
  for (const std::uint8_t byte : mac) b.push_back(byte);
}

bool is_ipv6(const Endpoint& e) {
  return e.ip_version == 6;
}

std::span<const std::uint8_t> address_of(const Endpoint& e) {
  return std::span<const std::uint8_t>(e.address).first(is_ipv6(e) ? 16 : 4);
}

// The transport checksum over the IP pseudo-header and the segment.
std::uint16_t transport_checksum(const Endpoint& from, const Endpoint& to, std::uint8_t protocol,
                                 std::span<const std::uint8_t> segment) {
  std::uint32_t sum = sum16(address_of(from));
  sum = sum16(address_of(to), sum);
  sum += protocol;
  sum += static_cast<std::uint32_t>(segment.size());
  return fold(sum16(segment, sum));
}

PacketBytes ip_packet(const Endpoint& from, const Endpoint& to, std::uint8_t protocol,
                      std::uint16_t ip_id, PacketBytes segment) {
  const std::size_t checksum_at = protocol == 6 ? 16 : 6;
  const std::uint16_t checksum = transport_checksum(from, to, protocol, segment);
  segment[checksum_at] = static_cast<std::uint8_t>(checksum >> 8);
  segment[checksum_at + 1] = static_cast<std::uint8_t>(checksum);
  PacketBytes ip;
  if (!is_ipv6(from)) {
    ip = {0x45, 0x00};
    put16(ip, static_cast<std::uint16_t>(20 + segment.size()));
    put16(ip, ip_id);
    put16(ip, 0x4000);  // don't fragment
    ip.push_back(64);
    ip.push_back(protocol);
    put16(ip, 0);
    ip.insert(ip.end(), from.address.begin(), from.address.begin() + 4);
    ip.insert(ip.end(), to.address.begin(), to.address.begin() + 4);
    const std::uint16_t header_sum = fold(sum16(ip));
    ip[10] = static_cast<std::uint8_t>(header_sum >> 8);
    ip[11] = static_cast<std::uint8_t>(header_sum);
  } else {
    ip = {0x60, 0x00, 0x00, 0x00};
    put16(ip, static_cast<std::uint16_t>(segment.size()));
    ip.push_back(protocol);
    ip.push_back(64);
    ip.insert(ip.end(), from.address.begin(), from.address.end());
    ip.insert(ip.end(), to.address.begin(), to.address.end());
  }
  ip.insert(ip.end(), segment.begin(), segment.end());
  return ip;
}

PacketBytes with_link(LinkLayer link, const Route& route, PacketBytes ip) {
  const bool ipv6 = is_ipv6(route.from);
  const std::uint16_t ethertype = ipv6 ? 0x86DD : 0x0800;
  PacketBytes out;
  switch (link) {
    case LinkLayer::Ethernet:
      put_mac(out, route.to_mac);
      put_mac(out, route.from_mac);
      put16(out, ethertype);
      break;
    case LinkLayer::Sll:
      out = {0x00, 0x00, 0x00, 0x01, 0x00, 0x06};  // to us, ARPHRD_ETHER, address length
      put_mac(out, route.from_mac);
      put16(out, 0);  // address padding
      put16(out, ethertype);
      break;
    case LinkLayer::Sll2:
      put16(out, ethertype);
      put16(out, 0);     // reserved
      put32(out, 2);     // interface index
      put16(out, 1);     // ARPHRD_ETHER
      out.push_back(0);  // packet type: to us
      out.push_back(6);  // address length
      put_mac(out, route.from_mac);
      put16(out, 0);  // address padding
      break;
    case LinkLayer::Loopback:
      // BSD loopback: the address family in the capturing host's order (little-endian here).
      out = {static_cast<std::uint8_t>(ipv6 ? 30 : 2), 0, 0, 0};
      break;
    case LinkLayer::Raw:
      break;
  }
  out.insert(out.end(), ip.begin(), ip.end());
  // Ethernet pads frames to 60 bytes; the IP length tells where the packet ends.
  if (link == LinkLayer::Ethernet) {
    while (out.size() < 60) out.push_back(0);
  }
  return out;
}

}  // namespace

Endpoint ipv4_endpoint(std::uint8_t a, std::uint8_t b, std::uint8_t c, std::uint8_t d,
                       std::uint16_t port) {
  Endpoint h;
  h.address[0] = a;
  h.address[1] = b;
  h.address[2] = c;
  h.address[3] = d;
  h.port = port;
  return h;
}

Endpoint ipv6_endpoint(std::uint16_t last_group, std::uint16_t port) {
  Endpoint h;
  h.ip_version = 6;
  h.address[0] = 0xFD;
  h.address[14] = static_cast<std::uint8_t>(last_group >> 8);
  h.address[15] = static_cast<std::uint8_t>(last_group);
  h.port = port;
  return h;
}

int link_type_of(LinkLayer link) {
  switch (link) {
    case LinkLayer::Ethernet:
      return DLT_EN10MB;
    case LinkLayer::Sll:
      return DLT_LINUX_SLL;
    case LinkLayer::Sll2:
      return DLT_LINUX_SLL2;
    case LinkLayer::Raw:
      return DLT_RAW;
    case LinkLayer::Loopback:
      return DLT_NULL;
  }
  return DLT_EN10MB;
}

PacketBytes tcp_packet(LinkLayer link, const Route& route, const TcpHeader& tcp,
                       std::span<const std::uint8_t> payload) {
  const Endpoint& from = route.from;
  const Endpoint& to = route.to;
  PacketBytes segment;
  put16(segment, from.port);
  put16(segment, to.port);
  put32(segment, tcp.seq);
  put32(segment, tcp.ack);
  segment.push_back(0x50);  // 20-byte header
  segment.push_back(tcp.flags);
  put16(segment, tcp.window);
  put16(segment, 0);  // checksum, filled in below
  put16(segment, 0);  // urgent pointer
  segment.insert(segment.end(), payload.begin(), payload.end());
  return with_link(link, route, ip_packet(from, to, 6, tcp.ip_id, std::move(segment)));
}

PacketBytes udp_packet(LinkLayer link, const Route& route, std::span<const std::uint8_t> payload) {
  const Endpoint& from = route.from;
  const Endpoint& to = route.to;
  PacketBytes segment;
  put16(segment, from.port);
  put16(segment, to.port);
  put16(segment, static_cast<std::uint16_t>(8 + payload.size()));
  put16(segment, 0);
  segment.insert(segment.end(), payload.begin(), payload.end());
  return with_link(link, route, ip_packet(from, to, 17, TcpHeader{}.ip_id, std::move(segment)));
}

PacketBytes arp_packet() {
  PacketBytes out = {0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0x02,
                     0x00, 0x00, 0x00, 0x00, 0x01, 0x08, 0x06};
  const PacketBytes body = {0x00, 0x01, 0x08, 0x00, 0x06, 0x04, 0x00, 0x01, 0x02, 0x00,
                            0x00, 0x00, 0x00, 0x01, 0x0A, 0x00, 0x00, 0x01, 0x00, 0x00,
                            0x00, 0x00, 0x00, 0x00, 0x0A, 0x00, 0x00, 0x02};
  out.insert(out.end(), body.begin(), body.end());
  while (out.size() < 60) out.push_back(0);
  return out;
}

}  // namespace pvtap
