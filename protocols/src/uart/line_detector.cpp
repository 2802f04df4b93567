// LineDetector: the idle level from where the samples lie, the rate from the pulses, the
// format from which reading makes frames check.
#include "pvtap/uart/line_detector.h"

#include <array>

namespace pvtap {
namespace {

constexpr std::array<UartFormat, 4> kCandidates = {
    UartFormat{8, Parity::None, 2, false}, UartFormat{8, Parity::Even, 1, false},
    UartFormat{8, Parity::Odd, 1, false}, UartFormat{8, Parity::None, 1, false}};

// A channel talks when it gives frames that check, or mostly clean characters of more than
// one value (a clock reads as clean 0x55 characters in 8N1: a square wave is exactly that).
constexpr std::uint64_t kMinCharacters = 4;

// In a reading of the wrong polarity a frame checks only by a CRC's chance (1 in 65,536 for
// each place the framing tries): where this many check, the other polarity is not read (on a
// line with glitches, its noise would add a third to the probe's work).
constexpr std::uint64_t kSureFrames = 4;

bool talks(const FormatTrial& t) {
  if (t.good_frames > 0) return true;
  return t.characters >= kMinCharacters && t.line_errors * 4 <= t.characters &&
         t.distinct_values > 1;
}

// A line held idle rests at mark: the level most samples are at. Only a guess: a bus line
// without failsafe bias rests in space between frames, wherever no driver holds it.
bool idles_low(std::span<const SampleRun> runs) {
  std::uint64_t high = 0;
  std::uint64_t low = 0;
  for (const SampleRun& r : runs) (r.level ? high : low) += r.count;
  return low > high;
}

// The first and last runs are cut by the session's edges: their widths are not pulses.
std::vector<std::uint64_t> pulse_widths(std::span<const SampleRun> runs) {
  std::vector<std::uint64_t> widths;
  if (runs.size() < 3) return widths;
  widths.reserve(runs.size() - 2);
  for (std::size_t i = 1; i + 1 < runs.size(); ++i) widths.push_back(runs[i].count);
  return widths;
}

// Every candidate format at one polarity: the best reading into `d`.
void try_formats(DetectedLine& d, bool inverted, std::span<const SampleRun> runs,
                 DialectSet dialects) {
  bool first = true;
  for (UartFormat format : kCandidates) {
    format.inverted = inverted;
    UartLine line = d.line;
    line.format = format;
    const FormatTrial trial = try_format(line, runs, dialects);
    if (first || trial.better_than(d.trial)) {
      d.trial = trial;
      d.line.format = format;
      first = false;
    }
  }
}

// The frames that check at one polarity, read once at 8N1: the loosest candidate reads the
// data bits of all four right, so its frames check wherever that polarity is the line's.
std::uint64_t frames_at(const DetectedLine& d, bool inverted, std::span<const SampleRun> runs,
                        DialectSet dialects) {
  UartLine line = d.line;
  line.format = UartFormat{8, Parity::None, 1, inverted};
  return try_format(line, runs, dialects).good_frames;
}

}  // namespace

bool LineDetector::add(SampleRun run) {
  if (!runs_.empty() && runs_.back().level == run.level) {
    runs_.back().count += run.count;
  } else {
    runs_.push_back(run);
  }
  return runs_.size() < kStretchRuns;
}

std::span<const UartFormat> LineDetector::candidates() {
  return kCandidates;
}

std::optional<DetectedLine> LineDetector::decide(double sample_rate, DialectSet dialects) const {
  const std::optional<BaudEstimate> baud = estimate_baud(pulse_widths(runs_), sample_rate);
  if (!baud) return std::nullopt;
  DetectedLine d;
  d.baud = *baud;
  d.line.sample_rate = sample_rate;
  d.line.baud = baud->measured;
  // The polarity is the reading whose frames check; the idle level only breaks a tie. A bus
  // line that rests in space between frames, its drivers pulsing as they switch, idles "low".
  const bool idle_low = idles_low(runs_);
  try_formats(d, idle_low, runs_, dialects);
  const bool sure = d.trial.good_frames >= kSureFrames;
  if (!sure && frames_at(d, !idle_low, runs_, dialects) > d.trial.good_frames) {
    d.trial = FormatTrial{};
    try_formats(d, !idle_low, runs_, dialects);
  }
  d.has_traffic = talks(d.trial);
  return d;
}

}  // namespace pvtap
