// MqttEventQueue: events waiting for the broker, oldest first, in bounded memory.
#pragma once

#include <cstddef>
#include <cstdint>
#include <deque>
#include <string>

namespace pvtap::analyzer {

// QueuedMessage: one message as it will be published.
struct QueuedMessage {
  std::string topic;
  std::string payload;
};

// When full, the oldest event is dropped (and counted) to make room: an operator looking at a
// degraded bus after an outage needs its latest events more than its first ones.
class MqttEventQueue {
 public:
  static constexpr std::size_t kDefaultBound = 10000;

  explicit MqttEventQueue(std::size_t bound = kDefaultBound) : bound_(bound) {}

  void push(QueuedMessage message);
  bool empty() const { return messages_.empty(); }
  std::size_t size() const { return messages_.size(); }
  std::size_t bound() const { return bound_; }
  QueuedMessage& front() { return messages_.front(); }
  void pop() { messages_.pop_front(); }
  std::uint64_t dropped() const { return dropped_; }

 private:
  std::size_t bound_;
  std::deque<QueuedMessage> messages_;
  std::uint64_t dropped_ = 0;
};

}  // namespace pvtap::analyzer
