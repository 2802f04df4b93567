// SunSpecInverter: a string inverter that answers the SunSpec models, the truth for pvtap's
// passive SunSpec decoding: "SunS" at 40000, then common (1), three-phase inverter (103) and
// multiple MPPT (160, two modules), then the end model. Its logger scans the chain as a SunSpec
// client does (marker, each header, the common model), again each round until one scan came
// back whole, and reads 103 and 160 every round. Scale factors differ per point and some points are
// not implemented (0x8000, 0xFFFF), as on real devices.
#pragma once

#include <cstdint>
#include <string>

#include "devices/modbus_device.h"
#include "sim_random.h"

namespace pvtap::sim {

class SunSpecInverter : public ModbusDevice {
 public:
  SunSpecInverter(std::uint8_t station, std::uint64_t seed, Micros start);

  DeviceLabel label() const override;
  std::vector<Frame> requests(unsigned round) const override;
  BusEvent reply(const Frame& request, Micros request_end) override;
  void answered(const Frame& request, bool whole) override;

  static constexpr std::uint16_t kBase = 40000;
  static constexpr std::uint16_t kCommon = kBase + 2;       // model 1 header
  static constexpr std::uint16_t kInverter = kCommon + 68;  // model 103 header
  static constexpr std::uint16_t kMppt = kInverter + 52;    // model 160 header
  static constexpr std::uint16_t kEnd = kMppt + 50;         // end model header

 private:
  // One point's register, scaled value and key as pvtap names it, for the ground truth.
  struct Point {
    std::uint16_t address;
    std::string key;
    double value;
    int sf;  // the value is sent as round(value / 10^sf)
  };
  void advance(Micros now);
  std::uint16_t word_at(std::uint16_t address, const std::vector<Point>& points) const;
  std::vector<Point> points() const;

  SimRandom random_;
  Micros now_;
  double power_w_ = 0.0;
  double energy_wh_ = 0.0;
  double volts_[3] = {230.0, 230.0, 230.0};
  double hz_ = 50.0;
  double cabinet_c_ = 35.0;
  std::string serial_;
  bool scanned_ = false;       // a scan came back whole: the client knows the chain
  bool scan_damaged_ = false;  // a reply of the scan under way was damaged or missing
};

}  // namespace pvtap::sim
