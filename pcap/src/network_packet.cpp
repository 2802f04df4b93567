#include "pvtap/pcap/network_packet.h"

#include <algorithm>
#include <cstdio>
#include <optional>

#include "pvtap/pcap/link_types.h"

namespace pvtap {
namespace {

using Bytes = std::span<const std::uint8_t>;

constexpr std::uint16_t kEtherIpv4 = 0x0800;
constexpr std::uint16_t kEtherIpv6 = 0x86DD;
constexpr std::uint8_t kIpTcp = 6;
constexpr std::uint8_t kIpUdp = 17;

std::uint16_t be16(Bytes b, std::size_t at) {
  return static_cast<std::uint16_t>((b[at] << 8) | b[at + 1]);
}

std::uint32_t be32(Bytes b, std::size_t at) {
  return (std::uint32_t{b[at]} << 24) | (std::uint32_t{b[at + 1]} << 16) |
         (std::uint32_t{b[at + 2]} << 8) | std::uint32_t{b[at + 3]};
}

// IpPacket: the IP header and payload of a link-layer frame, or why there is none.
struct IpPacket {
  Bytes bytes;
  PacketVerdict verdict = PacketVerdict::Segment;
};

IpPacket ip_by_version(Bytes b) {
  if (b.empty()) return {{}, PacketVerdict::Malformed};
  const unsigned version = b[0] >> 4;
  if (version != 4 && version != 6) return {{}, PacketVerdict::NotIp};
  return {b, PacketVerdict::Segment};
}

IpPacket ip_by_ethertype(Bytes b, std::size_t header, std::uint16_t ethertype) {
  if (ethertype != kEtherIpv4 && ethertype != kEtherIpv6) return {{}, PacketVerdict::NotIp};
  return ip_by_version(b.subspan(header));
}

IpPacket ip_of_ethernet(Bytes b) {
  std::size_t at = 12;
  if (b.size() < at + 2) return {{}, PacketVerdict::Malformed};
  std::uint16_t type = be16(b, at);
  // 802.1Q and 802.1ad tags, possibly stacked.
  while (type == 0x8100 || type == 0x88A8 || type == 0x9100) {
    at += 4;
    if (b.size() < at + 2) return {{}, PacketVerdict::Malformed};
    type = be16(b, at);
  }
  return ip_by_ethertype(b, at + 2, type);
}

// The 4-byte address family of loopback captures; its byte order is the capturing host's for
// DLT_NULL, so both orders are tried. Linux uses 10 for IPv6, the BSDs 24, 28 or 30.
IpPacket ip_of_loopback(Bytes b) {
  if (b.size() < 4) return {{}, PacketVerdict::Malformed};
  const std::uint32_t big = be32(b, 0);
  const std::uint32_t little = (std::uint32_t{b[3]} << 24) | (std::uint32_t{b[2]} << 16) |
                               (std::uint32_t{b[1]} << 8) | std::uint32_t{b[0]};
  const auto is = [&](std::uint32_t family) { return big == family || little == family; };
  if (!is(2) && !is(10) && !is(24) && !is(28) && !is(30)) return {{}, PacketVerdict::NotIp};
  return ip_by_version(b.subspan(4));
}

IpPacket ip_of_link(int link_type, Bytes b) {
  switch (link_type) {
    case dlt::kEthernet:
      return ip_of_ethernet(b);
    case dlt::kLinuxSll:
      if (b.size() < 16) return {{}, PacketVerdict::Malformed};
      return ip_by_ethertype(b, 16, be16(b, 14));
    case dlt::kLinuxSll2:
      if (b.size() < 20) return {{}, PacketVerdict::Malformed};
      return ip_by_ethertype(b, 20, be16(b, 0));
    case dlt::kNull:
    case dlt::kLoop:
      return ip_of_loopback(b);
    default:
      return ip_by_version(b);
  }
}

// Transport: the protocol, the transport header onwards, and its length on the wire.
struct TransportPart {
  std::uint8_t protocol = 0;
  Bytes bytes;  // captured, from the transport header on
  std::size_t on_wire = 0;
};

std::optional<TransportPart> ipv4_transport(Bytes b, Segment& out, PacketVerdict& verdict) {
  if (b.size() < 20) return std::nullopt;
  const std::size_t header = std::size_t{b[0] & 0x0Fu} * 4;
  const std::size_t total = be16(b, 2);
  if (header < 20 || b.size() < header || total < header) return std::nullopt;
  const std::uint16_t fragment = be16(b, 6);
  if ((fragment & 0x3FFF) != 0) {  // more fragments, or an offset
    verdict = PacketVerdict::Fragment;
    return std::nullopt;
  }
  out.source.ip_version = out.destination.ip_version = 4;
  std::copy_n(b.begin() + 12, 4, out.source.address.begin());
  std::copy_n(b.begin() + 16, 4, out.destination.address.begin());
  // Ethernet pads short frames: the IP total length, not the capture, says where data ends.
  const std::size_t captured_end = std::min(b.size(), total);
  return TransportPart{b[9], b.subspan(header, captured_end - header), total - header};
}

std::optional<TransportPart> ipv6_transport(Bytes b, Segment& out, PacketVerdict& verdict) {
  if (b.size() < 40) return std::nullopt;
  const std::size_t payload = be16(b, 4);
  std::uint8_t next = b[6];
  out.source.ip_version = out.destination.ip_version = 6;
  std::copy_n(b.begin() + 8, 16, out.source.address.begin());
  std::copy_n(b.begin() + 24, 16, out.destination.address.begin());
  const std::size_t end = 40 + payload;
  std::size_t at = 40;
  // Hop-by-hop, routing and destination options, authentication header.
  while (next == 0 || next == 43 || next == 60 || next == 51) {
    if (b.size() < at + 2) return std::nullopt;
    const std::size_t length =
        next == 51 ? (std::size_t{b[at + 1]} + 2) * 4 : (std::size_t{b[at + 1]} + 1) * 8;
    next = b[at];
    at += length;
  }
  if (next == 44) {
    verdict = PacketVerdict::Fragment;
    return std::nullopt;
  }
  if (payload == 0 || at > end || b.size() < at) return std::nullopt;
  const std::size_t captured_end = std::min(b.size(), end);
  return TransportPart{next, b.subspan(at, captured_end - at), end - at};
}

PacketVerdict decode_tcp(const TransportPart& t, Segment& out) {
  const Bytes b = t.bytes;
  if (b.size() < 20) return PacketVerdict::Malformed;
  const std::size_t header = static_cast<std::size_t>(b[12] >> 4) * 4;
  if (header < 20 || b.size() < header || t.on_wire < header) return PacketVerdict::Malformed;
  out.transport = Transport::Tcp;
  out.source.port = be16(b, 0);
  out.destination.port = be16(b, 2);
  out.seq = be32(b, 4);
  out.ack = be32(b, 8);
  out.flags = b[13];
  out.payload = b.subspan(header);
  out.payload_on_wire = static_cast<std::uint32_t>(t.on_wire - header);
  return PacketVerdict::Segment;
}

PacketVerdict decode_udp(const TransportPart& t, Segment& out) {
  const Bytes b = t.bytes;
  if (b.size() < 8 || t.on_wire < 8) return PacketVerdict::Malformed;
  out.transport = Transport::Udp;
  out.source.port = be16(b, 0);
  out.destination.port = be16(b, 2);
  out.seq = out.ack = 0;
  out.flags = 0;
  out.payload = b.subspan(8);
  out.payload_on_wire = static_cast<std::uint32_t>(t.on_wire - 8);
  return PacketVerdict::Segment;
}

}  // namespace

std::string Endpoint::to_string() const {
  char text[64];
  if (ip_version == 4) {
    std::snprintf(text, sizeof text, "%u.%u.%u.%u:%u", address[0], address[1], address[2],
                  address[3], port);
    return text;
  }
  std::string out = "[";
  for (std::size_t i = 0; i < 16; i += 2) {
    if (i > 0) out += ':';
    std::snprintf(text, sizeof text, "%x", (address[i] << 8) | address[i + 1]);
    out += text;
  }
  std::snprintf(text, sizeof text, "]:%u", port);
  return out + text;
}

PacketVerdict decode_network_packet(int link_type, std::span<const std::uint8_t> packet,
                                    Segment& out) {
  const IpPacket ip = ip_of_link(link_type, packet);
  if (ip.verdict != PacketVerdict::Segment) return ip.verdict;
  PacketVerdict verdict = PacketVerdict::Malformed;
  const auto transport = (ip.bytes[0] >> 4) == 4 ? ipv4_transport(ip.bytes, out, verdict)
                                                 : ipv6_transport(ip.bytes, out, verdict);
  if (!transport) return verdict;
  if (transport->protocol == kIpTcp) return decode_tcp(*transport, out);
  if (transport->protocol == kIpUdp) return decode_udp(*transport, out);
  return PacketVerdict::OtherIp;
}

}  // namespace pvtap
