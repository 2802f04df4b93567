// SampleHold: the probe's reading, kept while it fits.
#include "logic/input/sample_hold.h"

namespace pvtap::analyzer {

void HeldSamples::replay(LogicSink& sink) const {
  sink.begin(channels, sample_rate);
  for (const std::vector<std::uint8_t>& chunk : chunks) sink.samples(chunk, unitsize);
}

void SampleHold::begin(const std::vector<LogicChannel>& channels, double sample_rate) {
  held_.channels = channels;
  held_.sample_rate = sample_rate;
  probe_.begin(channels, sample_rate);
}

void SampleHold::samples(std::span<const std::uint8_t> data, unsigned unitsize) {
  // Read on past a satisfied probe only to keep the rest: the tap scans it when replayed.
  if (probe_.wants_more()) probe_.samples(data, unitsize);
  if (!keeping_) return;
  if (held_.bytes + data.size() > limit_) {
    keeping_ = false;
    held_.chunks = {};
    return;
  }
  held_.unitsize = unitsize;
  held_.chunks.emplace_back(data.begin(), data.end());
  held_.bytes += data.size();
}

bool SampleHold::wants_more() const {
  // A refused probe (a channel name the file lacks) needs nothing more.
  if (!probe_.missing().empty()) return false;
  return probe_.wants_more() || keeping_;
}

HeldSamples SampleHold::take() {
  // Reading stops early only once keeping has failed: anything still kept is the whole file.
  held_.whole = keeping_ && probe_.missing().empty();
  if (!held_.whole) held_.chunks = {};
  return std::move(held_);
}

}  // namespace pvtap::analyzer
