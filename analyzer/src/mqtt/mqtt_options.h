// MqttOptions: where and how `pvtap sniff --mqtt` and `pvtap audit --mqtt` publish, as typed.
#pragma once

#include <string>

namespace pvtap::analyzer {

struct MqttOptions {
  std::string url;        // mqtt://host[:1883] or mqtts://host[:8883]; empty: no MQTT
  std::string topic;      // prefix; empty means pvtap/<hostname>
  std::string client_id;  // empty means pvtap-<hostname>-<pid>
  std::string user;
  std::string password_file;  // first line is the password (never on the command line)
  std::string ca_file;        // TLS: the broker's CA; empty uses the system's CAs
  std::string cert_file;      // TLS client certificate and its key, for brokers that ask
  std::string key_file;
  double interval = 10;    // seconds between value, state and health publications
  bool discovery = false;  // Home Assistant discovery configs under homeassistant/
  bool raw = false;        // also the words no map names, as reg_0x0836 (--mqtt-raw)
  // The bus of the run's one serial tap (a capture of serial records, or sniff with one
  // --device): its topic level is "bus", so that topics and Home Assistant entities stay the
  // same whether the bus was heard live or from a capture, and when the adapter's path changes.
  std::string lone_serial_bus;
  bool active() const { return !url.empty(); }
};

}  // namespace pvtap::analyzer
