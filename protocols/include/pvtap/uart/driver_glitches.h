// RS485 driver glitches: the byte a transceiver puts on the line when its driver switches on
// (a 0x00 with a framing error) or off (a 0xFE or 0xFF), told from the frame beside it.
#pragma once

#include <cstddef>
#include <vector>

#include "pvtap/uart/uart_decoder.h"

namespace pvtap {

// DriverGlitch: a character that was the line switching, not data; `switch_on`: right before
// a frame (else right after one).
struct DriverGlitch {
  UartCharacter character;
  bool switch_on = true;
};

// DriverGlitchFilter: holds each run of characters between silences of 3.5 characters (where
// a driver may switch) and gives it out without its glitches, so that they neither join the
// frame beside them nor break it. A run's first character is a switch-on glitch when it is
// suspect (a framing error, or 0x00, 0xFE, 0xFF) and the next starts within about a character
// time of its end; its last is a switch-off glitch when suspect and it starts within about a
// character time of the one before. A suspect byte read cleanly (no framing or parity error:
// on a parity line a switch-off 0xFF has its parity bit wrong) is only a glitch when the run
// checks (CRC-16/MODBUS) without it and does not with it: a frame's own 0x00 or 0xFF stays,
// and a damaged frame keeps its last byte unless that byte's own bits say it is a glitch.
class DriverGlitchFilter {
 public:
  explicit DriverGlitchFilter(const UartLine& line);

  // The next character (no breaks); runs it ends go to `out` and `glitches`.
  void feed(const UartCharacter& c, std::vector<UartCharacter>& out,
            std::vector<DriverGlitch>& glitches);
  // Where the held run starts (none held: `otherwise`): nothing earlier is still to come.
  std::uint64_t held_from(std::uint64_t otherwise) const {
    return run_.empty() ? otherwise : run_.front().start;
  }
  // The samples ended: the held run is given out.
  void flush(std::vector<UartCharacter>& out, std::vector<DriverGlitch>& glitches);

 private:
  void close_run(std::vector<UartCharacter>& out, std::vector<DriverGlitch>& glitches);
  bool switch_on_glitch(std::size_t first, std::size_t last) const;
  bool switch_off_glitch(std::size_t first, std::size_t last) const;

  double char_samples_;
  std::vector<UartCharacter> run_;
  bool head_open_ = true;  // the run's first character is still held (it may be a glitch)
};

}  // namespace pvtap
