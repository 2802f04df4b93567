// LineProbe: the channels asked for, each fed to a line detector until its stretch is full.
#include "logic/plan/line_probe.h"

#include <algorithm>

#include "logic/plan/channel_pairing.h"

namespace pvtap::analyzer {

LineProbe::LineProbe(std::vector<std::string> names) : names_(std::move(names)) {}

void LineProbe::begin(const std::vector<LogicChannel>& channels, double sample_rate) {
  available_ = channels;
  sample_rate_ = sample_rate;
  std::vector<unsigned> bits;
  for (const LogicChannel& c : channels) {
    const bool asked =
        names_.empty() || std::find(names_.begin(), names_.end(), c.name) != names_.end();
    if (!asked || c.index >= 64) continue;
    probed_.push_back(ProbedChannel{c, std::nullopt, {}, 0});
    bits.push_back(c.index);
  }
  for (const std::string& name : names_) {
    const bool found = std::any_of(channels.begin(), channels.end(),
                                   [&](const LogicChannel& c) { return c.name == name; });
    if (!found) missing_.push_back(name);
  }
  detectors_.resize(probed_.size());
  full_.assign(probed_.size(), false);
  scanner_ = std::make_unique<EdgeScanner>(std::move(bits));
}

void LineProbe::samples(std::span<const std::uint8_t> data, unsigned unitsize) {
  if (scanner_) scanner_->scan(data, unitsize, *this);
}

bool LineProbe::wants_more() const {
  if (!scanner_) return true;
  if (!missing_.empty()) return false;  // the run is refused anyway
  return std::find(full_.begin(), full_.end(), false) != full_.end();
}

void LineProbe::run(std::size_t slot, SampleRun run) {
  if (!full_[slot]) full_[slot] = !detectors_[slot].add(run);
}

void LineProbe::finish() {
  if (!scanner_) return;
  scanner_->finish(*this);
  if (sample_rate_ <= 0) return;
  for (std::size_t i = 0; i < probed_.size(); ++i) {
    probed_[i].line = detectors_[i].decide(sample_rate_);
    for (const SampleRun& r : detectors_[i].runs()) probed_[i].probed += r.count;
    if (probed_[i].line) probed_[i].bursts = bursts_of(detectors_[i].runs(), *probed_[i].line);
  }
}

}  // namespace pvtap::analyzer
