// EventFanout: hands every event of the buses to each consumer in turn (the output format,
// the --write file, the run's tally, and whatever else a command adds).
#pragma once

#include <vector>

#include "events/event_writer.h"

namespace pvtap::analyzer {

class EventFanout : public EventWriter {
 public:
  // `consumer` must outlive the fan-out.
  void add(EventWriter& consumer) { consumers_.push_back(&consumer); }

  void begin() override {
    for (EventWriter* c : consumers_) c->begin();
  }
  void frame(const EventContext& c, const SessionFrame& f) override {
    for (EventWriter* w : consumers_) w->frame(c, f);
  }
  void timeout(const EventContext& c, const SessionTimeout& t) override {
    for (EventWriter* w : consumers_) w->timeout(c, t);
  }
  void noise(const EventContext& c, const SessionNoise& n) override {
    for (EventWriter* w : consumers_) w->noise(c, n);
  }
  void gap(const EventContext& c, const SessionGap& g) override {
    for (EventWriter* w : consumers_) w->gap(c, g);
  }
  void collision(const EventContext& c, const SessionCollision& k) override {
    for (EventWriter* w : consumers_) w->collision(c, k);
  }
  void driver_glitch(const EventContext& c, const SessionDriverGlitch& g) override {
    for (EventWriter* w : consumers_) w->driver_glitch(c, g);
  }
  void line_error(const EventContext& c, const SessionLineError& e) override {
    for (EventWriter* w : consumers_) w->line_error(c, e);
  }

 private:
  std::vector<EventWriter*> consumers_;
};

}  // namespace pvtap::analyzer
