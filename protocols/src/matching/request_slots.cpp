#include "pvtap/matching/request_slots.h"

#include <algorithm>
#include <limits>

namespace pvtap {

void RequestSlots::open(Slot& slot, const RequestRecord& request) {
  slot.state = State::Pending;
  pending_.insert(index_of(slot));
  slot.request = request;
  if (is_broadcast(slot)) broadcast_answered_by_.reset();
}

void RequestSlots::settle(Slot& slot, State outcome) {
  slot.state = outcome;
  pending_.erase(index_of(slot));
}

double RequestSlots::earliest_deadline() const {
  double earliest = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < pending_.size(); ++k) {
    earliest = std::min(earliest, slots_[pending_[k]].request.deadline);
  }
  return earliest;
}

std::span<RequestSlots::Slot* const> RequestSlots::pending_by_deadline(bool only_overdue,
                                                                       double now) {
  std::size_t n = 0;
  for (std::size_t k = 0; k < pending_.size(); ++k) {
    Slot& slot = slots_[pending_[k]];
    if (only_overdue && !(slot.request.deadline < now)) continue;
    due_[n++] = &slot;
  }
  std::sort(due_.begin(), due_.begin() + static_cast<std::ptrdiff_t>(n),
            [](const Slot* a, const Slot* b) {
              if (a->request.deadline != b->request.deadline) {
                return a->request.deadline < b->request.deadline;
              }
              return a->request.id < b->request.id;
            });
  return {due_.data(), n};
}

}  // namespace pvtap
