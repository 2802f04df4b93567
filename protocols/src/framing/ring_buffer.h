// RingBuffer: a first-in first-out queue over one array that only grows.
#pragma once

#include <algorithm>
#include <cstddef>
#include <vector>

namespace pvtap::detail {

// RingBuffer: pushed at the back and popped at the front for every chunk of a stream, with no
// allocation once it has reached its working size (std::deque allocates a block every few
// elements). Elements stay where they are until the buffer grows, which push_back reports.
template <typename T>
class RingBuffer {
 public:
  std::size_t size() const { return size_; }
  bool empty() const { return size_ == 0; }
  T& operator[](std::size_t i) { return slots_[(head_ + i) & mask_]; }
  const T& operator[](std::size_t i) const { return slots_[(head_ + i) & mask_]; }
  const T& front() const { return (*this)[0]; }
  const T& back() const { return (*this)[size_ - 1]; }

  // True when the elements moved to a larger array: pointers to them are then stale.
  bool push_back(const T& value) {
    const bool moved = size_ == slots_.size();
    if (moved) grow();
    slots_[(head_ + size_) & mask_] = value;
    ++size_;
    return moved;
  }
  void pop_front() {
    head_ = (head_ + 1) & mask_;
    --size_;
  }

 private:
  void grow() {
    std::vector<T> larger(std::max<std::size_t>(16, 2 * slots_.size()));  // a power of two
    for (std::size_t i = 0; i < size_; ++i) larger[i] = (*this)[i];
    slots_.swap(larger);
    head_ = 0;
    mask_ = slots_.size() - 1;
  }

  std::vector<T> slots_;
  std::size_t head_ = 0;
  std::size_t size_ = 0;
  std::size_t mask_ = 0;
};

}  // namespace pvtap::detail
