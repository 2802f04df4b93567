// EventWriter: one output format for what the bus sessions report as they go.
#pragma once

#include <string_view>

#include "pvtap/session/bus_session.h"

namespace pvtap::analyzer {

// EventContext: what every line needs besides the event: which bus it came from (empty for
// serial inputs, which have one bus) and whether the input has timestamps at all.
struct EventContext {
  std::string_view bus;
  bool has_timestamps = true;
};

class EventWriter {
 public:
  virtual ~EventWriter() = default;
  virtual void begin() {}
  virtual void frame(const EventContext& c, const SessionFrame& f) = 0;
  virtual void timeout(const EventContext& c, const SessionTimeout& t) = 0;
  virtual void noise(const EventContext& c, const SessionNoise& n) = 0;
  virtual void gap(const EventContext& c, const SessionGap& g) = 0;
};

}  // namespace pvtap::analyzer
