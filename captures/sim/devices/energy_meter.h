// EnergyMeter: a three-phase meter at the plant's point of connection. Its power is the house
// load less what the inverters feed (positive: import, negative: export), its voltages rise a
// little with the export, its import and export counters only grow.
#pragma once

#include <array>
#include <functional>

#include "devices/meter_registers.h"
#include "devices/modbus_device.h"
#include "sim_random.h"

namespace pvtap::sim {

class EnergyMeter : public ModbusDevice {
 public:
  // `plant_kw()`: the AC power the inverters feed now. `low_first`: the meter sends the low
  // word of each float first (as some makers do).
  EnergyMeter(std::uint8_t station, std::uint64_t seed, Micros start,
              std::function<double()> plant_kw, bool low_first = false);

  DeviceLabel label() const override;
  std::vector<LayoutTruth> layout() const override;
  std::vector<Frame> requests(unsigned round) const override;
  BusEvent reply(const Frame& request, Micros request_end) override;

 private:
  void advance(Micros now);
  double& at(MeterQuantity q) { return values_[static_cast<unsigned>(q)]; }
  float value(MeterQuantity q) const {
    return static_cast<float>(values_[static_cast<unsigned>(q)]);
  }
  BusEvent register_event(const Frame& request) const;

  std::function<double()> plant_kw_;
  bool low_first_ = false;
  SimRandom random_;
  Micros now_;
  double load_kw_ = 0.9;
  std::array<double, 3> voltage_drift_{};
  std::array<double, kMeterQuantities> values_{};
};

}  // namespace pvtap::sim
