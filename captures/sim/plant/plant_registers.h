// What every dialect's inverter uses to write a plant's state into its registers
// (dialects/<name>_inverter.cpp fill the registers of their maps by the maps' keys).
#pragma once

#include <cmath>
#include <cstdint>

namespace pvtap::sim {

inline std::uint32_t bit(bool on, unsigned index) {
  return on ? 1u << index : 0u;
}

// Reactive power that goes with active power `kw` at power factor `pf`.
inline double reactive_kvar(double kw, double pf) {
  return pf > 0 ? kw * std::sqrt(1.0 - pf * pf) / pf : 0.0;
}

// Two BCD digits per byte: 42 -> 0x42.
inline std::uint32_t bcd(unsigned value) {
  std::uint32_t out = 0;
  for (unsigned shift = 0; value > 0; shift += 4, value /= 10) out |= (value % 10) << shift;
  return out;
}

}  // namespace pvtap::sim
