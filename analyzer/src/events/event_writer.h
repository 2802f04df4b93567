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

// DriverGlitchEvent: a byte an RS485 driver put on the line as it switched on (right before a
// frame) or off (right after one); kept out of the frames and of the noise.
struct DriverGlitchEvent {
  double time = 0;  // its start bit's edge
  std::uint8_t value = 0;
  bool switch_on = true;
  bool framing_error = false;
};

// LineErrorEvent: a character the UART could not read cleanly (a stop bit read as space, a
// parity bit that does not hold) or a break. Such a character still goes to its frame, whose
// check then fails; the event says which character and why.
struct LineErrorEvent {
  enum class Kind : std::uint8_t { framing, parity, framing_and_parity, line_break };
  double time = 0;  // its start bit's edge
  double duration = 0;
  std::uint8_t value = 0;  // none for a break
  Kind kind = Kind::framing;
};

// The words for a line error in every output: "framing", "parity", "framing+parity", "break".
constexpr std::string_view line_error_name(LineErrorEvent::Kind kind) {
  switch (kind) {
    case LineErrorEvent::Kind::framing:
      return "framing";
    case LineErrorEvent::Kind::parity:
      return "parity";
    case LineErrorEvent::Kind::framing_and_parity:
      return "framing+parity";
    case LineErrorEvent::Kind::line_break:
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
  virtual void driver_glitch(const EventContext&, const DriverGlitchEvent&) {}
  virtual void line_error(const EventContext&, const LineErrorEvent&) {}
};

}  // namespace pvtap::analyzer
