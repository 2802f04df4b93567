// MqttPublisher: events as they come, retained topics per interval.
#include "mqtt/mqtt_publisher.h"

#include <cstdio>

namespace pvtap::analyzer {
namespace {

// How long the end of a capture waits for the broker to take what is left.
constexpr double kLiveCloseSeconds = 5;
constexpr double kReplayCloseSeconds = 60;

bool is_event(const SessionFrame& f) {
  return !f.check.ok || !f.parse_error.empty() || f.unsolicited ||
         f.reply_kind == ReplyKind::GslException || f.reply_kind == ReplyKind::HybridError;
}

}  // namespace

MqttPublisher::MqttPublisher(std::unique_ptr<MqttClient> client, const MqttOptions& options,
                             std::string prefix, bool live)
    : client_(std::move(client)),
      topics_(std::move(prefix), options.lone_serial_bus),
      schedule_(options.interval, live),
      retained_(*client_, topics_, schedule_, options.discovery, options.raw) {}

MqttPublisher::~MqttPublisher() {
  // Ended without finish() (a device that could not be opened after the broker accepted
  // us): the site is not left "online", and nothing half-done is flushed.
  if (!finished_ && schedule_.live()) {
    client_->close(QueuedMessage{topics_.status(), "offline"}, 1.0);
  }
}

MqttBus& MqttPublisher::bus_of(const EventContext& c) {
  MqttBus& bus = retained_.bus(c.bus);
  if (c.session) bus.session = c.session;
  return bus;
}

void MqttPublisher::publish_event(const MqttBus& bus, std::string line) {
  schedule_.pace(*client_);
  client_->publish_event(topics_.events(bus.level), std::move(line));
}

void MqttPublisher::frame(const EventContext& c, const SessionFrame& f) {
  MqttBus& bus = bus_of(c);
  bus.health.count(f);
  bus.stations.record(f);
  if (is_event(f)) publish_event(bus, lines_.frame(c, f));
  tick(f.start_time);
}

void MqttPublisher::timeout(const EventContext& c, const SessionTimeout& t) {
  MqttBus& bus = bus_of(c);
  bus.health.count(t);
  if (t.kind != UnansweredKind::Timeout) return;
  publish_event(bus, lines_.timeout(c, t));
}

void MqttPublisher::noise(const EventContext& c, const SessionNoise& n) {
  bus_of(c).health.count(n);
}

void MqttPublisher::gap(const EventContext& c, const SessionGap& g) {
  MqttBus& bus = bus_of(c);
  bus.health.count(g);
  publish_event(bus, lines_.gap(c, g));
}

void MqttPublisher::line_errors(std::string_view bus,
                                const std::optional<LineErrorCounts>& counts) {
  retained_.bus(bus).health.line_errors = counts;
}

void MqttPublisher::tick(double now) {
  if (schedule_.due(now)) retained_.publish(now);
}

void MqttPublisher::finish(double now) {
  finished_ = true;
  retained_.publish(now);
  const bool live = schedule_.live();
  std::optional<QueuedMessage> last;
  if (live) last = QueuedMessage{topics_.status(), "offline"};
  if (!client_->close(last, live ? kLiveCloseSeconds : kReplayCloseSeconds)) {
    std::fprintf(stderr, "pvtap: warning: MQTT: %zu events were not delivered (%llu dropped)\n",
                 client_->events_queued(),
                 static_cast<unsigned long long>(client_->events_dropped()));
  }
}

}  // namespace pvtap::analyzer
