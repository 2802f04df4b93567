#include "pvtap/statistics/poll_masters.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <numeric>

#include "pvtap/statistics/timing_statistics.h"

namespace pvtap {
namespace {

constexpr double kShortest = 1e-4;  // seconds: shorter intervals share the lowest bin

// The bin of an interval from its binary exponent and the top four bits of its mantissa: 16
// bins an octave, 3-6 % wide, with no logarithm on the hot path.
std::int32_t bin_of(double interval) {
  const auto bits = std::bit_cast<std::uint64_t>(std::max(interval, kShortest));
  return static_cast<std::int32_t>(bits >> 48);  // sign (0), exponent, 4 mantissa bits
}

// How far `cycle` is from a whole multiple of `base` (base <= cycle), in units of base; a
// cycle of k rounds gathers the overruns of k rounds, so the tolerance grows from
// kSameMasterTolerance for one round to a quarter of a round for several.
double misfit(double cycle, double base) {
  const double ratio = cycle / base;
  const double k = std::max(1.0, std::round(ratio));
  const double tolerance = k < 2 ? kSameMasterTolerance : kSeveralRoundsTolerance;
  return std::abs(ratio - k) / tolerance;  // <= 1: fits
}

bool multiple_of(double cycle, double base) {
  return misfit(cycle, base) <= 1.0;
}

}  // namespace

namespace {
constexpr std::int64_t kMillisecondExponent = 1013;  // the binary exponent field of 2^-10 s
}  // namespace

void CoarseMedian::add(double seconds) {
  // Half octaves from 2^-10 s (about 1 ms): the exponent field, and the mantissa's top bit
  // (1.5 and above), with no logarithm on the hot path.
  const auto bits = std::bit_cast<std::uint64_t>(std::max(seconds, 0.0));
  const auto half_octaves = 2 * (static_cast<std::int64_t>(bits >> 52) - kMillisecondExponent) +
                            static_cast<std::int64_t>((bits >> 51) & 1) - 1;
  const auto bin = std::clamp<std::int64_t>(half_octaves, 0, kBins - 1);
  ++bins_[static_cast<std::size_t>(bin)];
  ++n_;
}

void CoarseMedian::merge(const CoarseMedian& other) {
  for (std::size_t i = 0; i < kBins; ++i) bins_[i] += other.bins_[i];
  n_ += other.n_;
}

std::optional<double> CoarseMedian::median() const {
  if (n_ == 0) return std::nullopt;
  // Bin b >= 1 begins at 2^-10 s times 2^((b+1)/2), or 1.5 times that when b+1 is odd.
  const auto lower = [](std::size_t b) {
    if (b == 0) return 0.0;
    const std::size_t h = b + 1;
    return std::ldexp(h % 2 ? 1.5 : 1.0, static_cast<int>(h / 2) - 10);
  };
  std::uint64_t seen = 0;
  for (std::size_t b = 0; b < kBins; ++b) {
    seen += bins_[b];
    if (2 * seen < n_) continue;
    if (b == 0) return lower(1) / 2;
    return std::sqrt(lower(b) * lower(b + 1));
  }
  return lower(kBins - 1);
}

void ModalInterval::add(double interval) {
  ++n_;
  const std::int32_t bin = bin_of(interval);
  Slot* free = nullptr;
  for (Slot& s : slots_) {
    if (s.count > 0 && s.bin == bin) {
      ++s.count;
      s.sum += interval;
      return;
    }
    if (s.count == 0 && !free) free = &s;
  }
  if (free) {
    *free = Slot{bin, 1, interval};
    return;
  }
  // Misra-Gries: every counter loses one, and the new interval is not kept.
  for (Slot& s : slots_) {
    s.sum -= s.sum / s.count;
    --s.count;
  }
}

std::pair<std::uint64_t, double> ModalInterval::modal() const {
  const Slot* top = nullptr;
  for (const Slot& s : slots_)
    if (s.count > 0 && (!top || s.count > top->count)) top = &s;
  if (!top) return {0, 0.0};
  std::uint64_t count = 0;
  double sum = 0;
  for (const Slot& s : slots_) {
    if (s.count == 0 || std::abs(s.bin - top->bin) > 1) continue;
    count += s.count;
    sum += s.sum;
  }
  return {count, sum};
}

std::optional<double> ModalInterval::mode() const {
  const auto [count, sum] = modal();
  if (count == 0) return std::nullopt;
  return sum / static_cast<double>(count);
}

std::optional<double> ModalInterval::cycle() const {
  const auto [count, sum] = modal();
  if (count == 0 || count * 100 < n_ * kRegularPercent) return std::nullopt;
  return sum / static_cast<double>(count);
}

std::vector<MasterPlan> recognise_masters(std::span<const PollPeriod> polls) {
  std::vector<std::size_t> cycled;
  std::vector<std::size_t> loose;
  for (std::size_t i = 0; i < polls.size(); ++i) {
    const bool has_cycle = polls[i].cycle && polls[i].period.intervals >= kMinCycleIntervals;
    (has_cycle ? cycled : loose).push_back(i);
  }
  std::stable_sort(cycled.begin(), cycled.end(),
                   [&](std::size_t a, std::size_t b) { return *polls[a].cycle < *polls[b].cycle; });
  std::vector<MasterPlan> masters;
  for (const std::size_t i : cycled) {
    const double cycle = *polls[i].cycle;
    const auto same = std::find_if(masters.begin(), masters.end(), [&](const MasterPlan& m) {
      return multiple_of(cycle, m.period);
    });
    if (same != masters.end()) {
      same->polls.push_back(i);
    } else {
      masters.push_back(MasterPlan{cycle, {i}, 0, 0, std::nullopt});
    }
  }
  if (masters.empty() && !loose.empty()) masters.emplace_back();
  std::uint64_t total = 0;
  for (MasterPlan& m : masters)
    for (const std::size_t i : m.polls) m.requests += polls[i].requests;
  if (!masters.empty()) {
    auto busiest = std::max_element(
        masters.begin(), masters.end(),
        [](const MasterPlan& a, const MasterPlan& b) { return a.requests < b.requests; });
    for (const std::size_t i : loose) {
      auto home = busiest;
      if (polls[i].mode && masters.size() > 1) {
        const double mode = *polls[i].mode;
        const auto fits = std::find_if(masters.begin(), masters.end(), [&](const MasterPlan& m) {
          return mode >= m.period * (1 - kSameMasterTolerance) && multiple_of(mode, m.period);
        });
        if (fits != masters.end()) home = fits;
      }
      home->polls.push_back(i);
      home->requests += polls[i].requests;
    }
  }
  for (const MasterPlan& m : masters) total += m.requests;
  for (MasterPlan& m : masters) {
    std::sort(m.polls.begin(), m.polls.end());
    m.share = total ? static_cast<double>(m.requests) / static_cast<double>(total) : 0.0;
    CoarseMedian turnaround;
    for (const std::size_t i : m.polls) turnaround.merge(polls[i].turnaround);
    m.turnaround = turnaround.median();
  }
  std::stable_sort(masters.begin(), masters.end(), [](const MasterPlan& a, const MasterPlan& b) {
    return a.requests > b.requests;
  });
  return masters;
}

}  // namespace pvtap
