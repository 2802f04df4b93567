// MqttPublisher::open: from the options as typed to a connected client (defaults, the
// password file, the last will).
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <fstream>

#include "mqtt/mqtt_publisher.h"

namespace pvtap::analyzer {
namespace {

std::string host_name() {
  char name[256] = {};
  if (::gethostname(name, sizeof name - 1) != 0) return "localhost";
  return name;
}

bool read_password(const std::string& path, std::string& password, std::string& error) {
  std::ifstream in(path);
  if (!in) {
    error = "--mqtt-password-file " + path + ": " + std::strerror(errno);
    return false;
  }
  std::getline(in, password);
  if (!password.empty() && password.back() == '\r') password.pop_back();
  return true;
}

bool client_config(const MqttOptions& o, const std::string& prefix, bool live, MqttClientConfig& c,
                   std::string& error) {
  const std::optional<MqttUrl> url = parse_mqtt_url(o.url, error);
  if (!url) return false;
  if (!url->tls && (!o.ca_file.empty() || !o.cert_file.empty() || !o.key_file.empty())) {
    error = "--mqtt-ca, --mqtt-cert and --mqtt-key need an mqtts:// URL";
    return false;
  }
  if (o.cert_file.empty() != o.key_file.empty()) {
    error = "--mqtt-cert and --mqtt-key go together";
    return false;
  }
  if (!o.password_file.empty() && o.user.empty()) {
    error = "--mqtt-password-file needs --mqtt-user";
    return false;
  }
  c.broker = *url;
  c.client_id =
      o.client_id.empty() ? "pvtap-" + host_name() + "-" + std::to_string(::getpid()) : o.client_id;
  c.user = o.user;
  if (!o.password_file.empty() && !read_password(o.password_file, c.password, error)) {
    return false;
  }
  c.ca_file = o.ca_file;
  c.cert_file = o.cert_file;
  c.key_file = o.key_file;
  if (live) {
    c.will = QueuedMessage{prefix + "/status", "offline"};
    c.birth = QueuedMessage{prefix + "/status", "online"};
  }
  return true;
}

}  // namespace

std::unique_ptr<MqttPublisher> MqttPublisher::open(const MqttOptions& options, bool live,
                                                   std::string& error) {
  std::string prefix = options.topic.empty() ? "pvtap/" + host_name() : options.topic;
  while (!prefix.empty() && prefix.back() == '/') prefix.pop_back();
  if (prefix.empty() || prefix.find_first_of("+#") != std::string::npos) {
    error = "--mqtt-topic " + options.topic + ": not a topic prefix (no +, # or empty)";
    return nullptr;
  }
  MqttClientConfig config;
  if (!client_config(options, prefix, live, config, error)) return nullptr;
  std::unique_ptr<MqttClient> client = MqttClient::connect(config, error);
  if (!client) return nullptr;
  return std::unique_ptr<MqttPublisher>(
      new MqttPublisher(std::move(client), options, std::move(prefix), live));
}

}  // namespace pvtap::analyzer
