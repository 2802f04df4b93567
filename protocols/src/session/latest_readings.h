// LatestReadings: the newest register data each station reported, kept as raw frames and
// decoded only when the report asks, so that following a long capture costs one copy per reply.
#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <optional>
#include <unordered_map>
#include <vector>

#include "pvtap/codec/frame.h"
#include "pvtap/registers/register_decoder.h"
#include "pvtap/session/bus_report.h"

namespace pvtap::detail {

// StationReadings: the decoded newest values of one station and when the newest arrived.
struct StationReadings {
  double last_time = 0;
  std::vector<LatestValue> values;  // sorted by dialect, table, then address
};

class LatestReadings {
 public:
  // Distinct blocks (station, dialect, function, start, count) kept; later new blocks are dropped,
  // so that memory stays bounded on a bus that reads ever new addresses.
  static constexpr std::size_t kMaxBlocks = 4096;

  // A reply with a good check, and the request it answers when known and sound.
  void store(const Frame& reply, const Frame* request, double time);
  std::map<std::uint8_t, StationReadings> decode(const RegisterDecoder& decoder) const;

 private:
  // Block: the newest reply of one kind, and of its request what decoding needs (a whole
  // request frame would double the copying per reply).
  struct Block {
    std::uint64_t sequence = 0;
    double time = 0;
    Frame reply;
    bool has_request = false;
    std::uint8_t request_function = 0;
    std::optional<std::uint16_t> request_start;
    std::optional<std::uint16_t> request_count;
  };
  static Frame request_of(const Block& b);
  static std::optional<std::uint64_t> key_of(const Frame& reply, const Frame* request);

  std::unordered_map<std::uint64_t, Block> blocks_;
  std::uint64_t sequence_ = 0;
};

}  // namespace pvtap::detail
