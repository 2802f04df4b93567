// TestSuiteServer: the server of a Modbus library's own test suite, driven by that suite's
// master: a report server ID, read/write multiple registers (0x17), writes answered by their
// normal echoes, and a read to a station nobody has whose reply a peer puts on the line after
// the master gave it up (a suite checking that replies for another slave are ignored), and a
// read broadcast to address 0, which the specification does not allow and nobody answers.
#pragma once

#include <array>
#include <string_view>

#include "devices/modbus_device.h"

namespace pvtap::sim {

class TestSuiteServer : public ModbusDevice {
 public:
  explicit TestSuiteServer(std::uint8_t station);

  DeviceLabel label() const override;
  std::vector<Frame> requests(unsigned round) const override;
  BusEvent reply(const Frame& request, Micros request_end) override;
  Answer answer_of(const Frame& request) const override;
  bool keeps_echoes_whole() const override { return true; }

  // The text of its report server ID reply: the name a reader should give the station.
  static constexpr std::string_view kName = "pvtap-sim test server v1";
  static constexpr std::uint8_t kServerId = 0x2A;
  static constexpr std::uint16_t kRegisters = 16;
  static constexpr std::uint8_t kUserDefined = 0x42;

  // The station the suite's master asks although no server has it; its reply comes late.
  std::uint8_t absent_station() const;

 private:
  WordList read(std::uint16_t start, std::uint16_t count) const;
  void write(std::uint16_t start, const WordList& words);

  std::array<std::uint16_t, kRegisters> registers_{};
  bool coil_ = false;
};

}  // namespace pvtap::sim
