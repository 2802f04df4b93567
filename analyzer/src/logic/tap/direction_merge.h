// The two directions of one bus on two channels (the master's TX and RX, say) merged into one
// stream in time order, so that the bus sees each request before its reply.
#pragma once

#include <cstdint>
#include <deque>
#include <vector>

#include "pvtap/framing/bus_chunk.h"
#include "pvtap/uart/uart_decoder.h"

namespace pvtap::analyzer {

struct DirectedCharacter {
  UartCharacter character;
  Direction direction = Direction::Unknown;
};

// DirectionMerge: a channel's decoder gives a character out only once the line moves after
// it, which may be long after the other channel has spoken; characters wait here until
// neither side can still give one that starts earlier (its watermark), or until too many wait.
class DirectionMerge {
 public:
  // Side 0 carries the requests (ToSlave), side 1 the replies (FromSlave).
  void add(std::size_t side, const UartCharacter& c);
  // Side `side` will give no character starting before sample `from`.
  void advance(std::size_t side, std::uint64_t from) { watermark_[side] = from; }
  // The characters that can go, in time order.
  void release(std::vector<DirectedCharacter>& out);
  // End of samples: every waiting character.
  void finish(std::vector<DirectedCharacter>& out);

 private:
  std::deque<DirectedCharacter> pending_;  // ordered by start
  std::uint64_t watermark_[2] = {0, 0};
};

}  // namespace pvtap::analyzer
