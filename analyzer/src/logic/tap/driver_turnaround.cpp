// TurnaroundWatch: each fall of a DE channel matched to the frame that ended just before it.
#include "logic/tap/driver_turnaround.h"

#include <algorithm>

namespace pvtap::analyzer {

TurnaroundWatch::TurnaroundWatch(std::vector<std::string> drivers, double sample_rate,
                                 double char_samples)
    : drivers_(std::move(drivers)),
      sample_rate_(sample_rate),
      char_samples_(char_samples),
      position_(drivers_.size(), 0),
      falls_(drivers_.size()) {}

void TurnaroundWatch::driver_run(std::size_t driver, SampleRun run) {
  position_[driver] += run.count;
  // A high run that ends is the driver released; the recording's last run ends nothing.
  if (run.level) falls_[driver].push_back(position_[driver]);
}

// A silence of 1.5 characters may be a driver's turnaround (a reply too early still has one);
// the station is the first byte after 3.5, where frames begin.
void TurnaroundWatch::character(const UartCharacter& c) {
  const double silence =
      frames_.empty() ? 1e300
                      : static_cast<double>(c.start) - static_cast<double>(frames_.back().last_end);
  if (silence >= 3.5 * char_samples_) station_ = static_cast<std::uint8_t>(c.value);
  if (silence >= 1.5 * char_samples_) frames_.push_back(FrameEnd{station_, 0, 0});
  frames_.back().last_start = c.start;
  frames_.back().last_end = c.end;
}

// A release belongs to the frame whose last character started before it, when it comes
// within 3.5 characters of that character's end (later, the driver served something else).
void TurnaroundWatch::add_release(std::size_t driver, std::uint64_t fall,
                                  std::vector<DriverTurnaround>& out) const {
  const auto after =
      std::upper_bound(frames_.begin(), frames_.end(), fall,
                       [](std::uint64_t f, const FrameEnd& e) { return f <= e.last_start; });
  if (after == frames_.begin()) return;
  const FrameEnd& frame = *(after - 1);
  const double release = static_cast<double>(fall) - static_cast<double>(frame.last_end);
  if (release > 3.5 * char_samples_) return;
  const double us = release / sample_rate_ * 1e6;
  auto it = std::find_if(out.begin(), out.end(), [&](const DriverTurnaround& t) {
    return t.driver == drivers_[driver] && t.station == frame.station;
  });
  if (it == out.end()) {
    out.push_back(DriverTurnaround{drivers_[driver], frame.station, 0, 0, us, 0, us});
    it = out.end() - 1;
  }
  ++it->frames;
  it->truncated += release < 0 ? 1 : 0;
  it->min_us = std::min(it->min_us, us);
  it->max_us = std::max(it->max_us, us);
  it->mean_us += (us - it->mean_us) / static_cast<double>(it->frames);
}

std::vector<DriverTurnaround> TurnaroundWatch::turnarounds() const {
  std::vector<DriverTurnaround> out;
  for (std::size_t d = 0; d < drivers_.size(); ++d)
    for (std::uint64_t fall : falls_[d]) add_release(d, fall, out);
  return out;
}

}  // namespace pvtap::analyzer
