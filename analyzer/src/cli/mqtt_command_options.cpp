// The --mqtt options.
#include "cli/mqtt_command_options.h"

#include <CLI/CLI.hpp>

#include "broker/mqtt_outbox.h"

namespace pvtap::analyzer {

const char* const kMqttHelpFooter =
    "\nMQTT (--mqtt URL): values go to PREFIX/<bus>/<station>/<key> (retained, on change, at\n"
    "most once per --mqtt-interval), with PREFIX/<bus>/<station>/state (JSON of all values),\n"
    "PREFIX/<bus>/<station>/availability, PREFIX/<bus>/health (JSON per interval) and\n"
    "PREFIX/<bus>/events (damaged frames, exceptions, unsolicited replies, timeouts, gaps,\n"
    "stations going offline/online; QoS 1, each as its --format jsonl line). The bus level is\n"
    "\"bus\" for a single serial tap. pvtap sniff keeps PREFIX/status online, offline as its\n"
    "last will. The first connection is made before capturing: a refused login, a bad\n"
    "certificate or an unreachable broker is an error (exit 2). Later outages never slow the\n"
    "capture: values are held (latest only), up to 10000 events queue (the oldest are dropped\n"
    "and counted in health) and the client reconnects with backoff (1 s doubling to 30 s).\n";

void add_mqtt_options(CLI::App& command, MqttOptions& o) {
  CLI::Option* mqtt = command.add_option(
      "--mqtt", o.url,
      "publish values, health and events to an MQTT broker: mqtt://HOST[:1883] or "
      "mqtts://HOST[:8883] (TLS)");
  mqtt->type_name("URL");
  command.add_option("--mqtt-topic", o.topic, "topic prefix (default pvtap/<hostname>)")
      ->type_name("PREFIX");
  command
      .add_option("--mqtt-client-id", o.client_id,
                  "MQTT client id (default pvtap-<hostname>-<pid>)")
      ->type_name("ID");
  command.add_option("--mqtt-user", o.user, "user name to log in to the broker")->type_name("USER");
  command
      .add_option("--mqtt-password-file", o.password_file,
                  "file whose first line is the broker password (never give it on the command "
                  "line)")
      ->type_name("FILE");
  command.add_option("--mqtt-ca", o.ca_file, "CA certificate that signed the broker's (mqtts)")
      ->type_name("FILE");
  command.add_option("--mqtt-cert", o.cert_file, "client certificate, for brokers that ask one")
      ->type_name("FILE");
  command.add_option("--mqtt-key", o.key_file, "private key of --mqtt-cert")->type_name("FILE");
  command
      .add_option("--mqtt-interval", o.interval,
                  "seconds between publications of values, states and health")
      ->check(CLI::Range(0.1, 86400.0).description(""))
      ->type_name("SECONDS")
      ->default_str("10");
  command.add_flag("--mqtt-discovery", o.discovery,
                   "publish Home Assistant discovery configs under homeassistant/");
  command.add_flag("--mqtt-raw", o.raw,
                   "also publish the words no register map names, as raw words keyed by table "
                   "and address (reg_0x0836, input_reg_0x0002)");
  // Each of them describes the --mqtt connection: alone it would do nothing.
  for (CLI::Option* option : command.get_options()) {
    if (option != mqtt && option->get_name().rfind("--mqtt-", 0) == 0) option->needs(mqtt);
  }
}

}  // namespace pvtap::analyzer
