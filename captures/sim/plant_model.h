// PlantModel: the physics of one simulated PV inverter — power that follows a daylight curve
// and passing clouds, energy counters that only grow, a temperature that drifts with load,
// and alarms that set and clear.
#pragma once

#include <cstdint>

#include "bus_event.h"
#include "sim_random.h"

namespace pvtap::sim {

struct PlantState {
  double rated_kw = 5.0;
  double pv_kw = 0.0;
  double pv_voltage = 0.0;
  double grid_voltage = 230.0;
  double grid_hz = 50.0;
  double temperature_c = 25.0;
  double energy_total_kwh = 0.0;  // never decreases
  double energy_today_kwh = 0.0;  // never decreases within the run
  std::uint16_t alarm_bit = 0;    // index of the raised alarm bit while one is raised
  bool alarm = false;
};

class PlantModel {
 public:
  PlantModel(std::uint8_t station, std::uint64_t seed, Micros start);
  // Moves the plant forward to `now` (never backwards).
  void advance(Micros now);
  const PlantState& state() const { return state_; }
  std::uint8_t station() const { return station_; }

 private:
  void drift_weather(double seconds);
  void step_alarm(double seconds);

  std::uint8_t station_;
  SimRandom random_;
  Micros now_;
  double cloud_ = 0.9;  // fraction of clear-sky power reaching the panels
  double alarm_left_s_ = 0.0;
  PlantState state_;
};

// Fraction of peak sun at a time of day (UTC used as solar time): 0 at night, 1 at noon.
double daylight(Micros time);

}  // namespace pvtap::sim
