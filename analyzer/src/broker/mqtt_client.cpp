// MqttClient while running: publishing, the event queue, and what the network thread tells
// of the connection.
#include "broker/mqtt_client.h"

#include <chrono>
#include <cstdio>
#include <thread>

#include "broker/mqtt_client_impl.h"
#include "broker/sigpipe_blocked.h"

namespace pvtap::analyzer {

MqttClient::MqttClient(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
MqttClient::~MqttClient() = default;

bool MqttClient::Impl::send(const std::string& topic, const std::string& payload, int qos,
                            bool retain) {
  int mid = 0;
  SigpipeBlocked blocked;  // the publish may be written at once, to a broker that is gone
  const int rc = mosquitto_publish(mosq, &mid, topic.c_str(), static_cast<int>(payload.size()),
                                   payload.data(), qos, retain);
  if (rc != MOSQ_ERR_SUCCESS) return false;
  unacknowledged.insert(mid);
  return true;
}

void MqttClient::Impl::drain_events() {
  while (is_connected && !events.empty() && unacknowledged.size() < kMaxInflight) {
    QueuedMessage& m = events.front();
    if (!send(m.topic, m.payload, 1, false)) return;
    events.pop();
  }
}

void MqttClient::Impl::on_connect(int rc) {
  connack.store(rc);
  std::lock_guard lock(mutex);
  if (rc != 0) {
    if (!starting && !refusal_reported) {
      std::fprintf(stderr, "pvtap: warning: %s refused the connection: %s; retrying\n",
                   where().c_str(), mosquitto_connack_string(rc));
      refusal_reported = true;
    }
    return;
  }
  is_connected = true;
  ++connection_count;
  // Messages of the old connection that libmosquitto still holds are its to resend.
  unacknowledged.clear();
  if (outage_reported) {
    std::fprintf(stderr, "pvtap: %s is back; sending %zu queued events (%llu dropped)\n",
                 where().c_str(), events.size(), static_cast<unsigned long long>(events.dropped()));
  }
  outage_reported = false;
  refusal_reported = false;
  if (config.birth) send(config.birth->topic, config.birth->payload, 1, true);
  drain_events();
}

void MqttClient::Impl::on_disconnect(int rc) {
  std::lock_guard lock(mutex);
  is_connected = false;
  if (rc == 0 || starting || outage_reported) return;  // 0: our own disconnect
  std::fprintf(stderr,
               "pvtap: warning: lost the connection to %s; holding values, queueing up to %zu "
               "events, reconnecting\n",
               where().c_str(), events.bound());
  outage_reported = true;
}

void MqttClient::Impl::on_publish(int mid) {
  std::lock_guard lock(mutex);
  unacknowledged.erase(mid);
  drain_events();
}

bool MqttClient::publish_retained(const std::string& topic, const std::string& payload, int qos) {
  std::lock_guard lock(impl_->mutex);
  return impl_->is_connected && impl_->send(topic, payload, qos, true);
}

void MqttClient::publish_event(std::string topic, std::string payload) {
  std::lock_guard lock(impl_->mutex);
  Impl& i = *impl_;
  // Straight out only when nothing older waits, so that events keep their order.
  if (i.is_connected && i.events.empty() && i.unacknowledged.size() < kMaxInflight &&
      i.send(topic, payload, 1, false)) {
    return;
  }
  i.events.push(QueuedMessage{std::move(topic), std::move(payload)});
}

void MqttClient::wait_for_room(std::size_t limit) {
  for (;;) {
    {
      std::lock_guard lock(impl_->mutex);
      if (!impl_->is_connected || impl_->unacknowledged.size() < limit) return;
    }
    std::this_thread::sleep_for(std::chrono::microseconds(200));
  }
}

bool MqttClient::connected() const {
  std::lock_guard lock(impl_->mutex);
  return impl_->is_connected;
}

std::uint64_t MqttClient::connections() const {
  std::lock_guard lock(impl_->mutex);
  return impl_->connection_count;
}

std::uint64_t MqttClient::events_dropped() const {
  std::lock_guard lock(impl_->mutex);
  return impl_->events.dropped();
}

std::size_t MqttClient::events_queued() const {
  std::lock_guard lock(impl_->mutex);
  return impl_->events.size();
}

bool MqttClient::close(const std::optional<QueuedMessage>& last, double timeout) {
  if (last) publish_retained(last->topic, last->payload, 1);
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout);
  for (;;) {
    {
      std::lock_guard lock(impl_->mutex);
      if (impl_->events.empty() && impl_->unacknowledged.empty()) return true;
      if (!impl_->is_connected) return false;  // nobody to wait for
    }
    if (std::chrono::steady_clock::now() >= deadline) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
}

}  // namespace pvtap::analyzer
