// Runs of one level per channel from interleaved logic samples: the only per-sample work of a
// logic recording, a comparison of each sample with the one before (eight at a time where the
// line is quiet).
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "pvtap/uart/uart_decoder.h"

namespace pvtap::analyzer {

// RunConsumer: receives each channel's runs in order; `slot` is the channel's place in the
// scanner's list.
class RunConsumer {
 public:
  virtual ~RunConsumer() = default;
  virtual void run(std::size_t slot, SampleRun run) = 0;
};

class EdgeScanner {
 public:
  // The channels' bits in a sample (below 64).
  explicit EdgeScanner(std::vector<unsigned> bits);

  // Whole samples of `unitsize` bytes; a run is given out when its level ends.
  void scan(std::span<const std::uint8_t> data, unsigned unitsize, RunConsumer& out);
  // End of samples: each channel's last run.
  void finish(RunConsumer& out);

 private:
  void edge(std::uint64_t sample, RunConsumer& out);
  void scan_bytes(std::span<const std::uint8_t> data, RunConsumer& out);

  std::vector<unsigned> bits_;
  std::uint64_t mask_ = 0;
  std::uint64_t position_ = 0;  // samples scanned
  std::uint64_t last_ = 0;      // the last sample, masked
  bool started_ = false;
  std::vector<std::uint64_t> run_start_;
};

}  // namespace pvtap::analyzer
