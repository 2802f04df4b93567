// MqttOutbox: handing messages to libmosquitto in order, within the in-flight bound; the
// event queue dropping its oldest when full.
#include "broker/mqtt_outbox.h"

#include <mosquitto.h>

#include "broker/mqtt_client.h"
#include "broker/sigpipe_blocked.h"

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

bool MqttOutbox::send(const std::string& topic, const std::string& payload, int qos, bool retain) {
  int mid = 0;
  SigpipeBlocked blocked;  // the publish may be written at once, to a broker that is gone
  const int rc = mosquitto_publish(mosq_, &mid, topic.c_str(), static_cast<int>(payload.size()),
                                   payload.data(), qos, retain);
  if (rc != MOSQ_ERR_SUCCESS) return false;
  unacknowledged_.insert(mid);
  return true;
}

void MqttOutbox::publish_event(std::string topic, std::string payload) {
  if (connected_ && events_.empty() && unacknowledged_.size() < MqttClient::kMaxInflight &&
      send(topic, payload, 1, false)) {
    return;
  }
  events_.push(QueuedMessage{std::move(topic), std::move(payload)});
}

void MqttOutbox::connected() {
  connected_ = true;
  ++connections_;
  unacknowledged_.clear();
}

void MqttOutbox::acknowledged(int mid) {
  unacknowledged_.erase(mid);
  drain();
}

void MqttOutbox::drain() {
  while (connected_ && !events_.empty() && unacknowledged_.size() < MqttClient::kMaxInflight) {
    QueuedMessage& m = events_.front();
    if (!send(m.topic, m.payload, 1, false)) return;
    events_.pop();
  }
}

}  // namespace pvtap::analyzer
