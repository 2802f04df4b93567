// The simulated bus laid out character by character at the session's format and bit clock:
// who drives the line when (driver enable), the glitch bytes drivers emit when they switch,
// and the timing violations planted on purpose. The timeline is moved to match.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "bus/bus_event.h"
#include "logic/logic_options.h"

namespace pvtap::sim {

// Times in this layout are microseconds from the session's first sample.
struct DrivenCharacter {
  double start = 0;
  std::uint8_t value = 0;
  bool master = true;  // on the master's TX line (else on its RX line)
};

// GlitchPulse: the bus pulled to space by a driver switching; what a receiver reads of it.
struct GlitchPulse {
  double start = 0;
  double bits = 1;  // how long the line stays in space
  std::uint8_t value = 0;
  bool switch_on = true;  // right before a frame (else right after one)
  int talker = 0;         // 0: the master, else the station
};

// DriverWindow: a talker's driver enabled from `on` to `off`; `release` is `off` less the end
// of the last stop bit (negative: the last character was cut short).
struct DriverWindow {
  double on = 0, off = 0, release = 0;
  int talker = 0;
};

// DrivenSpan (--undriven space): the A-B line held by a driver from `on` to `off`, space
// elsewhere. Switching on, the driver lifts the line to mark and then lets it dip back to
// space for `spike` µs from `spike_at`: a pulse under half a bit, which opens no character.
struct DrivenSpan {
  double on = 0, off = 0, spike_at = 0, spike = 0;
};

struct Violation {
  double start = 0;
  std::string kind;  // "early_reply" (2.5 characters after its request), "pause_in_frame"
  std::uint8_t station = 0;
};

struct LogicLayout {
  Micros origin = 0;  // the Unix time of the first sample
  double end = 0;     // the last sample's time
  double bit = 0;     // microseconds per bit on the line
  std::vector<DrivenCharacter> characters;
  std::vector<GlitchPulse> glitches;
  std::vector<DriverWindow> drivers;
  std::vector<DrivenSpan> driven;  // --undriven space: every event's, frames and noise
  std::vector<Violation> violations;
};

// Lays out `timeline` (events moved to their new times, replies' latencies and the timeouts'
// and faults' times with them).
LogicLayout lay_out_logic(BusTimeline& timeline, const LogicOptions& options, unsigned baud,
                          std::uint64_t seed);

}  // namespace pvtap::sim
