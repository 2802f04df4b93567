// What a logic recording will be audited as: its UART channels and their settings, found by
// a first pass, or the one-line reason it cannot be audited (decided before any output).
#pragma once

#include <string>
#include <vector>

#include "logic/input/sample_hold.h"
#include "logic/plan/line_probe.h"

namespace pvtap::analyzer {

// A file pvtap reads as a logic recording rather than as a capture: a sigrok session (.sr), a
// Value Change Dump (.vcd) or a logic CSV (.csv), all through libsigrok.
bool is_logic_recording(const std::string& path);

// LogicPlan: the channels with UART traffic (each with its line), or why there are none.
struct LogicPlan {
  std::string path;
  double sample_rate = 0;               // --samplerate, or else the recording's own
  std::vector<ProbedChannel> channels;  // every one has a line with traffic
  std::vector<LogicChannel> drivers;    // --de: driver-enable channels, never read as UARTs
  // The buses, as indexes into `channels`: one channel carrying both directions, or two, the
  // requests' and the replies'.
  std::vector<std::vector<std::size_t>> buses;
  std::string error;  // empty when the plan can run
  HeldSamples held;   // the samples the probe read, when it read the whole recording
};

// A recording of at most this many bytes of samples is read once: the probe's reading is kept.
inline constexpr std::size_t kHeldRecordingLimit = std::size_t{32} << 20;

// A decoder needs this many samples per bit to find a start bit's middle.
inline constexpr double kMinSamplesPerBit = 4.0;

// `buses`: --channels, each "NAME" (a bus on one channel) or "REQUESTS,REPLIES" (the two
// directions of one bus); empty for every channel with UART traffic. `drivers`: --de.
// `sample_rate`: --samplerate, in place of the recording's own (0: the recording's).
LogicPlan plan_logic_audit(const std::string& path, const std::vector<std::string>& buses,
                           const std::vector<std::string>& drivers = {}, double sample_rate = 0);

// From a finished probe: the channels that talk into `plan` (which has its sample rate), or
// why none can be read in plan.error. `asked`: each probed channel was named, and must talk.
void keep_probed(const LineProbe& probe, bool asked, LogicPlan& plan);

}  // namespace pvtap::analyzer
