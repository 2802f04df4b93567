// decode_network_packet on packets of every network link type pvtap reads.
#include "pvtap/pcap/network_packet.h"

#include <gtest/gtest.h>

#include "pvtap/pcap/link_types.h"
#include "pvtap/pcap/packet_builder.h"

namespace pvtap::analyzer {
namespace {

using Bytes = PacketBytes;

const Bytes kPayload = {0x01, 0x03, 0x00, 0x00, 0x00, 0x0A, 0xC5, 0xCD};

void expect_segment(LinkLayer link, const Endpoint& from, const Endpoint& to) {
  const Bytes packet = tcp_packet(link, {from, to}, {1234, 5678, 0x18}, kPayload);
  Segment s;
  ASSERT_EQ(decode_network_packet(link_type_of(link), packet, s), PacketVerdict::Segment);
  EXPECT_EQ(s.transport, Transport::Tcp);
  EXPECT_EQ(s.source.port, from.port);
  EXPECT_EQ(s.destination.port, to.port);
  EXPECT_EQ(s.seq, 1234u);
  EXPECT_EQ(s.ack, 5678u);
  EXPECT_EQ(s.flags, 0x18);
  EXPECT_EQ(Bytes(s.payload.begin(), s.payload.end()), kPayload);
  EXPECT_EQ(s.payload_on_wire, kPayload.size());
}

TEST(NetworkPacket, EveryLinkLayerCarriesTcpOverIpv4) {
  const auto master = ipv4_endpoint(10, 0, 0, 1, 50000);
  const auto gateway = ipv4_endpoint(10, 0, 0, 2, 4001);
  for (const LinkLayer link : {LinkLayer::Ethernet, LinkLayer::Sll, LinkLayer::Sll2, LinkLayer::Raw,
                               LinkLayer::Loopback}) {
    SCOPED_TRACE(link_type_of(link));
    expect_segment(link, master, gateway);
  }
}

TEST(NetworkPacket, Ipv6AndItsEndpointText) {
  const auto master = ipv6_endpoint(1, 50000);
  const auto gateway = ipv6_endpoint(2, 502);
  expect_segment(LinkLayer::Sll2, master, gateway);
  const Bytes packet = udp_packet(LinkLayer::Raw, {master, gateway}, kPayload);
  Segment s;
  ASSERT_EQ(decode_network_packet(dlt::kRaw, packet, s), PacketVerdict::Segment);
  EXPECT_EQ(s.transport, Transport::Udp);
  EXPECT_EQ(s.destination.to_string(), "[fd00:0:0:0:0:0:0:2]:502");
}

TEST(NetworkPacket, EthernetPaddingIsNotPayload) {
  const Bytes packet =
      tcp_packet(LinkLayer::Ethernet, {ipv4_endpoint(1, 2, 3, 4, 1), ipv4_endpoint(1, 2, 3, 5, 2)},
                 {1, 0, 0x10}, {});
  ASSERT_EQ(packet.size(), 60u);  // padded from 54
  Segment s;
  ASSERT_EQ(decode_network_packet(dlt::kEthernet, packet, s), PacketVerdict::Segment);
  EXPECT_TRUE(s.payload.empty());
  EXPECT_EQ(s.source.to_string(), "1.2.3.4:1");
}

TEST(NetworkPacket, SnapLengthCutIsVisible) {
  Bytes packet =
      tcp_packet(LinkLayer::Raw, {ipv4_endpoint(1, 2, 3, 4, 1), ipv4_endpoint(1, 2, 3, 5, 2)},
                 {1, 0, 0x10}, kPayload);
  packet.resize(packet.size() - 3);
  Segment s;
  ASSERT_EQ(decode_network_packet(dlt::kRaw, packet, s), PacketVerdict::Segment);
  EXPECT_EQ(s.payload.size(), kPayload.size() - 3);
  EXPECT_EQ(s.payload_on_wire, kPayload.size());
}

TEST(NetworkPacket, OtherTrafficIsToldApart) {
  Segment s;
  EXPECT_EQ(decode_network_packet(dlt::kEthernet, arp_packet(), s), PacketVerdict::NotIp);
  Bytes icmp = udp_packet(LinkLayer::Raw,
                          {ipv4_endpoint(1, 2, 3, 4, 1), ipv4_endpoint(1, 2, 3, 5, 2)}, kPayload);
  icmp[9] = 1;  // protocol ICMP
  EXPECT_EQ(decode_network_packet(dlt::kRaw, icmp, s), PacketVerdict::OtherIp);
  Bytes fragment = icmp;
  fragment[9] = 17;
  fragment[6] = 0x20;  // more fragments
  EXPECT_EQ(decode_network_packet(dlt::kRaw, fragment, s), PacketVerdict::Fragment);
  EXPECT_EQ(decode_network_packet(dlt::kRaw, Bytes{0x45, 0x00}, s), PacketVerdict::Malformed);
  EXPECT_EQ(decode_network_packet(dlt::kEthernet, Bytes(10, 0), s), PacketVerdict::Malformed);
}

}  // namespace
}  // namespace pvtap::analyzer
