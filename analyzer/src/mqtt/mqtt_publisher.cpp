// MqttPublisher: events as they come, retained topics per interval.
#include "mqtt/mqtt_publisher.h"

#include <cstdio>

#include "mqtt/ha_discovery.h"
#include "mqtt/mqtt_payloads.h"
#include "writers/event_writers.h"

namespace pvtap::analyzer {
namespace {

// How long the end of a capture waits for the broker to take what is left.
constexpr double kLiveCloseSeconds = 5;
constexpr double kReplayCloseSeconds = 60;
// A replay waits while this many messages are on their way (bounds its memory); a live
// capture never waits.
constexpr std::size_t kReplayWindow = 500;

bool is_event(const SessionFrame& f) {
  return !f.check.ok || !f.parse_error.empty() || f.unsolicited ||
         f.reply_kind == ReplyKind::GslException || f.reply_kind == ReplyKind::HybridError;
}

}  // namespace

MqttPublisher::MqttPublisher(std::unique_ptr<MqttClient> client, const MqttOptions& options,
                             std::string prefix, bool live)
    : client_(std::move(client)),
      topics_(std::move(prefix)),
      interval_(options.interval),
      discovery_(options.discovery),
      live_(live),
      line_sink_(std::fopen("/dev/null", "w")),
      line_(std::make_unique<OutputStream>(line_sink_)),
      jsonl_(make_jsonl_event_writer(*line_)) {}

MqttPublisher::~MqttPublisher() {
  // Ended without finish() (a device that could not be opened after the broker accepted
  // us): the site is not left "online", and nothing half-done is flushed.
  if (!finished_ && live_) client_->close(QueuedMessage{topics_.status(), "offline"}, 1.0);
  jsonl_.reset();
  line_.reset();
  if (line_sink_ != nullptr) std::fclose(line_sink_);
}

MqttPublisher::Bus& MqttPublisher::bus_of(const EventContext& c) {
  auto it = buses_.find(c.bus);
  if (it == buses_.end()) {
    Bus bus;
    bus.name = std::string(c.bus);
    bus.level = bus_level(c.bus);
    it = buses_.emplace(bus.name, std::move(bus)).first;
  }
  return it->second;
}

void MqttPublisher::pace() {
  if (!live_) client_->wait_for_room(kReplayWindow);
}

void MqttPublisher::publish_event_line(const Bus& bus) {
  pace();
  std::string& line = line_->buffer();
  if (!line.empty() && line.back() == '\n') line.pop_back();
  client_->publish_event(topics_.events(bus.level), line);
  line.clear();
}

void MqttPublisher::frame(const EventContext& c, const SessionFrame& f) {
  Bus& bus = bus_of(c);
  bus.health.count(f);
  bus.stations.record(f);
  if (is_event(f)) {
    jsonl_->frame(c, f);
    publish_event_line(bus);
  }
  tick(f.start_time);
}

void MqttPublisher::timeout(const EventContext& c, const SessionTimeout& t) {
  Bus& bus = bus_of(c);
  bus.health.count(t);
  if (t.kind != UnansweredKind::Timeout) return;
  jsonl_->timeout(c, t);
  publish_event_line(bus);
}

void MqttPublisher::noise(const EventContext& c, const SessionNoise& n) {
  bus_of(c).health.count(n);
}

void MqttPublisher::gap(const EventContext& c, const SessionGap& g) {
  Bus& bus = bus_of(c);
  bus.health.count(g);
  jsonl_->gap(c, g);
  publish_event_line(bus);
}

void MqttPublisher::line_errors(std::string_view bus,
                                const std::optional<LineErrorCounts>& counts) {
  EventContext c;
  c.bus = bus;
  bus_of(c).health.line_errors = counts;
}

void MqttPublisher::tick(double now) {
  // The first publication comes an interval after the first event, not with it.
  if (next_tick_ == 0) next_tick_ = now + interval_;
  if (now < next_tick_) return;
  next_tick_ = now + interval_;
  publish_due(now);
}

void MqttPublisher::publish_due(double now) {
  // Availability changes are events: judged whether or not the broker is there.
  for (auto& [name, bus] : buses_) judge_availability(bus, now);
  if (!client_->connected()) return;  // values stay held, latest only
  if (const std::uint64_t n = client_->connections(); n != connections_seen_) {
    connections_seen_ = n;
    forget_published();
  }
  for (auto& [name, bus] : buses_) publish_retained(bus, now);
}

void MqttPublisher::finish(double now) {
  finished_ = true;
  publish_due(now);
  std::optional<QueuedMessage> last;
  if (live_) last = QueuedMessage{topics_.status(), "offline"};
  if (!client_->close(last, live_ ? kLiveCloseSeconds : kReplayCloseSeconds)) {
    std::fprintf(stderr, "pvtap: warning: MQTT: %zu events were not delivered (%llu dropped)\n",
                 client_->events_queued(),
                 static_cast<unsigned long long>(client_->events_dropped()));
  }
}

void MqttPublisher::forget_published() {
  for (auto& [name, bus] : buses_) {
    bus.health_discovered = false;
    for (auto& [address, s] : bus.stations.stations()) {
      s.replied_since_state = true;
      s.identity_changed = true;
      if (s.online) {
        client_->publish_retained(topics_.availability(bus.level, address),
                                  *s.online ? "online" : "offline", 1);
      }
      for (auto& [key, held] : s.values) {
        held.published.clear();
        held.discovered = false;
      }
    }
  }
}

void MqttPublisher::judge_availability(Bus& bus, double now) {
  for (auto& [address, s] : bus.stations.stations()) {
    const bool answering = s.answering(now);
    if (s.online == answering) continue;
    if (s.online) {
      scratch_.clear();
      append_station_event_json(scratch_, answering, now, s, bus.name);
      client_->publish_event(topics_.events(bus.level), scratch_);
    }
    s.online = answering;
    // Sent now when connected, again with everything after a reconnection.
    client_->publish_retained(topics_.availability(bus.level, address),
                              answering ? "online" : "offline", 1);
  }
}

void MqttPublisher::publish_retained(Bus& bus, double now) {
  for (auto& [address, s] : bus.stations.stations()) {
    pace();
    if (discovery_) publish_discovery(bus, s);
    publish_station(bus, s);
  }
  publish_health(bus, now);
}

void MqttPublisher::publish_station(Bus& bus, StationState& s) {
  for (auto& [key, held] : s.values) {
    scratch_.clear();
    append_value_payload(scratch_, held.value);
    if (scratch_ == held.published) continue;
    if (client_->publish_retained(topics_.value(bus.level, s.address, key), scratch_, 0)) {
      held.published = scratch_;
    }
  }
  if (!s.replied_since_state) return;
  scratch_.clear();
  append_state_json(scratch_, s, bus.name, values_);
  if (client_->publish_retained(topics_.state(bus.level, s.address), scratch_, 0)) {
    s.replied_since_state = false;
  }
}

void MqttPublisher::publish_discovery(Bus& bus, StationState& s) {
  const DiscoveryScope scope{&topics_, bus.name, bus.level, live_};
  for (auto& [key, held] : s.values) {
    if (held.discovered && !s.identity_changed) continue;
    bool sent = true;
    for (const QueuedMessage& m : discovery_configs(scope, s, key, held)) {
      sent = client_->publish_retained(m.topic, m.payload, 1) && sent;
    }
    held.discovered = sent;
  }
  s.identity_changed = false;
  if (bus.health_discovered) return;
  bool sent = true;
  for (const QueuedMessage& m : health_discovery_configs(scope)) {
    sent = client_->publish_retained(m.topic, m.payload, 1) && sent;
  }
  bus.health_discovered = sent;
}

void MqttPublisher::publish_health(Bus& bus, double now) {
  HealthContext c;
  c.now = now;
  c.interval = interval_;
  c.bus = bus.name;
  for (const auto& [address, s] : bus.stations.stations()) {
    ++c.stations;
    if (s.online.value_or(true)) ++c.stations_answering;
  }
  c.poll_blocks = bus.stations.blocks();
  c.poll_blocks_missing = bus.stations.blocks_missing(now);
  c.events_queued = client_->events_queued();
  c.events_dropped = client_->events_dropped();
  scratch_.clear();
  append_health_json(scratch_, bus.health, c);
  client_->publish_retained(topics_.health(bus.level), scratch_, 0);
  bus.health.start_interval();
}

}  // namespace pvtap::analyzer
