// ModbusDevice: a plain Modbus RTU device on the inverters' bus (PROTOCOLS.md section 6): the
// requests a data logger sends it in each poll round and its normal replies.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "bus/bus_event.h"
#include "pvtap/codec/frame.h"

namespace pvtap::sim {

class ModbusDevice {
 public:
  explicit ModbusDevice(std::uint8_t station) : station_(station) {}
  virtual ~ModbusDevice() = default;

  std::uint8_t station() const { return station_; }
  virtual DeviceLabel label() const = 0;
  // What its polled registers hold, for the ground truth (empty: not published).
  virtual std::vector<LayoutTruth> layout() const { return {}; }
  // The requests of poll round `round`, in the order the logger sends them (round 0 adds the
  // start-up requests: diagnostics, identification, settings).
  virtual std::vector<Frame> requests(unsigned round) const = 0;
  // The normal reply to `request`, which ended at `request_end`, with the values it carries.
  // A write takes effect here: a device changes only what it answers.
  virtual BusEvent reply(const Frame& request, Micros request_end) = 0;
  // Told after each exchange whether the logger got `request`'s reply whole (no fault on it):
  // a client that must read something whole (a SunSpec scan) asks again in the next round.
  virtual void answered(const Frame& /*request*/, bool /*whole*/) {}

  // How a request is answered: normally (faults aside); for a station nobody has, by a reply
  // a peer puts on the line after the master gave the request up (a late reply); or, sent to
  // address 0, by nobody (a broadcast, which no station answers); or, for a request the
  // server refuses, free of faults: a user-defined function it lacks by exception 0x01
  // (illegal function), a write whose byte count the master got wrong by 0x03 (illegal data
  // value).
  enum class Answer { Normal, LateFromAbsent, Broadcast, Refused };
  virtual Answer answer_of(const Frame& /*request*/) const { return Answer::Normal; }
  // Whether the line never damages its echoes: on a carrier without directions an echo whose
  // station byte was damaged reads as a damaged request to another station, which no reader
  // can tell apart (the older devices keep their samples' bytes and may damage them).
  virtual bool keeps_echoes_whole() const { return false; }

 private:
  std::uint8_t station_;
};

}  // namespace pvtap::sim
