// A channel's line settings found from its first samples: rate, idle level and format.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "pvtap/codec/dialect.h"
#include "pvtap/uart/baud_estimate.h"
#include "pvtap/uart/format_trial.h"

namespace pvtap {

// DetectedLine: what the samples say about the line.
struct DetectedLine {
  UartLine line;  // to decode with: the measured rate, the idle level, the best format
  BaudEstimate baud;
  FormatTrial trial;  // of the chosen format over the detection stretch
  // Characters that read cleanly or frames that check: a UART is talking on the channel.
  bool has_traffic = false;
  double samples_per_bit() const { return line.samples_per_bit(); }
};

// LineDetector: holds a channel's first runs (a bounded stretch, so that a session of any
// length is never held), then decides. The runs it held are replayed into the decoder.
class LineDetector {
 public:
  static constexpr std::size_t kStretchRuns = 1 << 14;

  // False once the stretch is full: decide() now.
  bool add(SampleRun run);
  const std::vector<SampleRun>& runs() const { return runs_; }

  // The formats tried, in the order that wins a tie: Modbus RTU asks for two stop bits
  // without parity, so 8N2 is taken over 8N1 when both read alike.
  static std::span<const UartFormat> candidates();
  // nullopt when no pulse is common enough to be a bit.
  std::optional<DetectedLine> decide(double sample_rate,
                                     DialectSet dialects = DialectSet::all()) const;

 private:
  std::vector<SampleRun> runs_;
};

}  // namespace pvtap
