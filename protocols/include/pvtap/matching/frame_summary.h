// The few fields of a frame that pairing requests with replies depends on.
#pragma once

#include <cstdint>
#include <optional>

#include "pvtap/codec/dialect.h"
#include "pvtap/codec/frame.h"

namespace pvtap {

// FrameSummary: a frame reduced to what the transaction matcher compares (fits in a register
// or two, so the matcher can keep one per station without holding whole frames).
struct FrameSummary : FrameHeader {
  std::uint16_t word_count = 0;
  std::optional<std::uint16_t> first_word;  // the written value of a GSL 0x06 request/echo

  bool operator==(const FrameSummary&) const = default;
};

// Reduces a parsed frame to its summary.
FrameSummary summarize(const Frame& frame);

}  // namespace pvtap
