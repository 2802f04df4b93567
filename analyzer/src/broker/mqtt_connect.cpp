// MqttClient: setting up libmosquitto and the synchronous first connection, whose failures
// are one-line errors (a refused login, a certificate the CA does not vouch for, a broker
// that is not there).
#include <netdb.h>
#include <sys/socket.h>
#include <sys/time.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <string>

#include "broker/mqtt_client_impl.h"
#include "broker/sigpipe_blocked.h"

namespace pvtap::analyzer {
namespace {

constexpr int kKeepaliveSeconds = 30;
constexpr double kConnackWaitSeconds = 10;

extern "C" void connect_cb(mosquitto*, void* self, int rc) {
  static_cast<MqttClient::Impl*>(self)->on_connect(rc);
}
extern "C" void disconnect_cb(mosquitto*, void* self, int rc) {
  static_cast<MqttClient::Impl*>(self)->on_disconnect(rc);
}
extern "C" void publish_cb(mosquitto*, void* self, int mid) {
  static_cast<MqttClient::Impl*>(self)->on_publish(mid);
}
extern "C" void log_cb(mosquitto*, void* self, int level, const char* text) {
  static_cast<MqttClient::Impl*>(self)->on_log(level, text);
}

// One TCP connection attempt to the broker (at most 3 s per address): why it fails, or ""
// when it does not.
std::string tcp_connect_failure(const MqttUrl& broker) {
  addrinfo hints{};
  hints.ai_socktype = SOCK_STREAM;
  addrinfo* found = nullptr;
  const int looked_up =
      getaddrinfo(broker.host.c_str(), std::to_string(broker.port).c_str(), &hints, &found);
  if (looked_up != 0) return gai_strerror(looked_up);
  std::string why = "no address to connect to";
  for (const addrinfo* a = found; a != nullptr; a = a->ai_next) {
    const int fd = socket(a->ai_family, a->ai_socktype | SOCK_CLOEXEC, a->ai_protocol);
    if (fd < 0) {
      why = std::strerror(errno);
      continue;
    }
    const timeval limit{3, 0};
    setsockopt(fd, SOL_SOCKET, SO_SNDTIMEO, &limit, sizeof limit);
    const bool connected = ::connect(fd, a->ai_addr, a->ai_addrlen) == 0;
    why = connected ? "" : std::strerror(errno);
    close(fd);
    if (connected) break;
  }
  freeaddrinfo(found);
  return why;
}

// Why mosquitto_connect or the wait for its answer failed. libmosquitto 2.1 (Debian testing)
// reports a refused connection as MOSQ_ERR_ERRNO with errno EBADF, the socket it had closed; the
// reason is then found by trying the connection once more.
std::string connect_failure(int rc, int error_number, const MqttUrl& broker) {
  if (rc != MOSQ_ERR_ERRNO) return mosquitto_strerror(rc);
  if (error_number != EBADF) return std::strerror(error_number);
  const std::string why = tcp_connect_failure(broker);
  return why.empty() ? std::strerror(error_number) : why;
}

const char* or_null(const std::string& s) {
  return s.empty() ? nullptr : s.c_str();
}

}  // namespace

std::string MqttClient::Impl::where() const {
  return "MQTT broker " + config.broker.host + ":" + std::to_string(config.broker.port);
}

bool MqttClient::Impl::configure(std::string& error) {
  mosquitto_lib_init();
  mosq = mosquitto_new(config.client_id.c_str(), true, this);
  if (mosq == nullptr) {
    error = "cannot create an MQTT client: " + std::string(std::strerror(errno));
    return false;
  }
  outbox.attach(mosq);
  mosquitto_int_option(mosq, MOSQ_OPT_PROTOCOL_VERSION, MQTT_PROTOCOL_V311);
  mosquitto_connect_callback_set(mosq, connect_cb);
  mosquitto_disconnect_callback_set(mosq, disconnect_cb);
  mosquitto_publish_callback_set(mosq, publish_cb);
  mosquitto_log_callback_set(mosq, log_cb);
  mosquitto_reconnect_delay_set(mosq, 1, 30, true);
  if (!config.user.empty()) {
    mosquitto_username_pw_set(mosq, config.user.c_str(), or_null(config.password));
  }
  if (config.will) {
    const QueuedMessage& w = *config.will;
    mosquitto_will_set(mosq, w.topic.c_str(), static_cast<int>(w.payload.size()), w.payload.data(),
                       1, true);
  }
  if (!config.broker.tls) return true;
  // Without --mqtt-ca the system's CAs (Debian's ca-certificates) vouch for the broker.
  const char* capath = config.ca_file.empty() ? "/etc/ssl/certs" : nullptr;
  const int rc = mosquitto_tls_set(mosq, or_null(config.ca_file), capath, or_null(config.cert_file),
                                   or_null(config.key_file), nullptr);
  if (rc != MOSQ_ERR_SUCCESS) {
    error = "MQTT TLS settings: " + std::string(mosquitto_strerror(rc)) +
            " (check --mqtt-ca, --mqtt-cert and --mqtt-key)";
    return false;
  }
  return true;
}

bool MqttClient::Impl::connect_now(std::string& error) {
  SigpipeBlocked blocked;
  int rc =
      mosquitto_connect(mosq, config.broker.host.c_str(), config.broker.port, kKeepaliveSeconds);
  if (rc != MOSQ_ERR_SUCCESS) {
    const std::string why = connect_failure(rc, errno, config.broker);
    error = "cannot connect to " + where() + ": " + why;
    if (rc == MOSQ_ERR_TLS) error += last_error.detail();
    return false;
  }
  const auto deadline =
      std::chrono::steady_clock::now() + std::chrono::duration<double>(kConnackWaitSeconds);
  while (connack.load() < 0 && std::chrono::steady_clock::now() < deadline) {
    rc = mosquitto_loop(mosq, 100, 1);
    if (rc != MOSQ_ERR_SUCCESS && connack.load() < 0) {
      const std::string why = connect_failure(rc, errno, config.broker);
      error = "connection to " + where() + " failed: " + why;
      error += last_error.detail();
      return false;
    }
  }
  if (connack.load() != 0) {
    error = connack.load() < 0
                ? where() + " did not answer the connection within 10 s"
                : where() + " refused the connection: " + mosquitto_connack_string(connack.load());
    return false;
  }
  rc = mosquitto_loop_start(mosq);
  if (rc != MOSQ_ERR_SUCCESS) {
    error = "cannot start the MQTT network thread: " + std::string(mosquitto_strerror(rc));
    return false;
  }
  loop_running = true;
  std::lock_guard lock(mutex);
  warnings.running();
  return true;
}

MqttClient::Impl::~Impl() {
  if (mosq == nullptr) return;
  // Disconnecting writes to a broker that may be gone (over TLS, through OpenSSL).
  SigpipeBlocked blocked;
  mosquitto_disconnect(mosq);
  if (loop_running) mosquitto_loop_stop(mosq, false);
  mosquitto_destroy(mosq);
  mosquitto_lib_cleanup();
}

void MqttClient::Impl::on_log(int level, const char* text) {
  if (level != MOSQ_LOG_ERR || text == nullptr) return;
  last_error.keep(text);
}

std::unique_ptr<MqttClient> MqttClient::connect(const MqttClientConfig& config,
                                                std::string& error) {
  auto impl = std::make_unique<Impl>(config);
  if (!impl->configure(error) || !impl->connect_now(error)) return nullptr;
  return std::unique_ptr<MqttClient>(new MqttClient(std::move(impl)));
}

}  // namespace pvtap::analyzer
