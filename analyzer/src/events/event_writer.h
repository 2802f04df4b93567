// EventWriter: one output format for what the bus sessions report as they go.
#pragma once

#include <cstdint>
#include <string_view>

#include "pvtap/session/bus_session.h"

namespace pvtap::analyzer {

// EventContext: what every line needs besides the event: which bus it came from (empty for
// serial inputs, which have one bus) and whether the input has timestamps at all.
struct EventContext {
  std::string_view bus;
  bool has_timestamps = true;
};

// DriverGlitchEvent: a byte an RS485 driver put on the line as it switched on (right before a
// frame) or off (right after one); kept out of the frames and of the noise.
struct DriverGlitchEvent {
  double time = 0;  // its start bit's edge
  std::uint8_t value = 0;
  bool switch_on = true;
  bool framing_error = false;
};

class EventWriter {
 public:
  virtual ~EventWriter() = default;
  virtual void begin() {}
  virtual void frame(const EventContext& c, const SessionFrame& f) = 0;
  virtual void timeout(const EventContext& c, const SessionTimeout& t) = 0;
  virtual void noise(const EventContext& c, const SessionNoise& n) = 0;
  virtual void gap(const EventContext& c, const SessionGap& g) = 0;
  // Only logic recordings see the line itself: other formats need not show these.
  virtual void driver_glitch(const EventContext&, const DriverGlitchEvent&) {}
};

}  // namespace pvtap::analyzer
