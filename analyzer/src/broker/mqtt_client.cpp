// MqttClient while running: publishing, the event queue, and what the network thread tells
// of the connection.
#include "broker/mqtt_client.h"

#include <chrono>
#include <cstdio>
#include <thread>

#include "broker/mqtt_client_impl.h"

namespace pvtap::analyzer {

// One warning per outage.
bool OutageWarnings::refused() {
  if (starting_ || refusal_reported_) return false;
  refusal_reported_ = true;
  return true;
}

bool OutageWarnings::back() {
  const bool reported = outage_reported_;
  outage_reported_ = false;
  refusal_reported_ = false;
  return reported;
}

bool OutageWarnings::lost(bool own) {
  if (own || starting_ || outage_reported_) return false;
  outage_reported_ = true;
  return true;
}

MqttClient::MqttClient(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
MqttClient::~MqttClient() = default;

void MqttClient::Impl::on_connect(int rc) {
  connack.store(rc);
  std::lock_guard lock(mutex);
  if (rc != 0) {
    if (warnings.refused()) {
      std::fprintf(stderr, "pvtap: warning: %s refused the connection: %s; retrying\n",
                   where().c_str(), mosquitto_connack_string(rc));
    }
    return;
  }
  outbox.connected();
  if (warnings.back()) {
    const MqttEventQueue& events = outbox.events();
    std::fprintf(stderr, "pvtap: %s is back; sending %zu queued events (%llu dropped)\n",
                 where().c_str(), events.size(), static_cast<unsigned long long>(events.dropped()));
  }
  if (config.birth) outbox.send(config.birth->topic, config.birth->payload, 1, true);
  outbox.drain();
}

void MqttClient::Impl::on_disconnect(int rc) {
  std::lock_guard lock(mutex);
  outbox.disconnected();
  if (!warnings.lost(rc == 0)) return;  // 0: our own disconnect
  std::fprintf(stderr,
               "pvtap: warning: lost the connection to %s; holding values, queueing up to %zu "
               "events, reconnecting\n",
               where().c_str(), outbox.events().bound());
}

void MqttClient::Impl::on_publish(int mid) {
  std::lock_guard lock(mutex);
  outbox.acknowledged(mid);
}

bool MqttClient::publish_retained(const std::string& topic, const std::string& payload, int qos) {
  std::lock_guard lock(impl_->mutex);
  return impl_->outbox.is_connected() && impl_->outbox.send(topic, payload, qos, true);
}

void MqttClient::publish_event(std::string topic, std::string payload) {
  std::lock_guard lock(impl_->mutex);
  impl_->outbox.publish_event(std::move(topic), std::move(payload));
}

void MqttClient::wait_for_room(std::size_t limit) {
  for (;;) {
    {
      std::lock_guard lock(impl_->mutex);
      if (!impl_->outbox.is_connected() || impl_->outbox.in_flight() < limit) return;
    }
    std::this_thread::sleep_for(std::chrono::microseconds(200));
  }
}

bool MqttClient::connected() const {
  std::lock_guard lock(impl_->mutex);
  return impl_->outbox.is_connected();
}

std::uint64_t MqttClient::connections() const {
  std::lock_guard lock(impl_->mutex);
  return impl_->outbox.connections();
}

std::uint64_t MqttClient::events_dropped() const {
  std::lock_guard lock(impl_->mutex);
  return impl_->outbox.events().dropped();
}

std::size_t MqttClient::events_queued() const {
  std::lock_guard lock(impl_->mutex);
  return impl_->outbox.events().size();
}

bool MqttClient::close(const std::optional<QueuedMessage>& last, double timeout) {
  if (last) publish_retained(last->topic, last->payload, 1);
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout);
  for (;;) {
    {
      std::lock_guard lock(impl_->mutex);
      const MqttOutbox& outbox = impl_->outbox;
      if (outbox.events().empty() && outbox.in_flight() == 0) return true;
      if (!outbox.is_connected()) return false;  // nobody to wait for
    }
    if (std::chrono::steady_clock::now() >= deadline) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
}

}  // namespace pvtap::analyzer
