// Builds the bytes of one Ethernet/IPv4/TCP packet with correct checksums.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

namespace pvtap::sim {

// TcpEndpoint: one side of the connection.
struct TcpEndpoint {
  std::array<std::uint8_t, 6> mac{};
  std::array<std::uint8_t, 4> ip{};
  std::uint16_t port = 0;
};

namespace tcp_flag {
inline constexpr std::uint8_t kFin = 0x01;
inline constexpr std::uint8_t kSyn = 0x02;
inline constexpr std::uint8_t kPsh = 0x08;
inline constexpr std::uint8_t kAck = 0x10;
}  // namespace tcp_flag

struct TcpSegmentFields {
  std::uint32_t seq = 0;
  std::uint32_t ack = 0;
  std::uint8_t flags = 0;
  std::uint16_t ip_id = 0;
};

std::vector<std::uint8_t> tcp_packet(const TcpEndpoint& from, const TcpEndpoint& to,
                                     const TcpSegmentFields& fields,
                                     std::span<const std::uint8_t> payload);

}  // namespace pvtap::sim
