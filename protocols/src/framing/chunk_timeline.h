// ChunkTimeline: where each buffered chunk lies in the stream and when its bytes arrived.
#pragma once

#include <cstdint>
#include <optional>
#include <string_view>

#include "framing/ring_buffer.h"
#include "pvtap/framing/stream_reassembler.h"
#include "pvtap/statistics/bus_timing.h"

namespace pvtap::detail {

class ChunkTimeline {
 public:
  // `boundary_gap`, `segment_ends_pin`: see ReassemblerOptions (the gap already resolved).
  ChunkTimeline(const BusTiming& timing, TimestampTrust trust, double boundary_gap = 0.0,
                bool segment_ends_pin = false);

  // Records a chunk of `size` bytes that ends at stream offset `end`.
  void add(std::uint64_t end, std::size_t size, double time, Direction direction);
  // Forgets chunks that end at or before `offset`.
  void drop_before(std::uint64_t offset);
  // Nothing before the next chunk may be timed against what came before (data loss).
  void break_continuity() { have_previous_ = false; }

  double byte_end_time(std::uint64_t offset) const;  // estimated end of that byte
  // SpanTimes: when bytes first..last began and ended, and the longest silence between them.
  struct SpanTimes {
    double start;
    double end;
    double max_gap;
  };
  SpanTimes span_times(std::uint64_t first, std::uint64_t last) const {
    const Mark* m = find(first);
    if (!m) return {0.0, 0.0, 0.0};
    const double start = end_time_in(*m, first) - timing_.char_time;
    // Most frames lie inside one chunk: no further lookup and no silence inside.
    if (last < m->end) return {start, end_time_in(*m, last), 0.0};
    return {start, byte_end_time(last), max_gap_inside(first, last)};
  }
  Direction direction_at(std::uint64_t offset) const {
    if (!mixed_directions_) return marks_.empty() ? Direction::Unknown : marks_.back().direction;
    const Mark* m = find(offset);
    return m ? m->direction : Direction::Unknown;
  }
  // Silence right before the byte at `offset` (0 inside a chunk; < 0 when unknown).
  double gap_before(std::uint64_t offset) const;
  double max_gap_inside(std::uint64_t first, std::uint64_t last) const;
  // True when a silence that proves a frame boundary precedes `offset`: t3.5 with trusted
  // timing, the boundary gap with batched timing.
  bool silence_before(std::uint64_t offset) const { return proves_boundary(gap_before(offset)); }
  // True when such a silence lies between first and last.
  bool silence_inside(std::uint64_t first, std::uint64_t last) const {
    return proves_boundary(widest_gap_inside(first, last));
  }
  // True when a chunk ends right before `offset` and chunk ends pin frames (gateways).
  bool segment_ends_at(std::uint64_t offset) const {
    if (!segment_ends_pin_ || offset == 0) return false;
    const Mark* m = find(offset - 1);
    return m != nullptr && m->end == offset;
  }
  bool silent_since_last_byte(double now) const {
    return have_previous_ && proves_boundary(now - previous_time_);
  }
  // The earliest `now` at which silent_since_last_byte(now - delay) holds; nullopt when no
  // silence can prove a boundary (batched timing without a boundary gap, or no byte yet).
  std::optional<double> silence_proven_at(double delay = 0.0) const;

  bool trusted() const { return trusted_; }
  std::string_view reason() const { return reason_; }
  const BusTiming& timing() const { return timing_; }

 private:
  struct Mark {
    std::uint64_t start;
    std::uint64_t end;
    double time;
    double previous_time;  // last byte of the chunk before (valid when gap_before >= 0)
    double gap_before;     // < 0: unknown (first chunk or after a break)
    Direction direction;
  };
  const Mark* find(std::uint64_t offset) const {
    // Queries move forward through the stream: the chunk found last time usually answers.
    if (last_ && offset >= last_->start && offset < last_->end) return last_;
    return search(offset);
  }
  const Mark* search(std::uint64_t offset) const;
  // The index of the first mark that ends after `offset` (marks_.size() when none does).
  std::size_t first_ending_after(std::uint64_t offset) const;
  double widest_gap_inside(std::uint64_t first, std::uint64_t last) const;
  bool proves_boundary(double gap) const {
    if (trusted_) return gap + kGapToleranceChars * timing_.char_time >= timing_.t35;
    return boundary_gap_ > 0 && gap >= boundary_gap_;
  }
  // A silence counts as t3.5 when it is within a tenth of a character of it.
  static constexpr double kGapToleranceChars = 0.1;
  double end_time_in(const Mark& m, std::uint64_t offset) const {
    const std::uint64_t last = m.end - 1;
    const double behind = static_cast<double>(last - (offset < last ? offset : last));
    const double estimate = m.time - behind * timing_.char_time;
    // Bytes of a batched chunk cannot have ended before the previous chunk's last byte.
    if (m.gap_before < 0) return estimate;
    return estimate > m.previous_time ? estimate : m.previous_time;
  }
  void distrust(std::string_view why);

  BusTiming timing_;
  TimestampTrust mode_;
  double boundary_gap_;
  bool segment_ends_pin_;
  bool trusted_;
  std::string_view reason_;
  RingBuffer<Mark> marks_;
  mutable const Mark* last_ = nullptr;  // the mark that answered the last query
  bool mixed_directions_ = false;       // false while every chunk had the same direction
  bool have_previous_ = false;
  double previous_time_ = 0.0;
};

}  // namespace pvtap::detail
