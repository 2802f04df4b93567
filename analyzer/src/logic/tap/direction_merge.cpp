// DirectionMerge: an ordered queue released up to the lower of the two sides' watermarks.
#include "logic/tap/direction_merge.h"

#include <algorithm>

namespace pvtap::analyzer {
namespace {

// A side silent for ever (a slave that never answers) must not hold the other's traffic
// without bound: past this many, the oldest go anyway.
constexpr std::size_t kMostWaiting = 4096;

}  // namespace

void DirectionMerge::add(std::size_t side, const UartCharacter& c) {
  const DirectedCharacter d{c, side == 0 ? Direction::ToSlave : Direction::FromSlave};
  // Each side comes in order: the place is near the back.
  auto at = pending_.end();
  while (at != pending_.begin() && (at - 1)->character.start > c.start) --at;
  pending_.insert(at, d);
}

void DirectionMerge::release(std::vector<DirectedCharacter>& out) {
  const std::uint64_t safe = std::min(watermark_[0], watermark_[1]);
  while (!pending_.empty() &&
         (pending_.front().character.start < safe || pending_.size() > kMostWaiting)) {
    out.push_back(pending_.front());
    pending_.pop_front();
  }
}

void DirectionMerge::finish(std::vector<DirectedCharacter>& out) {
  out.insert(out.end(), pending_.begin(), pending_.end());
  pending_.clear();
}

}  // namespace pvtap::analyzer
