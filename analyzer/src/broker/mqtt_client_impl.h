// MqttClient::Impl: the libmosquitto handle and the state its network thread shares with the
// capture thread (guarded by `mutex`).
#pragma once

#include <mosquitto.h>

#include <atomic>
#include <mutex>
#include <string>

#include "broker/last_error_line.h"
#include "broker/mqtt_client.h"
#include "broker/mqtt_outbox.h"
#include "broker/outage_warnings.h"

namespace pvtap::analyzer {

struct MqttClient::Impl {
  explicit Impl(MqttClientConfig c) : config(std::move(c)), outbox(config.event_bound) {}
  ~Impl();

  // Setting up and the synchronous first connection (mqtt_connect.cpp).
  bool configure(std::string& error);
  bool connect_now(std::string& error);
  std::string where() const;

  // libmosquitto callbacks, on its network thread (or the caller's, while connecting).
  void on_connect(int rc);
  void on_disconnect(int rc);
  void on_publish(int mid);
  void on_log(int level, const char* text);

  MqttClientConfig config;
  mosquitto* mosq = nullptr;
  bool loop_running = false;

  mutable std::mutex mutex;
  MqttOutbox outbox;
  OutageWarnings warnings;
  // While connecting synchronously: the broker's answer, and libmosquitto's last error line.
  std::atomic<int> connack{-1};
  LastErrorLine last_error;
};

}  // namespace pvtap::analyzer
