// StationTable: what MQTT holds of the stations of one bus between publications: the latest
// value of every register (latest only, however long the broker is away), the poll blocks
// and their periods, and whether each station still answers.
#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <utility>

#include "pvtap/session/bus_report.h"
#include "pvtap/session/bus_session.h"

namespace pvtap::analyzer {

// HeldValue: the newest reading of one register of a station and what was published of it.
struct HeldValue {
  DecodedValue value;
  double time = 0;          // start of the reply that carried it
  std::string published;    // the payload last sent (empty: never sent)
  bool discovered = false;  // its Home Assistant config was sent
};

// PollBlock: a run of registers a master reads (station, function, start address), and how
// often good replies bring it: the median of its last intervals, so that a master's retry or
// a duplicate reply (a short interval) or one lost poll (a long one) does not move it.
struct PollBlock {
  static constexpr std::size_t kIntervals = 9;
  // No period (and so no outage) before this many intervals: a master's first round often
  // reads a block twice in quick succession.
  static constexpr std::size_t kIntervalsToJudge = 3;
  double last = 0;
  std::array<double, kIntervals> intervals{};
  std::size_t count = 0;  // intervals seen, up to kIntervals
  std::size_t next = 0;   // ring position of the next interval

  void seen(double time);
  std::optional<double> period() const;
  bool missing(double now) const;
};

// StationState: one station's held values and timing.
struct StationState {
  std::uint8_t address = 0;
  Dialect dialect = kDefaultDialect;
  std::map<std::string, HeldValue, std::less<>> values;  // by value_key()
  std::map<std::pair<std::uint8_t, std::uint16_t>, PollBlock> blocks;
  double last_reply = 0;
  bool replied_since_state = false;  // a reply since the state topic was last sent
  std::optional<bool> online;        // as last published
  bool identity_changed = false;     // model, serial or maker changed: rediscover the device
  DeviceName device;                 // what a Modbus device said of itself (device identification)
  // The shortest period of its blocks: the station should answer at least this often.
  std::optional<double> period() const;
  // Answered within three poll periods, and within the last second (a station with no known
  // period yet answered once).
  bool answering(double now) const;
};

class StationTable {
 public:
  // Takes the values of a good reply; other frames change nothing.
  void record(const SessionFrame& f);
  // Whether words no map names are held (and so published) too, keyed reg_0x0836.
  void publish_raw(bool raw) { raw_ = raw; }
  std::map<std::uint8_t, StationState>& stations() { return stations_; }
  const std::map<std::uint8_t, StationState>& stations() const { return stations_; }
  std::size_t blocks() const;
  std::size_t blocks_missing(double now) const;

 private:
  std::map<std::uint8_t, StationState> stations_;
  bool raw_ = false;
};

// Keys whose value names the device (Home Assistant shows them on the device's card).
bool is_identity_key(std::string_view key);

}  // namespace pvtap::analyzer
