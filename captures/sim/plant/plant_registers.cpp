#include "plant/plant_registers.h"

#include <algorithm>
#include <cmath>

namespace pvtap::sim {
namespace {

std::uint32_t bit(bool on, unsigned index) {
  return on ? 1u << index : 0u;
}

// Reactive power that goes with active power `kw` at power factor `pf`.
double reactive_kvar(double kw, double pf) {
  return pf > 0 ? kw * std::sqrt(1.0 - pf * pf) / pf : 0.0;
}

// Two BCD digits per byte: 42 -> 0x42.
std::uint32_t bcd(unsigned value) {
  std::uint32_t out = 0;
  for (unsigned shift = 0; value > 0; shift += 4, value /= 10) out |= (value % 10) << shift;
  return out;
}

void fill_ascii(const PlantModel& p, RegisterImage& r) {
  const PlantState& s = p.state();
  // Table A1 solar fault bits 0..3 carry the raised alarm; A2 bit 14 says "running".
  r.set_raw("solar_fault", bit(s.alarm, s.alarm_bit));
  r.set_raw("inverter_status", bit(s.producing, 14) | bit(s.temperature_c > 60, 7));
  r.set_raw("line_fault", 0);
  r.set_value("pv_voltage", s.pv_voltage);
  r.set_value("pv_current", s.pv_voltage > 0 ? s.pv_kw * 1000 / s.pv_voltage : 0.0);
  // A single-phase inverter: phases S and T stay 0.
  const double output_kw = s.pv_kw * 0.96;
  r.set_value("line_voltage_r", s.grid_voltage);
  r.set_value("line_current_r",
              s.producing ? output_kw * 1000 / (s.grid_voltage * s.power_factor) : 0.0);
  r.set_value("line_frequency", s.grid_hz);
  r.set_value("pv_power", s.pv_kw);
  r.set_value("cumulative_energy", s.energy_total_kwh);
  r.set_value("inverter_output_power", output_kw);
  r.set_value("inverter_max_output_power", s.rated_kw);
  r.set_value("power_factor", s.power_factor * 100);
  r.set_value("energy_today", s.energy_today_kwh);
  // BCD: 1 phase, capacity in 0.1 kW (rated 4.25 kW reads "1 042" = 4.2 kW).
  r.set_raw("phase_and_capacity",
            0x1000 | bcd(static_cast<unsigned>(std::lround(s.rated_kw * 10)) % 1000));
  r.set_raw("manufacture_date", 0x2105);  // BCD YYMM: 2021-05
  r.set_raw("serial_number", p.station());
}

void fill_hybrid_settings(const PlantModel& p, RegisterImage& r) {
  const PlantState& s = p.state();
  // A 48 V battery bank of four 12 V strings, with the settings such a site would use.
  r.set_value("battery_strings", 4);
  r.set_value("battery_strings_setting", 4);
  r.set_value("battery_over_voltage", 60.0);
  r.set_value("charging_limit_voltage", 57.6);
  r.set_value("over_voltage_recovery_voltage", 58.0);
  r.set_value("boost_charging_voltage", 56.4);
  r.set_value("boost_charging_return_voltage", 52.0);
  r.set_value("float_charging_voltage", 54.0);
  r.set_value("over_discharge_voltage", 44.0);
  r.set_value("under_voltage_recovery_voltage", 48.0);
  r.set_value("battery_under_voltage", 46.0);
  r.set_value("boost_charging_time", 2);
  r.set_value("temperature_compensation_factor", 3);
  r.set_value("recharge_after_full_voltage", 52.0);
  r.set_value("output_voltage_setting", 230.0);
  r.set_value("voltage_class", 48.0);
  r.set_value("current_class", s.rated_kw * 1000 / 230.0);
  r.set_value("modbus_address", p.station());
  r.set_value("bypass_under_voltage_protection", 170.0);
  r.set_value("bypass_under_voltage_recovery", 180.0);
  r.set_value("bypass_over_voltage_protection", 270.0);
  r.set_value("bypass_over_voltage_recovery", 260.0);
  r.set_value("inverter_turn_on_voltage", 48.0);
  r.set_value("inverter_turn_off_voltage", 44.0);
  r.set_value("energy_saving_on_point", 50);
  r.set_value("energy_saving_off_point", 100);
  r.set_value("grid_charging_rated_current", 30.0);
}

void fill_hybrid(const PlantModel& p, RegisterImage& r) {
  const PlantState& s = p.state();
  const double battery_v = 51.2 + s.load() * 1.5;
  r.set_value("inverter_output_voltage", 230.0);
  r.set_value("grid_voltage", s.grid_voltage);
  r.set_value("load_voltage", 229.5);
  r.set_value("inverter_output_frequency", 50.0);
  r.set_value("inverter_output_current", s.pv_kw * 1000 / 230.0);
  r.set_value("battery_voltage", battery_v);
  r.set_value("heatsink_temperature", s.temperature_c);
  r.set_value("grid_frequency", s.grid_hz);
  r.set_raw("inverter_running_state", s.alarm ? 6 : 3);
  r.set_raw("internal_state", bit(true, 10) | bit(s.temperature_c > 40, 12));
  r.set_value("total_discharge_energy", s.energy_total_kwh);
  r.set_value("active_power", std::round(s.pv_kw * 1000));
  // The battery warms less than the heat sink, and slowly, with the charging current.
  r.set_value("battery_temperature", std::round(s.ambient_c + 3 + 5 * s.load()));
  r.set_value("rated_power", s.rated_kw * 1000);
  r.set_raw("pv_controller_fault", bit(s.alarm, s.alarm_bit));
  r.set_value("pv_panel_voltage", s.pv_voltage);
  r.set_value("pv_charging_current", s.pv_kw * 1000 / battery_v);
  r.set_value("pv_charging_power", s.pv_kw * 1000);
  r.set_raw("device_number", 0x32000000u | (1000u + p.station()));
  // On and feeding while the sun carries it; the PV charger tracks the maximum power point.
  r.set_raw("inverter_on_off_state", s.producing ? 1 : 0);
  r.set_raw("pv_controller_on_off_state", s.producing ? 1 : 0);
  r.set_raw("pv_charging_state", s.producing ? 1 : 0);
  r.set_raw("pv_controller_fan", s.temperature_c > 40 ? 1 : 0);
  r.set_raw("inverter_on_off", 1);
  r.set_raw("pv_charging_on_off", 1);
  fill_hybrid_settings(p, r);
}

void fill_gsl_times(const PlantState& s, RegisterImage& r) {
  const CivilTime up = civil_time(s.last_startup);
  const CivilTime down = civil_time(s.last_shutdown);
  const std::pair<const char*, int> fields[] = {
      {"last_startup_year", up.year},        {"last_startup_month", up.month},
      {"last_startup_day", up.day},          {"last_startup_hour", up.hour},
      {"last_startup_minute", up.minute},    {"last_startup_second", up.second},
      {"last_shutdown_year", down.year},     {"last_shutdown_month", down.month},
      {"last_shutdown_day", down.day},       {"last_shutdown_hour", down.hour},
      {"last_shutdown_minute", down.minute}, {"last_shutdown_second", down.second}};
  for (const auto& [key, value] : fields) r.set_value(key, value);
  r.set_value("grid_connected_time_today", s.connected_today_h);
}

void fill_gsl(const PlantModel& p, RegisterImage& r) {
  const PlantState& s = p.state();
  r.set_text("model_name", "GSL000500K");
  r.set_text("manufacturer_name", "KSTARSOLAR");
  r.set_raw("alarm_word_1", bit(s.alarm, s.alarm_bit));
  r.set_raw("status_word", bit(s.producing, 5) | bit(s.producing, 11) | bit(s.alarm, 15));
  const double efficiency = s.producing ? 0.94 + 0.03 * std::sqrt(s.load()) : 0.0;
  const double output_kw = s.pv_kw * efficiency;
  const double phase_kw = output_kw / 3;
  const double pf = s.power_factor;
  for (const char* key : {"grid_voltage_ab", "grid_voltage_bc", "grid_voltage_ca"})
    r.set_value(key, s.grid_voltage * 1.732);
  for (const char* key : {"output_current_a", "output_current_b", "output_current_c"})
    r.set_value(key, pf > 0 ? phase_kw * 1000 / (s.grid_voltage * pf) : 0.0);
  r.set_value("grid_frequency", s.grid_hz);
  for (const char* key : {"power_factor_a", "power_factor_b", "power_factor_c"})
    r.set_value(key, pf);
  for (const char* key : {"active_power_a", "active_power_b", "active_power_c"})
    r.set_value(key, phase_kw);
  for (const char* key : {"reactive_power_a", "reactive_power_b", "reactive_power_c"})
    r.set_value(key, reactive_kvar(phase_kw, pf));
  r.set_value("pv_voltage", s.pv_voltage);
  r.set_value("pv_current", s.pv_voltage > 0 ? s.pv_kw * 1000 / s.pv_voltage : 0.0);
  r.set_value("pv_input_power", s.pv_kw);
  r.set_value("energy_today", s.energy_today_kwh);
  r.set_value("inverter_efficiency", efficiency * 100);
  r.set_value("energy_this_year", s.energy_year_kwh);
  r.set_value("inverter_temperature", s.temperature_c);
  fill_gsl_times(s, r);
  r.set_value("total_energy", s.energy_total_kwh);
  r.set_value("total_active_power", output_kw);
  r.set_value("total_reactive_power", reactive_kvar(output_kw, pf));
  r.set_value("output_power_limit", 52.5);
  r.set_value("power_factor_setting", 1.0);
  r.set_value("total_power_factor", pf);
  // The grid's CO2 avoided per kWh, as inverters of this kind count it (0.475 kg/kWh).
  r.set_value("total_co2_reduction", s.energy_total_kwh * 0.475);
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
    case Dialect::Modbus:
      return;  // plain Modbus devices fill their own registers
  }
}

}  // namespace pvtap::sim
