// A recording's samples kept while it is probed, so that one the probe read whole is decoded
// from memory instead of being read (and inflated) a second time.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "logic/input/sigrok_file.h"
#include "logic/plan/line_probe.h"

namespace pvtap::analyzer {

// HeldSamples: the recording's samples as the file yielded them, chunk by chunk.
struct HeldSamples {
  std::vector<LogicChannel> channels;
  double sample_rate = 0;
  unsigned unitsize = 1;
  // As the file yielded them: a chunk each, so that holding never copies what it holds.
  std::vector<std::vector<std::uint8_t>> chunks;
  std::size_t bytes = 0;
  bool whole = false;  // every sample of the recording is here

  // Gives `sink` the recording as the file did: begin, then each chunk.
  void replay(LogicSink& sink) const;
};

// SampleHold: feeds the probe and keeps what it is given, up to `limit` bytes. Once the probe
// is satisfied it keeps reading only while the rest may still fit: a short recording is then
// held whole, a long one is given up at the limit and read again.
class SampleHold final : public LogicSink {
 public:
  SampleHold(LineProbe& probe, std::size_t limit) : probe_(probe), limit_(limit) {}

  void begin(const std::vector<LogicChannel>& channels, double sample_rate) override;
  void samples(std::span<const std::uint8_t> data, unsigned unitsize) override;
  bool wants_more() const override;

  // After the file was read without an error: what was held (whole, or nothing).
  HeldSamples take();

 private:
  LineProbe& probe_;
  std::size_t limit_;
  bool keeping_ = true;
  HeldSamples held_;
};

}  // namespace pvtap::analyzer
