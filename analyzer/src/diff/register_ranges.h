// RegisterRanges: the range every numeric register of every station took over a capture, for
// `pvtap diff` to tell a register whose values moved out of their earlier range. It listens to
// the event stream as any output does, and keeps one entry per register, not per reading.
#pragma once

#include <compare>
#include <cstdint>
#include <map>
#include <string>

#include "events/event_writer.h"

namespace pvtap::analyzer {

// RegisterKey: one register of one station on one bus (the bus's name, empty for a serial
// capture's one bus).
struct RegisterKey {
  std::string bus;
  std::uint8_t station = 0;
  Dialect dialect = kDefaultDialect;
  std::uint16_t address = 0;  // the written address of the value's first word
  friend auto operator<=>(const RegisterKey&, const RegisterKey&) = default;
};

// ValueRange: the lowest and highest reading, how many readings, and what the map calls the
// register ("battery voltage", "V"; empty for a word outside the map).
struct ValueRange {
  double min = 0;
  double max = 0;
  std::uint64_t readings = 0;
  std::string name;
  std::string unit;
};

using RegisterRangeMap = std::map<RegisterKey, ValueRange>;

class RegisterRanges : public EventWriter {
 public:
  const RegisterRangeMap& ranges() const { return ranges_; }

  void frame(const EventContext& c, const SessionFrame& f) override;
  void timeout(const EventContext&, const SessionTimeout&) override {}
  void noise(const EventContext&, const SessionNoise&) override {}
  void gap(const EventContext&, const SessionGap&) override {}

 private:
  RegisterRangeMap ranges_;
};

}  // namespace pvtap::analyzer
