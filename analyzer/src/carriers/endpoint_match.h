// same_endpoint: endpoint equality for the per-packet flow checks, as two 8-byte compares of
// the address (std::array's == calls memcmp, which costs more than the rest of the check).
#pragma once

#include <cstdint>
#include <cstring>

#include "pvtap/pcap/network_packet.h"

namespace pvtap::analyzer {

inline bool same_endpoint(const Endpoint& a, const Endpoint& b) {
  std::uint64_t x[2];
  std::uint64_t y[2];
  static_assert(sizeof x == sizeof a.address);
  std::memcpy(x, a.address.data(), sizeof x);
  std::memcpy(y, b.address.data(), sizeof y);
  return a.port == b.port && x[0] == y[0] && x[1] == y[1] && a.ip_version == b.ip_version;
}

}  // namespace pvtap::analyzer
