// HeldBytes: the bytes of serial records that the bus has not decided yet.
#pragma once

#include <algorithm>
#include <cstdint>
#include <span>
#include <vector>

namespace pvtap::dissector {

// A frame may start in one record and end in a later one; the record that completes it shows
// it whole, from these bytes. Only the undecided tail is kept: the core decides every byte
// within a frame's greatest length, so it stays small.
class HeldBytes {
 public:
  // Stream position up to which every piece has been shown.
  std::uint64_t shown_to() const { return shown_to_; }
  // Stream position after the last byte kept.
  std::uint64_t end() const { return start_ + bytes_.size(); }

  // The bytes in [from, to), clipped to what is kept.
  std::span<const std::uint8_t> range(std::uint64_t from, std::uint64_t to) const {
    from = std::clamp(from, start_, end());
    to = std::clamp(to, from, end());
    return std::span<const std::uint8_t>(bytes_).subspan(from - start_, to - from);
  }

  // Keeps `bytes` (stream position `at` on), then lets go of everything before `decided_to`,
  // which the record shows.
  void keep(std::uint64_t at, std::span<const std::uint8_t> bytes, std::uint64_t decided_to) {
    if (at != end()) {  // not contiguous: what was held can no longer join these bytes
      bytes_.clear();
      start_ = at;
    }
    bytes_.insert(bytes_.end(), bytes.begin(), bytes.end());
    const std::uint64_t drop = std::min(decided_to, end()) - std::min(decided_to, start_);
    bytes_.erase(bytes_.begin(), bytes_.begin() + static_cast<std::ptrdiff_t>(drop));
    start_ += drop;
    shown_to_ = std::max(shown_to_, decided_to);
  }

 private:
  std::uint64_t start_ = 0;  // stream position of bytes_[0]
  std::uint64_t shown_to_ = 0;
  std::vector<std::uint8_t> bytes_;
};

}  // namespace pvtap::dissector
