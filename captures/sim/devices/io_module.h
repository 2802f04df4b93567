// IoModule: a digital IO module: 16 coils (relay outputs the logger switches), 16 discrete
// inputs (contacts that open and close on their own), two analog inputs and two holding
// registers (a setpoint the logger writes). The logger reads and writes a different mix of
// them in each round, so that every read and write function code shows up in three rounds.
#pragma once

#include <array>

#include "devices/modbus_device.h"

namespace pvtap::sim {

class IoModule : public ModbusDevice {
 public:
  IoModule(std::uint8_t station, std::uint64_t seed);

  DeviceLabel label() const override;
  std::vector<Frame> requests(unsigned round) const override;
  BusEvent reply(const Frame& request, Micros request_end) override;

  static constexpr std::uint16_t kPoints = 16;  // coils and discrete inputs
  static constexpr std::uint16_t kSetpoint = 0x0010;

 private:
  std::vector<bool> inputs_at(Micros now) const;
  std::vector<bool> bits(const std::vector<bool>& all, const Frame& request) const;
  WordList words(const Frame& request, Micros now) const;
  void apply_write(const Frame& request);

  std::uint64_t seed_;
  std::vector<bool> coils_ = std::vector<bool>(kPoints, false);
  std::array<std::uint16_t, 2> setpoint_{100, 0};
};

}  // namespace pvtap::sim
