// ChunkMarks: where each buffered chunk lies in the stream and when it arrived, by offset.
#pragma once

#include <cstdint>

#include "framing/ring_buffer.h"
#include "pvtap/framing/bus_chunk.h"

namespace pvtap::detail {

// ChunkMark: one chunk of the stream, [start, end), and the time its last byte arrived.
struct ChunkMark {
  std::uint64_t start;
  std::uint64_t end;
  double time;
  double previous_time;  // last byte of the chunk before (valid when gap_before >= 0)
  double gap_before;     // < 0: unknown (first chunk or after a break)
  Direction direction;

  // Estimated end of the byte at `offset`, counted back from the chunk's arrival.
  double end_time(std::uint64_t offset, double char_time) const {
    const std::uint64_t last = end - 1;
    const double behind = static_cast<double>(last - (offset < last ? offset : last));
    const double estimate = time - behind * char_time;
    // Bytes of a batched chunk cannot have ended before the previous chunk's last byte.
    if (gap_before < 0) return estimate;
    return estimate > previous_time ? estimate : previous_time;
  }
};

class ChunkMarks {
 public:
  void add(const ChunkMark& mark);
  // Forgets the marks that end at or before `offset`, all but the last.
  void drop_before(std::uint64_t offset);

  // The mark holding `offset` (the last one when the offset lies beyond); nullptr when empty.
  const ChunkMark* find(std::uint64_t offset) const {
    // Queries move forward through the stream: the chunk found last time usually answers.
    if (last_ && offset >= last_->start && offset < last_->end) return last_;
    return search(offset);
  }
  Direction direction_at(std::uint64_t offset) const {
    if (!mixed_directions_) return marks_.empty() ? Direction::Unknown : marks_.back().direction;
    const ChunkMark* m = find(offset);
    return m ? m->direction : Direction::Unknown;
  }
  // Silence right before the byte at `offset` (0 inside a chunk; < 0 when unknown).
  double gap_before(std::uint64_t offset) const;
  // The longest silence before a chunk that starts after `first` and at or before `last`.
  double widest_gap_inside(std::uint64_t first, std::uint64_t last) const;

 private:
  const ChunkMark* search(std::uint64_t offset) const;
  // The index of the first mark that ends after `offset` (marks_.size() when none does).
  std::size_t first_ending_after(std::uint64_t offset) const;

  RingBuffer<ChunkMark> marks_;
  mutable const ChunkMark* last_ = nullptr;  // the mark that answered the last query
  bool mixed_directions_ = false;            // false while every chunk had the same direction
};

}  // namespace pvtap::detail
