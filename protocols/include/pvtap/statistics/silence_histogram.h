// Silences counted in fixed buckets, log-spaced in character times, split exactly at a rule's
// line (t1.5 or t3.5), so that the counts on either side are the rule's verdicts.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

namespace pvtap {

// Which side a silence exactly at the line counts on: the rule's own comparison decides it.
// t1.5 is broken by a silence longer than it (equal is within: Below); t3.5 by one shorter
// than it (equal is within: Above).
enum class LineSide : std::uint8_t { Below, Above };

// SilenceHistogram: bucket edges at 2^(k/4) character times from 1/8 to 2^14 (about 17 s at
// 9600 baud), plus the line as an edge of its own. Bucket 0 holds everything below the lowest
// edge (back-to-back characters, and negative silences of overlapping frames), the last
// everything above the highest. Memory is fixed: adding never allocates.
class SilenceHistogram {
 public:
  static constexpr int kPerOctave = 4;
  static constexpr int kLowestOctave = -3;
  static constexpr int kHighestOctave = 14;
  static constexpr std::size_t kEdges = (kHighestOctave - kLowestOctave) * kPerOctave + 2;
  static constexpr std::size_t kBuckets = kEdges + 1;

  // `char_time` and `line` in seconds; `equal` says where a silence exactly at the line goes.
  SilenceHistogram(double char_time, double line, LineSide equal);

  void add(double seconds);

  // Ascending, in seconds; bucket i lies between edges[i - 1] and edges[i].
  std::span<const double> edges() const { return edges_; }
  std::span<const std::uint64_t> counts() const { return counts_; }
  double line() const { return edges_[line_edge_]; }
  double char_time() const { return char_time_; }
  // Silences on each side of the line: the rule's verdicts.
  std::uint64_t below_line() const;
  std::uint64_t above_line() const;

 private:
  std::array<double, kEdges> edges_{};
  std::array<std::uint64_t, kBuckets> counts_{};
  double char_time_;
  std::size_t line_edge_ = 0;
  LineSide equal_;
};

}  // namespace pvtap
