// Characters from the samples of one logic channel: an asynchronous serial receiver fed runs.
#pragma once

#include <cstdint>
#include <vector>

#include "pvtap/uart/uart_format.h"

namespace pvtap {

// SampleRun: `count` consecutive samples at `level` (as read, before any inversion).
struct SampleRun {
  bool level = true;
  std::uint64_t count = 0;
};

// UartCharacter: one character as the line carried it; times are sample indexes.
struct UartCharacter {
  std::uint16_t value = 0;
  std::uint64_t start = 0;     // the start bit's leading edge
  std::uint64_t end = 0;       // where the last stop bit ends
  bool framing_error = false;  // a stop bit read as space
  bool parity_error = false;
  // The line stayed in space for longer than a character and a bit: no character at all.
  bool is_break = false;
};

// UartDecoder: reads characters as a receiver does, from runs rather than samples, so that
// an idle line costs one call per run whatever its length. The start edge opens a character;
// the start bit must still be space at mid-bit (a shorter glitch opens nothing), and every
// bit is read at its middle, counted from that edge.
class UartDecoder {
 public:
  explicit UartDecoder(const UartLine& line);

  // The next samples: characters they complete are appended to `out`.
  void feed(SampleRun run, std::vector<UartCharacter>& out);
  // End of samples: a character held to tell a break from a 0x00 is given out.
  void finish(std::vector<UartCharacter>& out);

  std::uint64_t position() const { return position_; }          // samples fed so far
  std::uint64_t false_starts() const { return false_starts_; }  // glitches under half a bit

 private:
  enum class State : std::uint8_t { Idle, Receiving, Space };

  void begin(std::uint64_t start);
  void read_bit(bool mark, std::vector<UartCharacter>& out);
  void complete(std::vector<UartCharacter>& out);
  void end_space(std::uint64_t mark_at, std::vector<UartCharacter>& out);

  UartFormat format_;
  double samples_per_bit_;
  unsigned bits_;
  State state_ = State::Idle;
  std::uint64_t position_ = 0;
  double next_point_ = 0;  // the sample at which the next bit is read
  unsigned bit_ = 0;       // the next bit's index, the start bit being 0
  unsigned ones_ = 0;
  UartCharacter current_;
  bool held_ = false;  // current_ is an all-space character waiting for the line to rise
  std::uint64_t false_starts_ = 0;
};

}  // namespace pvtap
