#include "pvtap/statistics/poll_masters.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "pvtap/statistics/timing_statistics.h"

namespace pvtap {
namespace {

constexpr double kBinWidth = 0.05;  // relative width of an interval bin
constexpr double kShortest = 1e-4;  // seconds: shorter intervals share the lowest bin

std::int32_t bin_of(double interval) {
  return static_cast<std::int32_t>(
      std::floor(std::log(std::max(interval, kShortest)) / std::log1p(kBinWidth)));
}

// Whether `cycle` is a whole multiple of `base` (base <= cycle).
bool multiple_of(double cycle, double base) {
  const double ratio = cycle / base;
  const double k = std::max(1.0, std::round(ratio));
  return std::abs(ratio / k - 1.0) <= kSameMasterTolerance;
}

}  // namespace

namespace {
constexpr double kMedianFirstBin = 1e-3;  // seconds
constexpr double kMedianRatio = 1.4;
}  // namespace

void CoarseMedian::add(double seconds) {
  double edge = kMedianFirstBin;
  std::size_t bin = 0;
  while (bin + 1 < kBins && seconds >= edge) {
    edge *= kMedianRatio;
    ++bin;
  }
  ++bins_[bin];
  ++n_;
}

void CoarseMedian::merge(const CoarseMedian& other) {
  for (std::size_t i = 0; i < kBins; ++i) bins_[i] += other.bins_[i];
  n_ += other.n_;
}

std::optional<double> CoarseMedian::median() const {
  if (n_ == 0) return std::nullopt;
  std::uint64_t seen = 0;
  double low = 0, high = kMedianFirstBin;
  for (std::size_t i = 0; i < kBins; ++i) {
    seen += bins_[i];
    if (2 * seen >= n_) return i == 0 ? high / 2 : std::sqrt(low * high);
    low = high;
    high *= kMedianRatio;
  }
  return low;
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
