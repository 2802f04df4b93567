// A simulated inverter of the ASCII dialect (PROTOCOLS.md section 1): single phase, read by
// its start address, silent when it cannot answer.
#include <array>
#include <cmath>

#include "dialects/inverter_dialect.h"
#include "plant/plant_registers.h"
#include "pvtap/codec/function_codes.h"

namespace pvtap::sim {
namespace {

constexpr std::array kAsciiBlocks{
    PollBlock{fc::kAsciiRead, 0x01E0, 3, true},  PollBlock{fc::kAsciiRead, 0x0004, 4, false},
    PollBlock{fc::kAsciiRead, 0x0020, 2, false}, PollBlock{fc::kAsciiRead, 0x0050, 7, false},
    PollBlock{fc::kAsciiRead, 0x0060, 8, false},
};

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

// A reply repeats its request's start address.
void shape_ascii_reply(Frame& reply, const PollBlock& block, DeviceNumber) {
  reply.start = block.start;
}

}  // namespace

extern const InverterDialect kAsciiInverter{
    .dialect = Dialect::Ascii,
    .poll_blocks = kAsciiBlocks,
    .fill_registers = fill_ascii,
    .shape_read_reply = shape_ascii_reply,
    .error_reply = nullptr,
    .errors_are_silence = true,
    .last_station = 0x1F,  // the station field holds 0x00-0x1F
};

}  // namespace pvtap::sim
