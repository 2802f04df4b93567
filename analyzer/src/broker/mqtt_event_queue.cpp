// MqttEventQueue: dropping the oldest when full.
#include "broker/mqtt_event_queue.h"

namespace pvtap::analyzer {

void MqttEventQueue::push(QueuedMessage message) {
  if (bound_ == 0) {
    ++dropped_;
    return;
  }
  if (messages_.size() >= bound_) {
    messages_.pop_front();
    ++dropped_;
  }
  messages_.push_back(std::move(message));
}

}  // namespace pvtap::analyzer
