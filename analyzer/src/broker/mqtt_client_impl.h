// MqttClient::Impl: the libmosquitto handle and the state its network thread shares with the
// capture thread (guarded by `mutex`).
#pragma once

#include <mosquitto.h>

#include <atomic>
#include <mutex>
#include <string>
#include <unordered_set>

#include "broker/mqtt_client.h"

namespace pvtap::analyzer {

struct MqttClient::Impl {
  explicit Impl(MqttClientConfig c) : config(std::move(c)), events(config.event_bound) {}
  ~Impl();

  // Setting up and the synchronous first connection (mqtt_connect.cpp).
  bool configure(std::string& error);
  bool connect_now(std::string& error);
  std::string where() const;
  std::string log_detail();  // " (libmosquitto's last error line)" or nothing

  // libmosquitto callbacks, on its network thread (or the caller's, while connecting).
  void on_connect(int rc);
  void on_disconnect(int rc);
  void on_publish(int mid);
  void on_log(int level, const char* text);

  // With `mutex` held.
  bool send(const std::string& topic, const std::string& payload, int qos, bool retain);
  void drain_events();

  MqttClientConfig config;
  mosquitto* mosq = nullptr;
  bool loop_running = false;

  mutable std::mutex mutex;
  bool is_connected = false;
  std::uint64_t connection_count = 0;
  MqttEventQueue events;
  std::unordered_set<int> unacknowledged;  // message ids handed to libmosquitto
  // While connecting synchronously: the broker's answer, and libmosquitto's last error line.
  std::atomic<int> connack{-1};
  std::mutex log_mutex;  // apart from `mutex`: libmosquitto logs from inside publish calls
  std::string last_error_log;
  // Warnings on stderr while running: once per outage, not once per retry.
  bool starting = true;
  bool outage_reported = false;
  bool refusal_reported = false;
};

}  // namespace pvtap::analyzer
