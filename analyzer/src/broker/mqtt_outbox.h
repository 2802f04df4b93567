// MqttOutbox: what is on its way to the broker through libmosquitto, with the client's mutex
// held: events waiting while it is away (MqttEventQueue, oldest first, in bounded memory), and
// messages handed over but not yet acknowledged.
#pragma once

#include <cstddef>
#include <cstdint>
#include <deque>
#include <string>
#include <unordered_set>

struct mosquitto;

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

// Events keep their order: one goes out directly only when nothing older waits, and the
// queue drains on reconnection and as acknowledgements make room in flight.
class MqttOutbox {
 public:
  explicit MqttOutbox(std::size_t event_bound) : events_(event_bound) {}

  // The handle messages are handed to, once libmosquitto has made it.
  void attach(mosquitto* mosq) { mosq_ = mosq; }
  // Hands one message to libmosquitto; false when it does not take it.
  bool send(const std::string& topic, const std::string& payload, int qos, bool retain);
  // QoS 1, not retained: sent now, or queued behind older events and while disconnected.
  void publish_event(std::string topic, std::string payload);

  // A (re)connection: libmosquitto resends what the old one left unacknowledged itself.
  void connected();
  void disconnected() { connected_ = false; }
  void acknowledged(int mid);
  // Sends queued events while connected and in-flight room remains.
  void drain();

  bool is_connected() const { return connected_; }
  std::uint64_t connections() const { return connections_; }
  std::size_t in_flight() const { return unacknowledged_.size(); }
  const MqttEventQueue& events() const { return events_; }

 private:
  mosquitto* mosq_ = nullptr;
  bool connected_ = false;
  std::uint64_t connections_ = 0;
  MqttEventQueue events_;
  std::unordered_set<int> unacknowledged_;  // message ids handed to libmosquitto
};

}  // namespace pvtap::analyzer
