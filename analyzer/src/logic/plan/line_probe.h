// The first pass over a logic recording: which channels carry a UART, and its settings, found
// from each channel's first stretch of samples (reading stops once every channel has one).
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "logic/input/edge_scanner.h"
#include "logic/input/sigrok_file.h"
#include "pvtap/uart/line_detector.h"

namespace pvtap::analyzer {

// Burst: samples [start, end) of a channel where characters follow each other closely.
struct Burst {
  std::uint64_t start = 0, end = 0;
};

// ProbedChannel: a channel and what its samples say.
struct ProbedChannel {
  LogicChannel channel;
  std::optional<DetectedLine> line;  // nullopt: no pulse common enough to be a bit
  std::vector<Burst> bursts;         // in the stretch probed, for pairing directions
  std::uint64_t probed = 0;          // samples the stretch covers
};

class LineProbe final : public LogicSink, private RunConsumer {
 public:
  // `names`: the channels to probe (--channels); empty for every logic channel.
  explicit LineProbe(std::vector<std::string> names);

  void begin(const std::vector<LogicChannel>& channels, double sample_rate) override;
  void samples(std::span<const std::uint8_t> data, unsigned unitsize) override;
  bool wants_more() const override;
  // After reading: decides every channel. The names asked for that the file lacks, if any.
  void finish();

  const std::vector<ProbedChannel>& channels() const { return probed_; }
  const std::vector<std::string>& missing() const { return missing_; }
  const std::vector<LogicChannel>& available() const { return available_; }
  double sample_rate() const { return sample_rate_; }

 private:
  void run(std::size_t slot, SampleRun run) override;

  std::vector<std::string> names_;
  std::vector<LogicChannel> available_;
  std::vector<std::string> missing_;
  std::vector<ProbedChannel> probed_;
  std::vector<LineDetector> detectors_;
  std::vector<bool> full_;
  std::unique_ptr<EdgeScanner> scanner_;
  double sample_rate_ = 0;
};

}  // namespace pvtap::analyzer
