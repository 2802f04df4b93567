// MqttClient: a thin wrapper over libmosquitto for one broker connection that never blocks
// the caller once connected.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>

#include "broker/mqtt_outbox.h"
#include "broker/mqtt_url.h"

namespace pvtap::analyzer {

// MqttClientConfig: the connection and the messages the client sends by itself.
struct MqttClientConfig {
  MqttUrl broker;
  std::string client_id;
  std::string user;
  std::string password;
  std::string ca_file;
  std::string cert_file;
  std::string key_file;
  // Retained, QoS 1: the broker publishes `will` when the connection dies without a
  // disconnect; `birth` is published on every (re)connection, before queued events.
  std::optional<QueuedMessage> will;
  std::optional<QueuedMessage> birth;
  std::size_t event_bound = MqttEventQueue::kDefaultBound;
};

// MqttClient: connects synchronously (so that a refused login, a bad certificate or an
// unreachable host is known before anything is published), then runs libmosquitto's own
// network thread (mosquitto_loop_start), which reconnects with backoff (1 s doubling to
// 30 s). Publishing only hands a message to that thread.
//
// Events (QoS 1, not retained) keep their order: they go to the broker directly while it
// is there and fewer than kMaxInflight messages wait for its acknowledgement, else into a
// bounded queue (MqttEventQueue) drained on reconnection and as acknowledgements arrive.
// Retained values are only sent while connected; the caller holds the latest ones.
class MqttClient {
 public:
  static constexpr std::size_t kMaxInflight = 1000;

  // Connected, or null with a one-line reason in `error`.
  static std::unique_ptr<MqttClient> connect(const MqttClientConfig& config, std::string& error);
  ~MqttClient();
  MqttClient(const MqttClient&) = delete;
  MqttClient& operator=(const MqttClient&) = delete;

  // Retained value, state or configuration (QoS 0 or 1); false when not connected.
  bool publish_retained(const std::string& topic, const std::string& payload, int qos);
  // An event: QoS 1, not retained, queued while the broker is away.
  void publish_event(std::string topic, std::string payload);

  // Waits while `limit` or more messages are with libmosquitto, not yet written or
  // acknowledged (returns at once when not connected). Only for replays, which may wait:
  // without it a capture read at full speed piles up in libmosquitto's queue.
  void wait_for_room(std::size_t limit);

  bool connected() const;
  // Successful connections so far (a change means the broker may have lost retained data).
  std::uint64_t connections() const;
  std::uint64_t events_dropped() const;
  std::size_t events_queued() const;

  // Publishes `last` (retained, when connected), waits up to `timeout` seconds for queued
  // and unacknowledged messages to reach the broker, and disconnects cleanly (no will).
  // False when messages were left undelivered.
  bool close(const std::optional<QueuedMessage>& last, double timeout);

  struct Impl;

 private:
  explicit MqttClient(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace pvtap::analyzer
