// SimRandom: the simulator's only source of chance, a SplitMix64 generator, so that one seed
// gives the same captures on every platform (std:: distributions differ between libraries).
#pragma once

#include <cstdint>

namespace pvtap::sim {

class SimRandom {
 public:
  explicit SimRandom(std::uint64_t seed) : state_(seed) {}

  std::uint64_t next() {
    std::uint64_t z = (state_ += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  // An integer in [lo, hi]; the tiny modulo bias does not matter for a simulation.
  std::int64_t between(std::int64_t lo, std::int64_t hi) {
    const auto span = static_cast<std::uint64_t>(hi - lo) + 1;
    return lo + static_cast<std::int64_t>(next() % span);
  }
  // A real number in [0, 1).
  double unit() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }
  bool percent(unsigned chance) { return between(1, 100) <= chance; }

 private:
  std::uint64_t state_;
};

}  // namespace pvtap::sim
