#include "framing/chunk_marks.h"

#include <algorithm>

namespace pvtap::detail {

void ChunkMarks::add(const ChunkMark& mark) {
  if (!marks_.empty() && mark.direction != marks_.back().direction) mixed_directions_ = true;
  if (marks_.push_back(mark)) last_ = nullptr;  // the marks moved
}

void ChunkMarks::drop_before(std::uint64_t offset) {
  // Keep the last mark: the next chunk's gap is measured from it. Popping the front leaves
  // the other marks where they are, so the cached one stays valid unless it goes.
  while (marks_.size() > 1 && marks_.front().end <= offset) {
    if (last_ == &marks_.front()) last_ = nullptr;
    marks_.pop_front();
  }
}

const ChunkMark* ChunkMarks::search(std::uint64_t offset) const {
  if (marks_.empty()) return nullptr;
  const std::size_t i = first_ending_after(offset);
  last_ = i == marks_.size() ? &marks_.back() : &marks_[i];
  return last_;
}

std::size_t ChunkMarks::first_ending_after(std::uint64_t offset) const {
  // The reassembler keeps a few chunks buffered: walking them beats a binary search, which
  // stays for the long buffers of noise.
  constexpr std::size_t kWalk = 8;
  if (marks_.size() <= kWalk) {
    std::size_t i = 0;
    while (i < marks_.size() && !(offset < marks_[i].end)) ++i;
    return i;
  }
  std::size_t low = 0;
  std::size_t high = marks_.size();
  while (low < high) {
    const std::size_t mid = low + (high - low) / 2;
    if (offset < marks_[mid].end) {
      high = mid;
    } else {
      low = mid + 1;
    }
  }
  return low;
}

double ChunkMarks::gap_before(std::uint64_t offset) const {
  const ChunkMark* m = find(offset);
  if (!m || m->start != offset) return 0.0;
  return m->gap_before;
}

double ChunkMarks::widest_gap_inside(std::uint64_t first, std::uint64_t last) const {
  double widest = 0.0;
  for (std::size_t i = first_ending_after(first); i < marks_.size() && marks_[i].start <= last;
       ++i) {
    if (marks_[i].start > first) widest = std::max(widest, marks_[i].gap_before);
  }
  return widest;
}

}  // namespace pvtap::detail
