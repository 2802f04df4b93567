#include "framing/chunk_timeline.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace pvtap::detail {
namespace {

// Arrival-time noise allowed before calling a chunk "too early" for the baud rate.
constexpr double kEarlyToleranceChars = 1.0;

}  // namespace

ChunkTimeline::ChunkTimeline(const BusTiming& timing, TimestampTrust trust, double boundary_gap,
                             bool segment_ends_pin)
    : timing_(timing),
      mode_(trust),
      boundary_gap_(boundary_gap),
      segment_ends_pin_(segment_ends_pin),
      trusted_(trust != TimestampTrust::Untrusted) {
  if (trust == TimestampTrust::Untrusted) reason_ = "timestamps declared too coarse by the source";
}

void ChunkTimeline::distrust(std::string_view why) {
  if (mode_ != TimestampTrust::Auto || !trusted_) return;
  trusted_ = false;
  reason_ = why;
}

void ChunkTimeline::add(std::uint64_t end, std::size_t size, double time, Direction direction) {
  if (size == 0) return;
  double gap = -1.0;
  if (have_previous_) {
    const double first_start = time - static_cast<double>(size) * timing_.char_time;
    gap = first_start - previous_time_;
    if (gap < -kEarlyToleranceChars * timing_.char_time) {
      distrust(
          "chunks arrive faster than the baud rate allows: timestamps are batched (USB adapter "
          "latency or a gateway's packing)");
      gap = 0.0;
    }
    gap = std::max(gap, 0.0);
  }
  if (!marks_.empty() && direction != marks_.back().direction) mixed_directions_ = true;
  if (marks_.push_back(Mark{end - size, end, time, previous_time_, gap, direction})) {
    last_ = nullptr;  // the marks moved
  }
  previous_time_ = time;
  have_previous_ = true;
}

std::optional<double> ChunkTimeline::silence_proven_at(double delay) const {
  if (!have_previous_) return std::nullopt;
  double silence = 0.0;
  if (trusted_) {
    silence = timing_.t35 - kGapToleranceChars * timing_.char_time;
  } else if (boundary_gap_ > 0) {
    silence = boundary_gap_;
  } else {
    return std::nullopt;
  }
  // The sum may round below what proves_boundary() accepts: step up to the first moment that
  // it does, so that a driver woken then always finds the silence proven.
  double now = previous_time_ + silence + delay;
  for (int step = 0; step < 64 && std::isfinite(now); ++step) {
    if (silent_since_last_byte(now - delay)) return now;
    now = std::nextafter(now, std::numeric_limits<double>::infinity());
  }
  return std::nullopt;
}

void ChunkTimeline::drop_before(std::uint64_t offset) {
  // Keep the last mark: the next chunk's gap is measured from it. Popping the front leaves
  // the other marks where they are, so the cached one stays valid unless it goes.
  while (marks_.size() > 1 && marks_.front().end <= offset) {
    if (last_ == &marks_.front()) last_ = nullptr;
    marks_.pop_front();
  }
}

const ChunkTimeline::Mark* ChunkTimeline::search(std::uint64_t offset) const {
  if (marks_.empty()) return nullptr;
  const std::size_t i = first_ending_after(offset);
  last_ = i == marks_.size() ? &marks_.back() : &marks_[i];
  return last_;
}

std::size_t ChunkTimeline::first_ending_after(std::uint64_t offset) const {
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

double ChunkTimeline::byte_end_time(std::uint64_t offset) const {
  const Mark* m = find(offset);
  return m ? end_time_in(*m, offset) : 0.0;
}

double ChunkTimeline::gap_before(std::uint64_t offset) const {
  const Mark* m = find(offset);
  if (!m || m->start != offset) return 0.0;
  return m->gap_before;
}

double ChunkTimeline::max_gap_inside(std::uint64_t first, std::uint64_t last) const {
  return trusted_ ? widest_gap_inside(first, last) : 0.0;
}

double ChunkTimeline::widest_gap_inside(std::uint64_t first, std::uint64_t last) const {
  double widest = 0.0;
  for (std::size_t i = first_ending_after(first); i < marks_.size() && marks_[i].start <= last;
       ++i) {
    if (marks_[i].start > first) widest = std::max(widest, marks_[i].gap_before);
  }
  return widest;
}

}  // namespace pvtap::detail
