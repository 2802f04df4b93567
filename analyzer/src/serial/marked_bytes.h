// MarkedBytes: a tty's input read with PARMRK back into bytes and their line errors.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "pvtap/uart/baud_search.h"

namespace pvtap::analyzer {

// The driver writes a byte with a framing or parity error as \377 \0 byte, a break as
// \377 \0 \0 (the same as a 0x00 with a framing error: a tty cannot tell them apart, so it
// is one here too) and a real \377 as \377 \377. A mark may be cut between two reads.
class MarkedBytes {
 public:
  void unmark(std::span<const std::uint8_t> in, std::vector<LineByte>& out);

 private:
  enum class State : std::uint8_t { Plain, Escape, EscapeZero };
  State state_ = State::Plain;
};

}  // namespace pvtap::analyzer
