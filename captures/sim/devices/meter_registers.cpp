#include "devices/meter_registers.h"

#include <array>

#include "pvtap/codec/function_codes.h"

namespace pvtap::sim {
namespace {

using Q = MeterQuantity;
constexpr std::uint8_t kInput = fc::kGslReadInput, kHolding = fc::kGslReadHolding;

constexpr std::array kTable{
    MeterRegister{kInput, 0x0000, Q::VoltageL1, "voltage_l1"},
    MeterRegister{kInput, 0x0002, Q::VoltageL2, "voltage_l2"},
    MeterRegister{kInput, 0x0004, Q::VoltageL3, "voltage_l3"},
    MeterRegister{kInput, 0x0006, Q::CurrentL1, "current_l1"},
    MeterRegister{kInput, 0x0008, Q::CurrentL2, "current_l2"},
    MeterRegister{kInput, 0x000A, Q::CurrentL3, "current_l3"},
    MeterRegister{kInput, 0x000C, Q::PowerL1, "power_l1"},
    MeterRegister{kInput, 0x000E, Q::PowerL2, "power_l2"},
    MeterRegister{kInput, 0x0010, Q::PowerL3, "power_l3"},
    MeterRegister{kInput, 0x0034, Q::TotalPower, "total_power"},
    MeterRegister{kInput, 0x0046, Q::Frequency, "frequency"},
    MeterRegister{kInput, 0x0048, Q::ImportEnergy, "import_energy"},
    MeterRegister{kInput, 0x004A, Q::ExportEnergy, "export_energy"},
    MeterRegister{kHolding, 0x000A, Q::SystemType, "system_type"},
    MeterRegister{kHolding, 0x0014, Q::NodeAddress, "node_address"},
};

}  // namespace

std::span<const MeterRegister> meter_registers() {
  return kTable;
}

const MeterRegister* meter_register_at(std::uint8_t function, std::uint16_t address) {
  for (const MeterRegister& r : kTable)
    if (r.function == function && r.address == address) return &r;
  return nullptr;
}

}  // namespace pvtap::sim
