#include "devices/energy_meter.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "bus/frame_shapes.h"
#include "dialects/modbus_frames.h"
#include "pvtap/codec/function_codes.h"

namespace pvtap::sim {
namespace {

constexpr const char* kVendor = "pvtap-sim";
constexpr const char* kProduct = "SDM630-compatible meter";
constexpr const char* kRevision = "1.04";

std::string hex_address(std::uint16_t address) {
  char buf[8];
  std::snprintf(buf, sizeof buf, "0x%04X", address);
  return buf;
}

}  // namespace

EnergyMeter::EnergyMeter(std::uint8_t station, std::uint64_t seed, Micros start,
                         std::function<double()> plant_kw, bool low_first)
    : ModbusDevice(station),
      plant_kw_(std::move(plant_kw)),
      low_first_(low_first),
      random_(seed ^ 0x3E7E4ull * (station + 1)),
      now_(start) {
  using Q = MeterQuantity;
  // Counters of a few years of a plant that exports more than it imports.
  at(Q::ImportEnergy) = 4000.0 + static_cast<double>(random_.between(0, 2000));
  at(Q::ExportEnergy) = 9000.0 + static_cast<double>(random_.between(0, 4000));
  at(Q::SystemType) = 3.0;  // three phases, four wires
  at(Q::NodeAddress) = station;
  at(Q::Frequency) = 50.0;
}

DeviceLabel EnergyMeter::label() const {
  return {"meter", kVendor, kProduct, kRevision, {}};
}

// Every float of the table is polled (the holding registers in the first round only).
std::vector<LayoutTruth> EnergyMeter::layout() const {
  std::vector<LayoutTruth> out;
  for (const MeterRegister& r : meter_registers())
    out.push_back({r.function, r.address, 2, "float32", low_first_, false, r.key});
  return out;
}

std::vector<Frame> EnergyMeter::requests(unsigned round) const {
  const std::uint8_t s = station();
  std::vector<Frame> out;
  if (round == 0) {
    out.push_back(return_query_data(s, 0xA537));
    out.push_back(read_device_identification(s));
    out.push_back(modbus_read(s, fc::kGslReadHolding, 0x000A, 2));
    out.push_back(modbus_read(s, fc::kGslReadHolding, 0x0014, 2));
  }
  out.push_back(modbus_read(s, fc::kGslReadInput, 0x0000, 18));
  out.push_back(modbus_read(s, fc::kGslReadInput, 0x0034, 2));
  out.push_back(modbus_read(s, fc::kGslReadInput, 0x0046, 6));
  return out;
}

void EnergyMeter::advance(Micros now) {
  using Q = MeterQuantity;
  const double hours = static_cast<double>(std::max<Micros>(0, now - now_)) / 3.6e9;
  now_ = std::max(now, now_);
  // The house load wanders between 0.3 and 4 kW.
  load_kw_ = std::clamp(load_kw_ + (random_.unit() - 0.5) * 0.2, 0.3, 4.0);
  const double net_kw = load_kw_ - plant_kw_();
  at(Q::ImportEnergy) += std::max(net_kw, 0.0) * hours;
  at(Q::ExportEnergy) += std::max(-net_kw, 0.0) * hours;
  at(Q::Frequency) = std::clamp(at(Q::Frequency) + (random_.unit() - 0.5) * 0.01, 49.95, 50.05);
  at(Q::TotalPower) = net_kw * 1000.0;
  for (unsigned phase = 0; phase < 3; ++phase) {
    voltage_drift_[phase] = std::clamp(voltage_drift_[phase] + (random_.unit() - 0.5), -4.0, 4.0);
    // A phase carries a third of the power, give or take the house's single-phase loads.
    const double watts = net_kw * 1000.0 / 3.0 * (0.95 + 0.1 * random_.unit());
    // Export lifts the voltage at the connection point (about 1 V per exported kW).
    const double volts = 230.0 + voltage_drift_[phase] - net_kw / 3.0;
    values_[static_cast<unsigned>(Q::VoltageL1) + phase] = volts;
    values_[static_cast<unsigned>(Q::CurrentL1) + phase] = std::abs(watts) / volts;
    values_[static_cast<unsigned>(Q::PowerL1) + phase] = watts;
  }
}

BusEvent EnergyMeter::register_event(const Frame& request) const {
  WordList words;
  std::vector<RegisterTruth> truth;
  const std::uint16_t start = request.start.value_or(0), count = request.count.value_or(0);
  for (std::uint16_t offset = 0; offset + 1 < count; offset += 2) {
    const auto address = static_cast<std::uint16_t>(start + offset);
    const MeterRegister* r = meter_register_at(request.function, address);
    const float v = r ? value(r->quantity) : 0.0f;
    push_float(words, v, low_first_);
    if (r) truth.push_back({hex_address(address), r->key, float_bits(v), v, true, {}});
  }
  // A read of an odd count (a count one short) ends on a float's first word.
  if (count % 2 == 1) {
    const auto address = static_cast<std::uint16_t>(start + count - 1);
    const MeterRegister* r = meter_register_at(request.function, address);
    WordList both;
    push_float(both, r ? value(r->quantity) : 0.0f, low_first_);
    words.push_back(both[0]);
  }
  BusEvent e = frame_event(register_reply(request, words));
  e.values = std::move(truth);
  return e;
}

BusEvent EnergyMeter::reply(const Frame& request, Micros request_end) {
  advance(request_end);
  switch (request.function) {
    case fc::kDiagnostics:
      return frame_event(echo_of(request));
    case fc::kEncapsulatedInterface:
      return frame_event(device_identification_reply(request, kVendor, kProduct, kRevision));
    default:
      return register_event(request);
  }
}

}  // namespace pvtap::sim
