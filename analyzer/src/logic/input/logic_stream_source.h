// LogicStreamSource: pvtap sniff --logic -: a logic analyzer's samples streamed live, as
// sigrok-cli's binary output (-O binary) writes them: one bit per channel, packed as the
// session packs them (bit 0 first), named by --channels and clocked by --samplerate.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "logic/plan/line_probe.h"
#include "logic/plan/logic_plan.h"
#include "logic/tap/uart_tap.h"
#include "pipeline/pipeline.h"
#include "report/live_report.h"
#include "sources/live_loop.h"
#include "sources/live_options.h"

namespace pvtap::analyzer {

// The first stretch is held while each channel's line is found, as pvtap audit finds it in a
// recording; then every channel that talks is a bus timed at the sample clock.
class LogicStreamSource {
 public:
  // Driver glitches go to `events` (the pipeline's).
  LogicStreamSource(const LiveOptions& live, Pipeline& pipeline);
  ~LogicStreamSource();

  // Reads the first stretch and finds the lines; false (after saying why) when no channel
  // can be read.
  bool open();
  // Reads to the end of the stream or until the loop says stop.
  void run(LiveLoop& loop, LiveSources& live);
  // The lines found, on the buses of `report`.
  void add_found_lines(AuditReport& report) const;

  // Held at most while the lines are found (a channel that never talks must not hold more).
  static constexpr std::size_t kHoldLimit = std::size_t{64} << 20;

 private:
  // The next read of whole samples into `chunk_`; false at the end of the stream.
  bool read_chunk();

  const LiveOptions& live_;
  Pipeline& pipeline_;
  int fd_ = -1;
  unsigned unitsize_ = 1;
  bool ended_ = false;
  std::vector<std::uint8_t> chunk_;
  std::vector<std::uint8_t> partial_;  // a sample cut by a read
  std::vector<std::uint8_t> held_;
  LogicPlan plan_;
  std::unique_ptr<UartTap> tap_;
  std::vector<TappedLine> lines_;
};

}  // namespace pvtap::analyzer
