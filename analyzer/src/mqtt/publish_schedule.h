// PublishSchedule: when pvtap publishes: the retained topics once per interval on the capture's
// clock, and a replay paced by what the broker has taken.
#pragma once

#include <optional>

#include "broker/mqtt_client.h"

namespace pvtap::analyzer {

// The capture's clock is wall time live and the capture's time when replaying: a replay
// publishes as often per capture second as the capture it replays.
class PublishSchedule {
 public:
  PublishSchedule(double interval, bool live) : interval_(interval), live_(live) {}

  // The clock reads `now`: true when the retained topics are due. The first publication comes
  // an interval after the first event, not with it.
  bool due(double now);
  // When due() next says true; nullopt before the clock was first read.
  std::optional<double> next_due() const {
    return next_ > 0 ? std::optional<double>(next_) : std::nullopt;
  }
  double interval() const { return interval_; }
  // A live capture (sniff), as opposed to a replay (audit).
  bool live() const { return live_; }
  // A replay waits here while many messages are on their way, which bounds its memory; a
  // live capture never waits.
  void pace(MqttClient& client) const;

 private:
  double interval_;
  bool live_;
  double next_ = 0;
};

}  // namespace pvtap::analyzer
