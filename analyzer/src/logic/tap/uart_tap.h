// The second pass over a logic recording: each UART channel decoded with its settings, every
// character fed to its bus with its own time, and the line's errors counted.
#pragma once

#include <memory>
#include <vector>

#include "events/event_writer.h"
#include "logic/input/edge_scanner.h"
#include "logic/input/sigrok_file.h"
#include "logic/tap/direction_merge.h"
#include "logic/tap/driver_turnaround.h"
#include "pvtap/session/bus_session.h"
#include "pvtap/uart/driver_glitches.h"
#include "pvtap/uart/line_detector.h"
#include "report/serial_line_report.h"

namespace pvtap::analyzer {

// TappedChannel: a channel, how to read it, and the bus its characters go to.
struct TappedChannel {
  LogicChannel channel;
  DetectedLine line;
  BusSession* bus = nullptr;
  std::string bus_name;  // as the report names `bus`
  // One direction of a bus on two channels: the pair's index and its side (0: requests,
  // 1: replies); none for a channel that is a bus of its own.
  int pair = -1;
  std::size_t side = 0;
};

// TappedLine: a channel's serial line and the bus it feeds.
struct TappedLine {
  std::string bus;
  SerialLineReport line;
};

class UartTap final : public LogicSink, private RunConsumer {
 public:
  // Characters, line errors and driver glitches go to each channel's bus. `drivers`: DE
  // channels whose releases are timed against the first channel's frames.
  UartTap(std::vector<TappedChannel> channels, std::vector<LogicChannel> drivers,
          double sample_rate);

  void begin(const std::vector<LogicChannel>& channels, double sample_rate) override;
  void samples(std::span<const std::uint8_t> data, unsigned unitsize) override;
  // After reading: the last characters decided and fed.
  void finish();

  // The time of the last sample read, in seconds from the recording's start.
  double end_time() const;
  std::uint64_t chunks() const { return chunks_; }  // of samples, as libsigrok handed them
  // Each channel's line, in the order given.
  std::vector<TappedLine> lines() const;

 private:
  struct Slot {
    TappedChannel tapped;
    UartDecoder decoder;
    DriverGlitchFilter glitch_filter;
    SerialLineReport report;
  };
  void run(std::size_t slot, SampleRun run) override;
  void deliver(Slot& s);
  void feed_bus(Slot& s, bool first);
  void report_line_error(const Slot& s, const UartCharacter& c);
  void feed_pair(Slot& s);
  void feed_merged(BusSession& bus);

  std::vector<Slot> slots_;
  double sample_rate_;
  EdgeScanner scanner_;
  TurnaroundWatch turnaround_;
  std::vector<DirectionMerge> pairs_;
  std::vector<DirectedCharacter> merged_;  // scratch
  // Scratch, reused for every run: decoded characters, then those of ended runs and glitches.
  std::vector<UartCharacter> characters_, bus_characters_;
  std::vector<DriverGlitch> glitches_;
  std::uint64_t chunks_ = 0;
};

}  // namespace pvtap::analyzer
