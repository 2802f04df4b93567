// Battery: a home battery beside the inverters, polled over function code 0x03, with the mix of
// register types a real one has and no map pvtap ships: a state of charge and a voltage
// (unsigned), a current and a power that change sign with charging (signed), an energy counter
// over two words, a status word of flags, a constant, fill words of registers it lacks, a
// message counter that wraps, and its model and serial as text.
#pragma once

#include <cstdint>
#include <string>

#include "devices/modbus_device.h"
#include "sim_random.h"

namespace pvtap::sim {

class Battery : public ModbusDevice {
 public:
  Battery(std::uint8_t station, std::uint64_t seed, Micros start);

  DeviceLabel label() const override;
  std::vector<LayoutTruth> layout() const override;
  std::vector<Frame> requests(unsigned round) const override;
  BusEvent reply(const Frame& request, Micros request_end) override;

  static constexpr std::uint16_t kStatus = 0x0100;  // the measurements, 14 registers
  static constexpr std::uint16_t kStatusCount = 14;
  static constexpr std::uint16_t kName = 0x0200;  // model and serial, 8 registers each
  static constexpr std::uint16_t kNameCount = 16;

 private:
  void advance(Micros now);
  std::uint16_t word_at(std::uint16_t address) const;

  SimRandom random_;
  Micros now_;
  double soc_ = 0.55;        // 0..1
  double current_a_ = 0.0;   // positive: charging
  double voltage_v_ = 51.2;  // of the pack
  double charged_wh_ = 0.0;  // energy counter, Wh
  std::uint16_t messages_ = 0;
  std::string model_ = "PVTAP-BAT-5K";
  std::string serial_;
};

}  // namespace pvtap::sim
