// MqttPublisher: the MQTT output of pvtap sniff and pvtap audit, an EventWriter like the
// text, jsonl and csv ones, plus a periodic tick for what is published per interval.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <string_view>

#include "broker/mqtt_client.h"
#include "events/event_writer.h"
#include "mqtt/event_lines.h"
#include "mqtt/mqtt_options.h"
#include "mqtt/mqtt_topics.h"
#include "mqtt/publish_schedule.h"
#include "mqtt/retained_topics.h"

namespace pvtap::analyzer {

// What goes out when:
// - events (damaged frames, exceptions, unsolicited replies, timeouts, capture gaps; a
//   station that stops answering or answers again) at once, as their jsonl line, QoS 1;
// - once per interval (on the capture's clock: wall time live, the capture's time when
//   replaying): every value that changed, each station's state and availability, each bus's
//   health, and the discovery configs of registers seen for the first time;
// - everything retained again after a reconnection (a restarted broker may have lost it).
// A live publisher (sniff) also keeps PREFIX/status: online, and offline as its last will.
class MqttPublisher : public EventWriter {
 public:
  // Connected to the broker, or null with a one-line reason in `error`.
  static std::unique_ptr<MqttPublisher> open(const MqttOptions& options, bool live,
                                             std::string& error);
  ~MqttPublisher() override;

  void frame(const EventContext& c, const SessionFrame& f) override;
  void timeout(const EventContext& c, const SessionTimeout& t) override;
  void noise(const EventContext& c, const SessionNoise& n) override;
  void gap(const EventContext& c, const SessionGap& g) override;

  // The capture clock reads `now`: publishes what is due. Cheap when nothing is.
  void tick(double now);
  // When tick() next has something to publish; nullopt before the first tick.
  std::optional<double> next_due() const { return schedule_.next_due(); }
  // A serial tap's driver counters (or none: not counted), for the health of its bus.
  void line_errors(std::string_view bus, const std::optional<LineErrorCounts>& counts);
  // End of input: publishes everything held, then (live) offline; waits a little for the
  // broker to take it all and disconnects. Warns when events were left undelivered.
  void finish(double now);

 private:
  MqttPublisher(std::unique_ptr<MqttClient> client, const MqttOptions& options, std::string prefix,
                bool live);

  void publish_event(const MqttBus& bus, std::string line);
  MqttBus& bus_of(const EventContext& c);

  std::unique_ptr<MqttClient> client_;
  MqttTopics topics_;
  PublishSchedule schedule_;
  RetainedTopics retained_;
  EventLines lines_;
  bool finished_ = false;
};

}  // namespace pvtap::analyzer
