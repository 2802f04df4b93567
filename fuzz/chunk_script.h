// ChunkScript: reads a fuzz input as the options of a bus and a sequence of chunks and
// events, so that the fuzzer chooses where the stream is cut, when and in which direction.
//
// Layout: one options byte (bits 0-2 the dialects, 0 = all; bits 3-4 timestamp trust; bits
// 5-7 the baud rate), then steps of one control byte and one time byte each:
//   control & 3 in 0..2: a chunk of (control >> 2) bytes (0-63) in that direction;
//   control & 3 == 3:    an event, (control >> 2) & 3: idle, discontinuity, end of turn, lost data.
//   time byte:           advances the clock by 0.2 ms per unit; 255 sets it back by a second.
#pragma once

#include <cstdint>
#include <span>

#include "fuzz_input.h"
#include "pvtap/framing/framing_probe.h"
#include "pvtap/framing/stream_reassembler.h"

namespace pvtap::fuzz {

struct ScriptOptions {
  DialectSet dialects = DialectSet::all();
  TimestampTrust trust = TimestampTrust::Auto;
  std::uint32_t baud = 9600;
};

enum class StepKind : std::uint8_t { Chunk, Idle, Discontinuity, EndTurn, DataLost };

struct ScriptStep {
  StepKind kind = StepKind::Chunk;
  BusChunk chunk;
};

inline ScriptOptions read_script_options(FuzzInput& in) {
  static constexpr std::uint32_t kBauds[] = {9600, 2400, 4800, 19200, 115200, 300, 1200, 57600};
  const std::uint8_t b = in.byte();
  ScriptOptions o;
  auto set = DialectSet::none();
  for (const Dialect d : {Dialect::Ascii, Dialect::Hybrid, Dialect::Gsl}) {
    if (b & (1u << static_cast<unsigned>(d))) set = set.with(d);
  }
  if (set != DialectSet::none()) o.dialects = set;
  const unsigned trust = (b >> 3) & 3u;
  o.trust = trust == 1   ? TimestampTrust::Trusted
            : trust == 2 ? TimestampTrust::Untrusted
                         : TimestampTrust::Auto;
  o.baud = kBauds[b >> 5];
  return o;
}

class ChunkScript {
 public:
  explicit ChunkScript(FuzzInput& in) : in_(in) {}

  // The next step; false at the end of the input.
  bool next(ScriptStep& step) {
    if (in_.empty()) return false;
    const std::uint8_t control = in_.byte();
    const std::uint8_t tick = in_.byte();
    time_ = tick == 255 ? time_ - 1.0 : time_ + tick * 0.0002;
    step.chunk.time = time_;
    const unsigned low = control & 3u;
    if (low != 3) {
      step.kind = StepKind::Chunk;
      step.chunk.direction = static_cast<Direction>(low);
      step.chunk.bytes = in_.take(control >> 2);
    } else {
      static constexpr StepKind kEvents[] = {StepKind::Idle, StepKind::Discontinuity,
                                             StepKind::EndTurn, StepKind::DataLost};
      step.kind = kEvents[(control >> 2) & 3u];
      step.chunk.direction = static_cast<Direction>((control >> 4) % 3u);
      step.chunk.bytes = {};
    }
    return true;
  }

 private:
  FuzzInput& in_;
  double time_ = 1.0e9;  // a capture clock since the epoch, as pcaps have it
};

// The longest frame a dialect allows: ASCII replies carry up to 255 words as hex digits; an
// RTU frame has one byte count (address, function, count, data, CRC).
constexpr std::size_t max_frame_length(Dialect d) {
  return d == Dialect::Ascii ? kMaxFrameLength : 5 + 255;
}

}  // namespace pvtap::fuzz
