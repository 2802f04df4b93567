// The masters of a bus, told apart by their poll cycles.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <utility>
#include <vector>

#include "pvtap/codec/dialect.h"

namespace pvtap {

struct PollBlock;
struct PollPeriod;

// ModalInterval: the most frequent interval of an event stream (its cycle), in constant memory.
// Intervals are put in bins 3-6 % wide (16 an octave) and counted with the Misra-Gries summary of
// kSlots counters, which keeps any bin holding more than 1/(kSlots+1) of the intervals. A poll
// cycle survives the longer intervals that a lost reply or a busy bus put into some rounds,
// which move a mean but not a mode.
class ModalInterval {
 public:
  static constexpr std::size_t kSlots = 6;
  // A cycle is regular when this share of the intervals (in percent) is within a bin of it.
  static constexpr std::uint64_t kRegularPercent = 50;

  void add(double interval);
  // The mean of the intervals in the modal bin and its two neighbours; nullopt without
  // intervals or when those hold less than kRegularPercent of them (no regular cycle: a
  // master whose rounds overrun their period now and then).
  std::optional<double> cycle() const;
  // The same without the regularity test: where most intervals fall, if anywhere.
  std::optional<double> mode() const;
  std::uint64_t intervals() const { return n_; }

 private:
  struct Slot {
    std::int32_t bin = 0;
    std::uint32_t count = 0;
    double sum = 0;
  };
  // The modal bin and its neighbours: their count and the sum of their intervals.
  std::pair<std::uint64_t, double> modal() const;

  std::array<Slot, kSlots> slots_{};
  std::uint64_t n_ = 0;
};

// CoarseMedian: the median of short durations (a master's turnaround) within a bin of 33-50 %,
// in 96 bytes: half-octave bins from about 1 ms (2^-10 s) up (the last one open-ended).
class CoarseMedian {
 public:
  static constexpr std::size_t kBins = 24;
  void add(double seconds);
  void merge(const CoarseMedian& other);
  std::uint64_t count() const { return n_; }
  std::optional<double> median() const;  // the geometric centre of the median's bin

 private:
  std::array<std::uint32_t, kBins> bins_{};
  std::uint64_t n_ = 0;
};

// MasterPlan: one master recognised from its poll plan: the blocks it polls in one cycle.
struct MasterPlan {
  double period = 0;               // its cycle, seconds (0: none measured, its blocks polled once)
  std::vector<std::size_t> polls;  // indexes into TimingReport::poll_periods
  std::uint64_t requests = 0;      // good requests of its blocks
  double share = 0;                // of the bus's good requests
  // From a reply's end to its next request, seconds: the median over its blocks (where the
  // frame before its request was another master's reply, that one counts too).
  std::optional<double> turnaround;
};

// Two cycles belong to one master when one is a whole multiple of the other (a logger reads
// fast values every round and slow ones every tenth) within this relative tolerance.
// For a cycle of several rounds (whose overruns add up), a quarter of a round.
inline constexpr double kSameMasterTolerance = 0.06;
inline constexpr double kSeveralRoundsTolerance = 0.25;
// A block needs this many intervals before its cycle names a master.
inline constexpr std::uint64_t kMinCycleIntervals = 3;

// The masters of a bus from its poll blocks (sorted by requests, the busiest first). A block
// without a regular cycle of its own goes to the master whose cycle its most frequent interval
// fits (a block that another master's collisions disturbed), else to the busiest master (a
// block read once at start-up). Cycles that are no whole multiples of each other are independent
// masters; two masters whose periods are whole multiples of each other are taken for one.
std::vector<MasterPlan> recognise_masters(std::span<const PollPeriod> polls);

}  // namespace pvtap
