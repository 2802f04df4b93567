// Parsing of --mqtt URLs.
#include "broker/mqtt_url.h"

#include <charconv>

namespace pvtap::analyzer {
namespace {

bool parse_port(std::string_view text, std::uint16_t& port) {
  unsigned value = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec != std::errc{} || end != text.data() + text.size() || value == 0 || value > 65535) {
    return false;
  }
  port = static_cast<std::uint16_t>(value);
  return true;
}

// Splits "host:port" or "[v6]:port" into `url`; false when malformed.
bool parse_authority(std::string_view rest, MqttUrl& url) {
  std::string_view host = rest;
  std::string_view port;
  if (rest.starts_with('[')) {
    const auto close = rest.find(']');
    if (close == std::string_view::npos) return false;
    host = rest.substr(1, close - 1);
    const std::string_view after = rest.substr(close + 1);
    if (!after.empty() && !after.starts_with(':')) return false;
    if (!after.empty()) port = after.substr(1);
  } else if (const auto colon = rest.rfind(':'); colon != std::string_view::npos) {
    host = rest.substr(0, colon);
    port = rest.substr(colon + 1);
  }
  if (host.empty() || host.find_first_of("/@ ") != std::string_view::npos) return false;
  url.host = std::string(host);
  return port.empty() || parse_port(port, url.port);
}

}  // namespace

std::optional<MqttUrl> parse_mqtt_url(std::string_view text, std::string& error) {
  MqttUrl url;
  std::string_view rest;
  if (text.starts_with("mqtt://")) {
    rest = text.substr(7);
  } else if (text.starts_with("mqtts://")) {
    rest = text.substr(8);
    url.tls = true;
    url.port = 8883;
  } else {
    error = "--mqtt " + std::string(text) + ": give mqtt://HOST[:PORT] or mqtts://HOST[:PORT]";
    return std::nullopt;
  }
  if (rest.ends_with('/')) rest.remove_suffix(1);
  if (!parse_authority(rest, url)) {
    error = "--mqtt " + std::string(text) + ": not a broker address (mqtt://HOST[:PORT])";
    return std::nullopt;
  }
  return url;
}

}  // namespace pvtap::analyzer
