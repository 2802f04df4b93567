// PlantModel: the physics of one simulated PV inverter — power that follows a daylight curve
// and passing clouds, an inverter that starts up in the morning and shuts down at dusk (or
// when an alarm trips it), energy counters for the day, the year and the plant's life that
// agree with that curve, temperatures that follow the load and the time of day, and a power
// factor near 1 while it feeds the grid.
#pragma once

#include <cstdint>

#include "bus/bus_event.h"
#include "sim_random.h"

namespace pvtap::sim {

// CivilTime: a UTC moment as an inverter's clock registers show it.
struct CivilTime {
  int year = 1970, month = 1, day = 1, hour = 0, minute = 0, second = 0;
};
CivilTime civil_time(Micros time);

struct PlantState {
  double rated_kw = 5.0;
  double pv_kw = 0.0;
  double pv_voltage = 0.0;
  double grid_voltage = 230.0;
  double grid_hz = 50.0;
  double ambient_c = 20.0;
  double temperature_c = 25.0;     // heat sink: ambient plus what the load adds
  double power_factor = 0.0;       // cos phi of the output; 0 while not feeding the grid
  double energy_total_kwh = 0.0;   // never decreases
  double energy_year_kwh = 0.0;    // since 1 January (UTC), so at most the total
  double energy_today_kwh = 0.0;   // since midnight (UTC), so at most the year's
  double connected_today_h = 0.0;  // hours fed into the grid today
  bool producing = false;          // the inverter is connected and feeding
  Micros last_startup = 0;
  Micros last_shutdown = 0;
  std::uint16_t alarm_bit = 0;  // index of the raised alarm bit while one is raised
  bool alarm = false;

  double load() const { return rated_kw > 0 ? pv_kw / rated_kw : 0.0; }
};

class PlantModel {
 public:
  PlantModel(std::uint8_t station, std::uint64_t seed, Micros start);
  // Moves the plant forward to `now` (never backwards).
  void advance(Micros now);
  const PlantState& state() const { return state_; }
  std::uint8_t station() const { return station_; }

 private:
  void set_history(Micros start);
  void drift_weather(double seconds);
  void step_alarm(double seconds);
  void switch_state(bool producing);
  void add_energy(double kwh, double seconds);

  std::uint8_t station_;
  SimRandom random_;
  Micros now_;
  double cloud_ = 0.9;  // fraction of clear-sky power reaching the panels
  double alarm_left_s_ = 0.0;
  PlantState state_;
};

// Fraction of peak sun at a time of day (UTC used as solar time): 0 at night, 1 at noon.
double daylight(Micros time);
// The sun above which an inverter connects (below, its input cannot carry the grid).
inline constexpr double kStartSun = 0.03;
// Energy of one day of the daylight curve at a mean cloud cover, in hours at rated power.
double daily_full_load_hours(double mean_cloud);

}  // namespace pvtap::sim
