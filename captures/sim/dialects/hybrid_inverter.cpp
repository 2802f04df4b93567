// A simulated inverter of the Hybrid dialect (PROTOCOLS.md section 2): a battery inverter whose
// replies start with its device number and whose error reply is 0xFF.
#include <array>
#include <cmath>

#include "dialects/inverter_dialect.h"
#include "plant/plant_registers.h"
#include "pvtap/codec/function_codes.h"

namespace pvtap::sim {
namespace {

constexpr std::array kHybridBlocks{
    PollBlock{fc::kHybridDeviceInfo, 0x1060, 0x0002, true},
    PollBlock{fc::kHybridSettings, 0x1024, 0x0027, true},
    PollBlock{fc::kHybridRunningData, 0x1000, 0x0024, false},
};

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

// Every Hybrid reply starts with the 4-byte device number.
void shape_hybrid_reply(Frame& reply, const PollBlock&, DeviceNumber device) {
  reply.byte_count = static_cast<std::uint8_t>(4 + 2 * reply.words.size());
  reply.device = device;
}

Frame hybrid_error_reply(std::uint8_t station, DeviceNumber device) {
  Frame f = make_frame(Dialect::Hybrid, Role::Response, station, fc::kHybridError);
  f.byte_count = 8;
  f.device = device;
  f.start = 0x1000;
  f.count = 0x00FF;
  return f;
}

}  // namespace

extern const InverterDialect kHybridInverter{
    .dialect = Dialect::Hybrid,
    .poll_blocks = kHybridBlocks,
    .fill_registers = fill_hybrid,
    .shape_read_reply = shape_hybrid_reply,
    .error_reply = hybrid_error_reply,
    .errors_are_silence = false,
    .last_station = fc::kLastModbusStation,
};

}  // namespace pvtap::sim
