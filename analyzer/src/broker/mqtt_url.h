// MqttUrl: the broker a --mqtt URL names (mqtt://host:port, mqtts://host:port).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace pvtap::analyzer {

struct MqttUrl {
  std::string host;
  std::uint16_t port = 1883;
  bool tls = false;
};

// The broker of `text`, or nullopt with a one-line reason in `error`. The port defaults to
// 1883 (mqtt://) or 8883 (mqtts://); IPv6 literals go in brackets (mqtt://[::1]:1883).
std::optional<MqttUrl> parse_mqtt_url(std::string_view text, std::string& error);

}  // namespace pvtap::analyzer
