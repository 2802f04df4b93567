// TimeoutList: the timeouts that one call of the matcher decided, in fixed memory.
#pragma once

#include <array>
#include <cstddef>
#include <span>

#include "pvtap/matching/match_events.h"
#include "pvtap/matching/request_slots.h"

namespace pvtap {

// At most one per request slot, since each timed-out request was pending.
class TimeoutList {
 public:
  void clear() { size_ = 0; }
  void push_back(const Timeout& timeout) { items_[size_++] = timeout; }
  // Valid until the next clear().
  std::span<const Timeout> view() const { return {items_.data(), size_}; }

 private:
  std::array<Timeout, RequestSlots::kSlots> items_{};
  std::size_t size_ = 0;
};

}  // namespace pvtap
