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
    : timing_(timing), segment_ends_pin_(segment_ends_pin), silence_(timing, trust, boundary_gap) {}

void ChunkTimeline::add(std::uint64_t end, std::size_t size, double time, Direction direction) {
  if (size == 0) return;
  double gap = -1.0;
  if (have_previous_) {
    const double first_start = time - static_cast<double>(size) * timing_.char_time;
    gap = first_start - previous_time_;
    if (gap < -kEarlyToleranceChars * timing_.char_time) {
      silence_.distrust(
          "chunks arrive faster than the baud rate allows: timestamps are batched (USB adapter "
          "latency or a gateway's packing)");
      gap = 0.0;
    }
    gap = std::max(gap, 0.0);
  }
  marks_.add(ChunkMark{end - size, end, time, previous_time_, gap, direction});
  previous_time_ = time;
  have_previous_ = true;
}

std::optional<double> ChunkTimeline::silence_proven_at(double delay) const {
  if (!have_previous_) return std::nullopt;
  const std::optional<double> silence = silence_.shortest();
  if (!silence) return std::nullopt;
  // The sum may round below what the rule accepts: step up to the first moment that it does,
  // so that a driver woken then always finds the silence proven.
  double now = previous_time_ + *silence + delay;
  for (int step = 0; step < 64 && std::isfinite(now); ++step) {
    if (silent_since_last_byte(now - delay)) return now;
    now = std::nextafter(now, std::numeric_limits<double>::infinity());
  }
  return std::nullopt;
}

}  // namespace pvtap::detail
