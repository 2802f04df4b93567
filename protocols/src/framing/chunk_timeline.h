// ChunkTimeline: when each buffered byte began and ended, and which silences end a frame.
#pragma once

#include <cstdint>
#include <optional>
#include <string_view>

#include "framing/boundary_silence.h"
#include "framing/chunk_marks.h"
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
  void drop_before(std::uint64_t offset) { marks_.drop_before(offset); }
  // Nothing before the next chunk may be timed against what came before (data loss).
  void break_continuity() { have_previous_ = false; }

  // SpanTimes: when bytes first..last began and ended, and the longest silence between them.
  struct SpanTimes {
    double start;
    double end;
    double max_gap;
  };
  SpanTimes span_times(std::uint64_t first, std::uint64_t last) const {
    const ChunkMark* m = marks_.find(first);
    if (!m) return {0.0, 0.0, 0.0};
    const double start = m->end_time(first, timing_.char_time) - timing_.char_time;
    // Most frames lie inside one chunk: no further lookup and no silence inside.
    if (last < m->end) return {start, m->end_time(last, timing_.char_time), 0.0};
    // Batched timestamps show no silence worth reporting.
    return {start, byte_end_time(last),
            silence_.trusted() ? marks_.widest_gap_inside(first, last) : 0.0};
  }
  Direction direction_at(std::uint64_t offset) const { return marks_.direction_at(offset); }
  // True when a silence that proves a frame boundary precedes `offset`: t3.5 with trusted
  // timing, the boundary gap with batched timing.
  bool silence_before(std::uint64_t offset) const {
    return silence_.proves(marks_.gap_before(offset));
  }
  // True when such a silence lies between first and last.
  bool silence_inside(std::uint64_t first, std::uint64_t last) const {
    return silence_.proves(marks_.widest_gap_inside(first, last));
  }
  // True when a chunk ends right before `offset` and chunk ends pin frames (gateways).
  bool segment_ends_at(std::uint64_t offset) const {
    if (!segment_ends_pin_ || offset == 0) return false;
    const ChunkMark* m = marks_.find(offset - 1);
    return m != nullptr && m->end == offset;
  }
  bool silent_since_last_byte(double now) const {
    return have_previous_ && silence_.proves(now - previous_time_);
  }
  // The earliest `now` at which silent_since_last_byte(now - delay) holds; nullopt when no
  // silence can prove a boundary (batched timing without a boundary gap, or no byte yet).
  std::optional<double> silence_proven_at(double delay = 0.0) const;

  bool trusted() const { return silence_.trusted(); }
  std::string_view reason() const { return silence_.reason(); }

 private:
  double byte_end_time(std::uint64_t offset) const {
    const ChunkMark* m = marks_.find(offset);
    return m ? m->end_time(offset, timing_.char_time) : 0.0;
  }

  BusTiming timing_;
  bool segment_ends_pin_;
  BoundarySilence silence_;
  ChunkMarks marks_;
  bool have_previous_ = false;
  double previous_time_ = 0.0;
};

}  // namespace pvtap::detail
