// EdgeScanner: edges found by comparing samples, runs given out per channel.
#include "logic/input/edge_scanner.h"

#include <algorithm>
#include <cstring>

namespace pvtap::analyzer {
namespace {

constexpr std::uint64_t kEveryByte = 0x0101010101010101ull;

std::uint64_t sample_at(const std::uint8_t* p, unsigned unitsize) {
  std::uint64_t s = 0;
  std::memcpy(&s, p, unitsize < 8 ? unitsize : 8);
  return s;
}

}  // namespace

EdgeScanner::EdgeScanner(std::vector<unsigned> bits)
    : bits_(std::move(bits)), run_start_(bits_.size(), 0) {
  for (unsigned b : bits_) mask_ |= 1ull << b;
}

// `sample` (masked) differs from the last one at position_: the channels that changed end
// their runs there.
void EdgeScanner::edge(std::uint64_t sample, RunConsumer& out) {
  const std::uint64_t changed = sample ^ last_;
  for (std::size_t i = 0; i < bits_.size(); ++i) {
    if ((changed >> bits_[i] & 1u) == 0) continue;
    out.run(i, SampleRun{(last_ >> bits_[i] & 1u) != 0, position_ - run_start_[i]});
    run_start_[i] = position_;
  }
  last_ = sample;
}

// Whether the 8 * `words` samples at `p` all equal the last one in the channels' bits.
template <int words>
bool quiet(const std::uint8_t* p, std::uint64_t want, std::uint64_t mask8) {
  std::uint64_t differ = 0;
  for (int w = 0; w < words; ++w) {
    std::uint64_t word = 0;
    std::memcpy(&word, p + 8 * w, 8);
    differ |= word ^ want;
  }
  return (differ & mask8) == 0;
}

// One byte a sample: quiet stretches are passed over 32 samples to a comparison, then 8; the
// samples around an edge are compared one by one.
void EdgeScanner::scan_bytes(std::span<const std::uint8_t> data, RunConsumer& out) {
  const std::uint64_t mask8 = (mask_ & 0xFF) * kEveryByte;
  const std::uint8_t* p = data.data();
  const std::size_t n = data.size();
  const std::uint64_t base = position_;
  std::size_t i = 0;
  while (i < n) {
    const std::uint64_t want = last_ * kEveryByte;
    while (i + 32 <= n && quiet<4>(p + i, want, mask8)) i += 32;
    while (i + 8 <= n && quiet<1>(p + i, want, mask8)) i += 8;
    for (const std::size_t stop = std::min(n, i + 8); i < stop;) {
      const std::uint64_t s = p[i++] & mask_;
      if (s == last_) continue;
      position_ = base + i - 1;
      edge(s, out);
      break;
    }
  }
  position_ = base + n;
}

void EdgeScanner::scan(std::span<const std::uint8_t> data, unsigned unitsize, RunConsumer& out) {
  if (unitsize == 0 || data.size() < unitsize) return;
  if (!started_) {
    last_ = sample_at(data.data(), unitsize) & mask_;
    started_ = true;
  }
  if (unitsize == 1) {
    scan_bytes(data, out);
    return;
  }
  for (std::size_t i = 0; i + unitsize <= data.size(); i += unitsize, ++position_) {
    const std::uint64_t s = sample_at(data.data() + i, unitsize) & mask_;
    if (s != last_) edge(s, out);
  }
}

void EdgeScanner::finish(RunConsumer& out) {
  for (std::size_t i = 0; i < bits_.size(); ++i) {
    if (position_ > run_start_[i]) {
      out.run(i, SampleRun{(last_ >> bits_[i] & 1u) != 0, position_ - run_start_[i]});
    }
    run_start_[i] = position_;
  }
}

}  // namespace pvtap::analyzer
