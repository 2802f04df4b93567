// ChunkTimeline: where each buffered chunk lies in the stream and when its bytes arrived.
#pragma once

#include <cstdint>
#include <deque>
#include <string_view>

#include "pvtap/bus_timing.h"
#include "pvtap/stream_reassembler.h"

namespace pvtap::detail {

class ChunkTimeline {
 public:
  ChunkTimeline(std::uint32_t baud, TimestampTrust trust);

  // Records a chunk of `size` bytes that ends at stream offset `end`.
  void add(std::uint64_t end, std::size_t size, double time, Direction direction);
  // Forgets chunks that end at or before `offset`.
  void drop_before(std::uint64_t offset);
  // Nothing before the next chunk may be timed against what came before (data loss).
  void break_continuity() { have_previous_ = false; }

  double byte_end_time(std::uint64_t offset) const;  // estimated end of that byte
  Direction direction_at(std::uint64_t offset) const;
  // Silence right before the byte at `offset` (0 inside a chunk; < 0 when unknown).
  double gap_before(std::uint64_t offset) const;
  double max_gap_inside(std::uint64_t first, std::uint64_t last) const;
  // True when timing is trusted and a silence of at least t3.5 precedes `offset`.
  bool silence_before(std::uint64_t offset) const;
  bool silent_since_last_byte(double now) const;

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
  const Mark* find(std::uint64_t offset) const;
  void distrust(std::string_view why);

  BusTiming timing_;
  TimestampTrust mode_;
  bool trusted_;
  std::string_view reason_;
  std::deque<Mark> marks_;
  mutable const Mark* last_ = nullptr;  // the mark that answered the last query
  bool mixed_directions_ = false;       // false while every chunk had the same direction
  bool have_previous_ = false;
  double previous_time_ = 0.0;
};

}  // namespace pvtap::detail
