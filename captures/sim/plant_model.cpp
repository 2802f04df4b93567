#include "plant_model.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace pvtap::sim {

double daylight(Micros time) {
  const double hour = static_cast<double>(time % 86'400'000'000) / 3.6e9;
  constexpr double kSunrise = 6.0, kSunset = 20.0;
  if (hour <= kSunrise || hour >= kSunset) return 0.0;
  return std::sin(std::numbers::pi * (hour - kSunrise) / (kSunset - kSunrise));
}

PlantModel::PlantModel(std::uint8_t station, std::uint64_t seed, Micros start)
    : station_(station), random_(seed ^ (0x5157ull * station)), now_(start) {
  // Plants of one site differ in size and history; the seed decides how.
  state_.rated_kw = 3.0 + static_cast<double>(random_.between(0, 20)) * 0.25;
  state_.energy_total_kwh = 1000.0 + static_cast<double>(random_.between(0, 40000));
  state_.energy_today_kwh = static_cast<double>(random_.between(0, 80)) * 0.1;
  state_.temperature_c = 30.0 + random_.unit() * 5.0;
  cloud_ = 0.75 + random_.unit() * 0.25;
  advance(start);
}

void PlantModel::drift_weather(double seconds) {
  // Clouds wander as a bounded random walk, a few percent per poll.
  cloud_ += (random_.unit() - 0.5) * 0.08 * std::min(seconds, 10.0);
  cloud_ = std::clamp(cloud_, 0.35, 1.0);
  state_.grid_voltage = 230.0 + (random_.unit() - 0.5) * 6.0;
  state_.grid_hz = 50.0 + (random_.unit() - 0.5) * 0.08;
}

void PlantModel::step_alarm(double seconds) {
  if (state_.alarm) {
    alarm_left_s_ -= seconds;
    if (alarm_left_s_ <= 0) state_.alarm = false;
    return;
  }
  if (random_.percent(4)) {
    state_.alarm = true;
    state_.alarm_bit = static_cast<std::uint16_t>(random_.between(0, 3));
    alarm_left_s_ = 15.0 + random_.unit() * 30.0;
  }
}

void PlantModel::advance(Micros now) {
  const double seconds = static_cast<double>(std::max<Micros>(0, now - now_)) / 1e6;
  now_ = std::max(now_, now);
  drift_weather(seconds);
  step_alarm(seconds);
  const double sun = daylight(now_);
  state_.pv_kw = state_.alarm ? 0.0 : state_.rated_kw * sun * cloud_;
  state_.pv_voltage = sun > 0 ? 300.0 + 80.0 * sun + (random_.unit() - 0.5) * 4.0 : 0.0;
  const double kwh = state_.pv_kw * seconds / 3600.0;
  state_.energy_total_kwh += kwh;
  state_.energy_today_kwh += kwh;
  // The heat sink warms towards a load-dependent level, slowly.
  const double target = 28.0 + 4.0 * state_.pv_kw;
  state_.temperature_c += (target - state_.temperature_c) * std::min(1.0, seconds / 600.0);
  state_.temperature_c += (random_.unit() - 0.5) * 0.2;
}

}  // namespace pvtap::sim
