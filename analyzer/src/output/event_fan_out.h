// EventFanOut: one EventWriter that hands every event to several (the chosen format on
// stdout, the --values file, the --html timeline), in the order they were added.
#pragma once

#include <vector>

#include "event_writer.h"

namespace pvtap::analyzer {

class EventFanOut : public EventWriter {
 public:
  // The writers are not owned; they must outlive the fan-out.
  explicit EventFanOut(std::vector<EventWriter*> writers) : writers_(std::move(writers)) {}

  void begin() override {
    for (EventWriter* w : writers_) w->begin();
  }
  void frame(const EventContext& c, const SessionFrame& f) override {
    for (EventWriter* w : writers_) w->frame(c, f);
  }
  void timeout(const EventContext& c, const SessionTimeout& t) override {
    for (EventWriter* w : writers_) w->timeout(c, t);
  }
  void noise(const EventContext& c, const SessionNoise& n) override {
    for (EventWriter* w : writers_) w->noise(c, n);
  }
  void gap(const EventContext& c, const SessionGap& g) override {
    for (EventWriter* w : writers_) w->gap(c, g);
  }

 private:
  std::vector<EventWriter*> writers_;
};

}  // namespace pvtap::analyzer
