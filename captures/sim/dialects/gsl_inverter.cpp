// A simulated inverter of the GSL dialect (PROTOCOLS.md section 3): a three-phase KSTAR
// inverter on Modbus RTU, answering with exceptions when it cannot.
#include <array>
#include <cmath>
#include <utility>

#include "dialects/inverter_dialect.h"
#include "plant/plant_registers.h"
#include "pvtap/codec/function_codes.h"

namespace pvtap::sim {
namespace {

// GSL IDs 1000.. (names), 1030.. (alarm and status words), 1050..1095 (measurements).
constexpr std::array kGslBlocks{
    PollBlock{fc::kGslReadHolding, 1000, 10, true},
    PollBlock{fc::kGslReadHolding, 1030, 4, false},
    PollBlock{fc::kGslReadHolding, 1050, 46, false},
};

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

void shape_gsl_reply(Frame& reply, const PollBlock&, DeviceNumber) {
  reply.byte_count = static_cast<std::uint8_t>(2 * reply.words.size());
}

}  // namespace

extern const InverterDialect kGslInverter{
    .dialect = Dialect::Gsl,
    .poll_blocks = kGslBlocks,
    .fill_registers = fill_gsl,
    .shape_read_reply = shape_gsl_reply,
    .error_reply = nullptr,
    .errors_are_silence = false,
    .last_station = fc::kLastModbusStation,
};

}  // namespace pvtap::sim
