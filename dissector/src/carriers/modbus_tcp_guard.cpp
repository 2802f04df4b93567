#include "carriers/modbus_tcp_guard.h"

namespace pvtap::dissector {
namespace {

constexpr std::size_t kMbapHeader =
    6;  // transaction id, protocol id, length; the unit id counts in length
constexpr std::size_t kSmallestLength = 2;  // unit id and function code
constexpr std::size_t kLargestLength = 254;

}  // namespace

bool looks_like_modbus_tcp(std::span<const std::uint8_t> prefix, std::size_t total,
                           std::uint32_t src_port, std::uint32_t dst_port) {
  if (src_port == kModbusTcpPort || dst_port == kModbusTcpPort) return true;
  std::size_t at = 0;
  while (at + kMbapHeader <= prefix.size()) {
    const auto protocol = static_cast<unsigned>((prefix[at + 2] << 8) | prefix[at + 3]);
    const std::size_t length = static_cast<std::size_t>((prefix[at + 4] << 8) | prefix[at + 5]);
    if (protocol != 0 || length < kSmallestLength || length > kLargestLength) return false;
    at += kMbapHeader + length;
    if (at > total) return false;
    if (at == total) return true;
  }
  return at > 0 && prefix.size() < total;
}

}  // namespace pvtap::dissector
