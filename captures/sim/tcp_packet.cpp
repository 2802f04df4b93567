#include "tcp_packet.h"

namespace pvtap::sim {
namespace {

constexpr std::size_t kEthernet = 14, kIpv4 = 20, kTcp = 20;

void put16(std::vector<std::uint8_t>& out, std::size_t at, std::uint32_t v) {
  out[at] = static_cast<std::uint8_t>(v >> 8);
  out[at + 1] = static_cast<std::uint8_t>(v);
}

void put32(std::vector<std::uint8_t>& out, std::size_t at, std::uint32_t v) {
  put16(out, at, v >> 16);
  put16(out, at + 2, v & 0xFFFF);
}

// RFC 1071 ones' complement sum of 16-bit words, carried from `sum`.
std::uint32_t ones_sum(std::span<const std::uint8_t> bytes, std::uint32_t sum) {
  for (std::size_t i = 0; i < bytes.size(); i += 2) {
    const std::uint32_t hi = bytes[i];
    const std::uint32_t lo = i + 1 < bytes.size() ? bytes[i + 1] : 0;
    sum += hi << 8 | lo;
  }
  return sum;
}

std::uint16_t fold(std::uint32_t sum) {
  while (sum >> 16) sum = (sum & 0xFFFF) + (sum >> 16);
  return static_cast<std::uint16_t>(~sum);
}

}  // namespace

std::vector<std::uint8_t> tcp_packet(const TcpEndpoint& from, const TcpEndpoint& to,
                                     const TcpSegmentFields& fields,
                                     std::span<const std::uint8_t> payload) {
  std::vector<std::uint8_t> out(kEthernet + kIpv4 + kTcp + payload.size(), 0);
  std::copy(to.mac.begin(), to.mac.end(), out.begin());
  std::copy(from.mac.begin(), from.mac.end(), out.begin() + 6);
  put16(out, 12, 0x0800);  // IPv4
  const std::size_t ip = kEthernet;
  out[ip] = 0x45;  // version 4, 5-word header
  put16(out, ip + 2, static_cast<std::uint32_t>(kIpv4 + kTcp + payload.size()));
  put16(out, ip + 4, fields.ip_id);
  put16(out, ip + 6, 0x4000);  // don't fragment
  out[ip + 8] = 64;            // TTL
  out[ip + 9] = 6;             // TCP
  std::copy(from.ip.begin(), from.ip.end(), out.begin() + ip + 12);
  std::copy(to.ip.begin(), to.ip.end(), out.begin() + ip + 16);
  put16(out, ip + 10, fold(ones_sum({out.data() + ip, kIpv4}, 0)));

  const std::size_t tcp = ip + kIpv4;
  put16(out, tcp, from.port);
  put16(out, tcp + 2, to.port);
  put32(out, tcp + 4, fields.seq);
  put32(out, tcp + 8, fields.ack);
  out[tcp + 12] = 0x50;  // 5-word header, no options
  out[tcp + 13] = fields.flags;
  put16(out, tcp + 14, 64240);  // window
  std::copy(payload.begin(), payload.end(), out.begin() + static_cast<std::ptrdiff_t>(tcp + kTcp));
  // Pseudo-header: addresses, protocol, TCP length; then the segment itself.
  std::uint32_t sum = ones_sum({out.data() + ip + 12, 8}, 0);
  sum += 6 + static_cast<std::uint32_t>(kTcp + payload.size());
  sum = ones_sum({out.data() + tcp, kTcp + payload.size()}, sum);
  put16(out, tcp + 16, fold(sum));
  return out;
}

}  // namespace pvtap::sim
