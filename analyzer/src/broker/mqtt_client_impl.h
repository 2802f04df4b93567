// MqttClient::Impl: the libmosquitto handle and the state its network thread shares with the
// capture thread (guarded by `mutex`).
#pragma once

#include <mosquitto.h>

#include <atomic>
#include <mutex>
#include <string>

#include "broker/mqtt_client.h"
#include "broker/mqtt_outbox.h"

namespace pvtap::analyzer {

// LastErrorLine: libmosquitto's last error log line, which names what a bare error code does
// not (the TLS verification that failed, the address refused). It has its own lock, apart from
// the client's mutex: libmosquitto logs from inside publish calls, which run with that mutex
// held.
class LastErrorLine {
 public:
  void keep(const char* text) {
    std::lock_guard lock(mutex_);
    text_ = text;
  }
  // " (the line)" to end an error message with, or nothing.
  std::string detail() {
    std::lock_guard lock(mutex_);
    return text_.empty() ? std::string() : " (" + text_ + ")";
  }

 private:
  std::mutex mutex_;
  std::string text_;
};

// OutageWarnings: which changes of the broker connection are worth a line on stderr: a line
// once per outage, not once per retry; none while the first connection is made, whose
// failure the caller reports as an error.
class OutageWarnings {
 public:
  // The first connection is made: warnings start.
  void running() { starting_ = false; }
  // The broker refused a reconnection: true when that deserves a warning.
  bool refused();
  // The connection came up: true when an outage was reported (the broker "is back").
  bool back();
  // The connection went down (`own`: by our disconnect): true when that deserves a warning.
  bool lost(bool own);

 private:
  bool starting_ = true;
  bool outage_reported_ = false;
  bool refusal_reported_ = false;
};

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
