// The --mqtt options that `pvtap sniff` and `pvtap audit` share.
#pragma once

#include "mqtt/mqtt_options.h"

namespace CLI {
class App;
}

namespace pvtap::analyzer {

// --mqtt, --mqtt-topic, --mqtt-client-id, --mqtt-user, --mqtt-password-file, --mqtt-ca,
// --mqtt-cert, --mqtt-key, --mqtt-interval, --mqtt-discovery.
void add_mqtt_options(CLI::App& command, MqttOptions& o);

// What --help says about MQTT below the options.
extern const char* const kMqttHelpFooter;

}  // namespace pvtap::analyzer
