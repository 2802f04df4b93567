#include "plant_registers.h"

#include <algorithm>
#include <cmath>

namespace pvtap::sim {
namespace {

std::uint32_t bit(bool on, unsigned index) {
  return on ? 1u << index : 0u;
}

void fill_ascii(const PlantModel& p, RegisterImage& r) {
  const PlantState& s = p.state();
  // Table A1 solar fault bits 0..3 carry the raised alarm; A2 bit 14 says "running".
  r.set_raw("solar_fault", bit(s.alarm, s.alarm_bit));
  r.set_raw("inverter_status", bit(s.pv_kw > 0, 14) | bit(s.temperature_c > 60, 7));
  r.set_raw("line_fault", 0);
  r.set_value("pv_voltage", s.pv_voltage);
  r.set_value("pv_current", s.pv_voltage > 0 ? s.pv_kw * 1000 / s.pv_voltage : 0.0);
  r.set_value("line_voltage_r", s.grid_voltage);
  r.set_value("line_current_r", s.pv_kw * 0.96 * 1000 / s.grid_voltage);
  r.set_value("line_frequency", s.grid_hz);
  r.set_value("pv_power", s.pv_kw);
  r.set_value("cumulative_energy", s.energy_total_kwh);
  r.set_value("inverter_output_power", s.pv_kw * 0.96);
  r.set_value("inverter_max_output_power", s.rated_kw);
  r.set_value("power_factor", 99.8);
  r.set_value("energy_today", s.energy_today_kwh);
  r.set_raw("phase_and_capacity", 0x1030);  // BCD: single phase, 3.0 kW
  r.set_raw("manufacture_date", 0x2105);    // BCD YYMM: 2021-05
  r.set_raw("serial_number", p.station());
}

void fill_hybrid(const PlantModel& p, RegisterImage& r) {
  const PlantState& s = p.state();
  r.set_value("inverter_output_voltage", 230.0);
  r.set_value("grid_voltage", s.grid_voltage);
  r.set_value("load_voltage", 229.5);
  r.set_value("inverter_output_frequency", 50.0);
  r.set_value("inverter_output_current", s.pv_kw * 1000 / 230.0);
  r.set_value("battery_voltage", 51.2 + s.pv_kw * 0.3);
  r.set_value("heatsink_temperature", s.temperature_c);
  r.set_value("grid_frequency", s.grid_hz);
  r.set_raw("inverter_running_state", s.alarm ? 6 : 3);
  r.set_raw("internal_state", bit(true, 10) | bit(s.temperature_c > 40, 12));
  r.set_value("total_discharge_energy", s.energy_total_kwh);
  r.set_value("active_power", std::round(s.pv_kw * 1000));
  r.set_value("battery_temperature", std::round(s.temperature_c - 5));
  r.set_value("rated_power", s.rated_kw * 1000);
  r.set_raw("pv_controller_fault", bit(s.alarm, s.alarm_bit));
  r.set_value("pv_panel_voltage", s.pv_voltage);
  r.set_value("pv_charging_power", s.pv_kw * 1000);
  r.set_raw("device_number", 0x32000000u | (1000u + p.station()));
  r.set_value("battery_over_voltage", 60.0);
  r.set_value("float_charging_voltage", 54.0);
  r.set_value("over_discharge_voltage", 44.0);
}

void fill_gsl(const PlantModel& p, RegisterImage& r) {
  const PlantState& s = p.state();
  r.set_text("model_name", "GSL000500K");
  r.set_text("manufacturer_name", "KSTARSOLAR");
  r.set_raw("alarm_word_1", bit(s.alarm, s.alarm_bit));
  r.set_raw("status_word", bit(s.pv_kw > 0, 5) | bit(s.pv_kw > 0, 11) | bit(s.alarm, 15));
  const double phase_kw = s.pv_kw * 0.97 / 3;
  for (const char* key : {"grid_voltage_ab", "grid_voltage_bc", "grid_voltage_ca"})
    r.set_value(key, s.grid_voltage * 1.732);
  for (const char* key : {"output_current_a", "output_current_b", "output_current_c"})
    r.set_value(key, phase_kw * 1000 / s.grid_voltage);
  r.set_value("grid_frequency", s.grid_hz);
  for (const char* key : {"active_power_a", "active_power_b", "active_power_c"})
    r.set_value(key, phase_kw);
  r.set_value("pv_voltage", s.pv_voltage);
  r.set_value("pv_current", s.pv_voltage > 0 ? s.pv_kw * 1000 / s.pv_voltage : 0.0);
  r.set_value("pv_input_power", s.pv_kw);
  r.set_value("energy_today", s.energy_today_kwh);
  r.set_value("inverter_efficiency", s.pv_kw > 0 ? 97.0 : 0.0);
  r.set_value("inverter_temperature", s.temperature_c);
  r.set_value("total_energy", s.energy_total_kwh);
  r.set_value("total_active_power", s.pv_kw * 0.97);
  r.set_value("output_power_limit", 52.5);
}

}  // namespace

void fill_registers(const PlantModel& plant, RegisterImage& image, Dialect dialect) {
  switch (dialect) {
    case Dialect::Ascii:
      return fill_ascii(plant, image);
    case Dialect::Hybrid:
      return fill_hybrid(plant, image);
    case Dialect::Gsl:
      return fill_gsl(plant, image);
  }
}

}  // namespace pvtap::sim
