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
  // Times count from a logic recording's start: there is no wall clock to read them by.
  bool from_recording_start = false;
  // The bus's session, for a writer that publishes what only it can say as it goes (MQTT
  // health: masters, collisions); null where the events come from no session.
  const BusSession* session = nullptr;
};

// The words for a line error in every output: "framing", "parity", "framing+parity", "break".
constexpr std::string_view line_error_name(LineErrorKind kind) {
  switch (kind) {
    case LineErrorKind::Framing:
      return "framing";
    case LineErrorKind::Parity:
      return "parity";
    case LineErrorKind::FramingAndParity:
      return "framing+parity";
    case LineErrorKind::Break:
      return "break";
  }
  return "framing";
}

class EventWriter {
 public:
  virtual ~EventWriter() = default;
  virtual void begin() {}
  virtual void frame(const EventContext& c, const SessionFrame& f) = 0;
  virtual void timeout(const EventContext& c, const SessionTimeout& t) = 0;
  virtual void noise(const EventContext& c, const SessionNoise& n) = 0;
  virtual void gap(const EventContext& c, const SessionGap& g) = 0;
  // Only buses with a second master have them; formats that list events show them.
  virtual void collision(const EventContext&, const SessionCollision&) {}
  // Only logic recordings see the line itself: other formats need not show these.
  virtual void driver_glitch(const EventContext&, const SessionDriverGlitch&) {}
  virtual void line_error(const EventContext&, const SessionLineError&) {}
};

}  // namespace pvtap::analyzer
