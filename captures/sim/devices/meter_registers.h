// The input and holding registers the simulated energy meter answers, at the addresses of the
// Eastron SDM630's published table: every value an IEEE-754 single in two registers, high
// word first.
#pragma once

#include <cstdint>
#include <span>

namespace pvtap::sim {

// MeterQuantity: what the meter measures or holds; MeterState keeps one value of each.
enum class MeterQuantity : unsigned {
  VoltageL1,
  VoltageL2,
  VoltageL3,
  CurrentL1,
  CurrentL2,
  CurrentL3,
  PowerL1,
  PowerL2,
  PowerL3,
  TotalPower,
  Frequency,
  ImportEnergy,
  ExportEnergy,
  SystemType,
  NodeAddress,
};
inline constexpr std::size_t kMeterQuantities = 15;

// MeterRegister: one float of the table: its first register, its function and its key.
struct MeterRegister {
  std::uint8_t function = 0;  // 0x04 input, 0x03 holding
  std::uint16_t address = 0;
  MeterQuantity quantity{};
  const char* key = "";
};

std::span<const MeterRegister> meter_registers();
// The float starting at `address` of `function`'s table, or nullptr.
const MeterRegister* meter_register_at(std::uint8_t function, std::uint16_t address);

}  // namespace pvtap::sim
