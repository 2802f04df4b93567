#include "devices/battery.h"

#include <algorithm>
#include <cmath>

#include "bus/frame_shapes.h"
#include "dialects/modbus_frames.h"
#include "pvtap/codec/function_codes.h"

namespace pvtap::sim {
namespace {

constexpr std::uint8_t kHolding = fc::kGslReadHolding;

// Status word flags.
constexpr std::uint16_t kRunning = 1u << 0;
constexpr std::uint16_t kCharging = 1u << 3;
constexpr std::uint16_t kDischarging = 1u << 4;
constexpr std::uint16_t kBalancing = 1u << 9;

std::uint16_t s16(double v) {
  return static_cast<std::uint16_t>(static_cast<std::int16_t>(std::lround(v)));
}

}  // namespace

Battery::Battery(std::uint8_t station, std::uint64_t seed, Micros start)
    : ModbusDevice(station), random_(seed ^ 0xBA77ull * (station + 1)), now_(start) {
  // A few hundred Wh short of the low word's wrap, so that a run of minutes crosses it.
  charged_wh_ = 3.0 * 65536.0 - 60.0 - static_cast<double>(random_.between(0, 40));
  messages_ = static_cast<std::uint16_t>(random_.between(0, 0xFFFF));
  serial_ = "SN" + std::to_string(100000 + random_.between(0, 899999)) + "-" +
            std::to_string(static_cast<unsigned>(station));
}

DeviceLabel Battery::label() const {
  return {"battery", {}, {}, {}, {}};
}

std::vector<LayoutTruth> Battery::layout() const {
  const auto at = [](unsigned offset) { return static_cast<std::uint16_t>(kStatus + offset); };
  return {
      {kHolding, at(0), 1, "u16", false, false, "state_of_charge"},
      {kHolding, at(1), 1, "s16", false, false, "current"},
      {kHolding, at(2), 1, "u16", false, false, "voltage"},
      {kHolding, at(3), 1, "s16", false, false, "power"},
      {kHolding, at(4), 2, "u32", false, true, "charged_energy"},
      {kHolding, at(6), 2, "s32", true, false, "grid_power"},
      {kHolding, at(8), 1, "bits", false, false, "status"},
      {kHolding, at(9), 1, "u16", false, false, "rated_capacity"},
      {kHolding, at(10), 1, "unused", false, false, "reserved_1"},
      {kHolding, at(11), 1, "unused", false, false, "reserved_2"},
      {kHolding, at(12), 1, "u16", false, true, "messages"},
      {kHolding, at(13), 1, "unused", false, false, "reserved_3"},
      {kHolding, kName, 8, "text", false, false, "model"},
      {kHolding, static_cast<std::uint16_t>(kName + 8), 8, "text", false, false, "serial"},
  };
}

std::vector<Frame> Battery::requests(unsigned /*round*/) const {
  return {modbus_read(station(), kHolding, kStatus, kStatusCount),
          modbus_read(station(), kHolding, kName, kNameCount)};
}

// The battery follows a charge and discharge cycle of a few minutes (a simulation is short),
// its current noisy, its voltage following the charge.
void Battery::advance(Micros now) {
  const double seconds = static_cast<double>(std::max<Micros>(0, now - now_)) / 1e6;
  now_ = std::max(now, now_);
  const double phase = std::sin(static_cast<double>(now_) / 1e6 / 90.0);
  current_a_ = std::clamp(40.0 * phase + (random_.unit() - 0.5) * 4.0, -60.0, 60.0);
  soc_ = std::clamp(soc_ + current_a_ * seconds / 3600.0 / 100.0, 0.05, 1.0);
  voltage_v_ = 48.0 + 6.0 * soc_ + current_a_ * 0.01;
  // Charging counts into the counter, and so does a steady trickle of balancing: it grows
  // in every minute.
  charged_wh_ += (std::max(current_a_, 0.0) * voltage_v_ + 800.0) * seconds / 3600.0;
  messages_ = static_cast<std::uint16_t>(messages_ + 997u);
}

std::uint16_t Battery::word_at(std::uint16_t address) const {
  const double power_w = current_a_ * voltage_v_;
  const auto energy = static_cast<std::uint32_t>(charged_wh_);
  // The grid's share of the power in W, as two's complement over 32 bits, low word first.
  const auto grid =
      static_cast<std::uint32_t>(static_cast<std::int32_t>(std::lround(power_w * 0.7)));
  std::uint16_t status = kRunning;
  if (current_a_ > 1.0) status |= kCharging;
  if (current_a_ < -1.0) status |= kDischarging;
  if (soc_ > 0.9) status |= kBalancing;
  switch (address - kStatus) {
    case 0:
      return static_cast<std::uint16_t>(std::lround(soc_ * 1000.0));  // 0.1 %
    case 1:
      return s16(current_a_ * 10.0);  // 0.1 A
    case 2:
      return static_cast<std::uint16_t>(std::lround(voltage_v_ * 100.0));  // 0.01 V
    case 3:
      return s16(power_w);  // 1 W
    case 4:
      return static_cast<std::uint16_t>(energy >> 16);
    case 5:
      return static_cast<std::uint16_t>(energy & 0xFFFFu);
    case 6:
      return static_cast<std::uint16_t>(grid & 0xFFFFu);
    case 7:
      return static_cast<std::uint16_t>(grid >> 16);
    case 8:
      return status;
    case 9:
      return 5120;  // rated capacity, Wh / 2
    case 10:
    case 11:
      return 0xFFFF;
    case 12:
      return messages_;
    case 13:
      return 0x8000;
    default:
      break;
  }
  if (address >= kName && address < kName + kNameCount) {
    const unsigned index = address - kName;
    return text_word(index < 8 ? model_ : serial_, index % 8);
  }
  return 0;
}

BusEvent Battery::reply(const Frame& request, Micros request_end) {
  advance(request_end);
  const WordList words = register_words(request, [this](std::uint16_t a) { return word_at(a); });
  return frame_event(register_reply(request, words));
}

}  // namespace pvtap::sim
