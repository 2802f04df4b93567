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
#include "pvtap/registers/register_inference.h"
#include "pvtap/session/bus_report.h"

namespace pvtap::detail {

// StationReadings: the decoded newest values of one station and when the newest arrived.
struct StationReadings {
  double last_time = 0;
  std::vector<LatestValue> values;  // sorted by dialect, table, then address
};

class LatestReadings {
 public:
  // `infer`: feed a BlockInference for each block with words the decoder's maps do not name.
  LatestReadings(const RegisterDecoder& decoder, bool infer) : decoder_(decoder), infer_(infer) {}

  // Distinct blocks (station, dialect, function, start, count) kept; later new blocks are dropped,
  // so that memory stays bounded on a bus that reads ever new addresses.
  static constexpr std::size_t kMaxBlocks = 4096;

  // A reply with a good check, and the request it answers when known and sound.
  void store(const Frame& reply, const Frame* request, double time);
  std::map<std::uint8_t, StationReadings> decode(const RegisterDecoder& decoder) const;
  std::map<std::uint8_t, std::vector<InferredBlock>> inferred() const;

  // Blocks whose words are inferred; the later ones are not (memory stays bounded).
  static constexpr std::size_t kMaxInferred = 512;

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
    std::int32_t inference = -1;  // index into inference_, or none
  };
  // Inference: the statistics of one block with unmapped words, and where those words are.
  struct Inference {
    BlockInference stats;
    std::vector<std::pair<std::uint16_t, std::uint16_t>> runs;  // unmapped: from, count
    std::uint8_t station = 0;
    Dialect dialect = kDefaultDialect;
    std::uint8_t function = 0;
    std::uint16_t start = 0;
  };
  std::int32_t start_inference(const Frame& reply, const Frame* request);
  static Frame request_of(const Block& b);
  static std::optional<std::uint64_t> key_of(const Frame& reply, const Frame* request);

  const RegisterDecoder& decoder_;
  bool infer_ = false;
  std::unordered_map<std::uint64_t, Block> blocks_;
  std::vector<Inference> inference_;
  std::vector<DecodedValue> scratch_;  // a new block's words decoded once, to find its gaps
  std::uint64_t sequence_ = 0;
};

}  // namespace pvtap::detail
