// Runs of logic samples synthesised from bytes, as a UART transmitter would drive the line.
#pragma once

#include <cmath>
#include <cstdint>
#include <span>
#include <vector>

#include "pvtap/uart/uart_decoder.h"

namespace pvtap::test {

// UartRuns: a line written bit by bit at a rate that may differ from the reader's; edges
// fall on the nearest sample, as a logic analyzer records them.
class UartRuns {
 public:
  UartRuns(double samples_per_bit, UartFormat format)
      : samples_per_bit_(samples_per_bit), format_(format) {}

  // The line held at `mark` (true) or space for `bits` bit times.
  UartRuns& hold(bool mark, double bits) {
    level(mark, bits * samples_per_bit_);
    return *this;
  }
  UartRuns& idle(double bits) { return hold(true, bits); }
  // One character; `parity_flip` sends the wrong parity, `stop_space` a space stop bit.
  UartRuns& byte(std::uint8_t value, bool parity_flip = false, bool stop_space = false) {
    hold(false, 1);
    unsigned ones = 0;
    for (unsigned i = 0; i < format_.data_bits; ++i) {
      const bool bit = ((unsigned{value} >> i) & 1u) != 0;
      ones += bit ? 1 : 0;
      hold(bit, 1);
    }
    if (format_.parity != Parity::None) {
      bool bit = (ones % 2 == 1) == (format_.parity == Parity::Even);
      hold(parity_flip ? !bit : bit, 1);
    }
    hold(!stop_space, format_.stop_bits);
    return *this;
  }
  UartRuns& bytes(std::span<const std::uint8_t> values, double gap_bits = 0) {
    for (std::uint8_t v : values) byte(v).idle(gap_bits);
    return *this;
  }
  // The sample at which the next bit would start.
  std::uint64_t now() const { return static_cast<std::uint64_t>(std::llround(time_)); }
  std::vector<SampleRun> runs() const { return runs_; }

 private:
  void level(bool mark, double samples) {
    const std::uint64_t from = now();
    time_ += samples;
    const std::uint64_t count = now() - from;
    const bool line = mark != format_.inverted;
    if (count == 0) return;
    if (!runs_.empty() && runs_.back().level == line) {
      runs_.back().count += count;
    } else {
      runs_.push_back(SampleRun{line, count});
    }
  }

  double samples_per_bit_;
  UartFormat format_;
  double time_ = 0;
  std::vector<SampleRun> runs_;
};

// Every character the runs hold, read by a decoder of `line`.
inline std::vector<UartCharacter> decode_runs(const UartLine& line,
                                              const std::vector<SampleRun>& runs) {
  UartDecoder decoder(line);
  std::vector<UartCharacter> out;
  for (const SampleRun& r : runs) decoder.feed(r, out);
  decoder.finish(out);
  return out;
}

}  // namespace pvtap::test
