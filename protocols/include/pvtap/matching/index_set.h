// IndexSet: a set of small indices with constant-time insert and erase, in no order.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

namespace pvtap {

// Used to visit only the requests that wait instead of every address.
template <std::size_t N>
class IndexSet {
 public:
  void insert(std::uint16_t i) {
    if (contains(i)) return;
    position_[i] = static_cast<std::uint16_t>(size_);
    members_[size_++] = i;
  }
  void erase(std::uint16_t i) {
    if (!contains(i)) return;
    const std::uint16_t last = members_[--size_];
    members_[position_[i]] = last;
    position_[last] = position_[i];
  }
  bool contains(std::uint16_t i) const {
    return position_[i] < size_ && members_[position_[i]] == i;
  }
  std::size_t size() const { return size_; }
  std::uint16_t operator[](std::size_t k) const { return members_[k]; }

 private:
  std::array<std::uint16_t, N> members_{};
  std::array<std::uint16_t, N> position_{};
  std::size_t size_ = 0;
};

}  // namespace pvtap
