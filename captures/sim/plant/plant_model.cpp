#include "plant/plant_model.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>

namespace pvtap::sim {
namespace {

constexpr Micros kDay = 86'400'000'000;
constexpr Micros kHour = 3'600'000'000;
constexpr double kSunrise = 6.0, kSunset = 20.0;
// The cloud cover a plant's history is estimated with (its yield so far this year and before).
constexpr double kMeanCloud = 0.8;

double hour_of_day(Micros time) {
  return static_cast<double>(time % kDay) / static_cast<double>(kHour);
}

// Hours at rated power the daylight curve gives from sunrise to `hour` (clear sky).
double sun_hours_until(double hour) {
  const double h = std::clamp(hour, kSunrise, kSunset);
  constexpr double kLength = kSunset - kSunrise;
  return kLength / std::numbers::pi * (1.0 - std::cos(std::numbers::pi * (h - kSunrise) / kLength));
}

// When the sun crosses kStartSun in the morning and in the evening (hours of the day).
double startup_hour() {
  return kSunrise + (kSunset - kSunrise) / std::numbers::pi * std::asin(kStartSun);
}
double shutdown_hour() {
  return kSunset - (startup_hour() - kSunrise);
}

Micros at_hour(Micros day_start, double hour) {
  return day_start + static_cast<Micros>(hour * static_cast<double>(kHour));
}

int day_of_year(Micros time) {
  using namespace std::chrono;
  const sys_days day = floor<days>(sys_time<microseconds>(microseconds(time)));
  const year_month_day ymd(day);
  return static_cast<int>((day - sys_days(ymd.year() / January / 1)).count());
}

// Air temperature over the day: coolest before sunrise, warmest in the afternoon.
double ambient_at(Micros time) {
  return 16.0 + 12.0 * daylight(time - 2 * kHour);
}

}  // namespace

CivilTime civil_time(Micros time) {
  using namespace std::chrono;
  const sys_time<microseconds> t{microseconds(time)};
  const sys_days day = floor<days>(t);
  const year_month_day ymd(day);
  const hh_mm_ss hms(floor<seconds>(t - day));
  return {static_cast<int>(ymd.year()),
          static_cast<int>(static_cast<unsigned>(ymd.month())),
          static_cast<int>(static_cast<unsigned>(ymd.day())),
          static_cast<int>(hms.hours().count()),
          static_cast<int>(hms.minutes().count()),
          static_cast<int>(hms.seconds().count())};
}

double daylight(Micros time) {
  const double hour = hour_of_day(time);
  if (hour <= kSunrise || hour >= kSunset) return 0.0;
  return std::sin(std::numbers::pi * (hour - kSunrise) / (kSunset - kSunrise));
}

double daily_full_load_hours(double mean_cloud) {
  return mean_cloud * (sun_hours_until(shutdown_hour()) - sun_hours_until(startup_hour()));
}

PlantModel::PlantModel(std::uint8_t station, std::uint64_t seed, Micros start)
    : station_(station), random_(seed ^ (0x5157ull * station)), now_(start) {
  // Plants of one site differ in size and history; the seed decides how.
  state_.rated_kw = 3.0 + static_cast<double>(random_.between(0, 20)) * 0.25;
  cloud_ = 0.75 + random_.unit() * 0.25;
  set_history(start);
  advance(start);
  state_.temperature_c = state_.ambient_c + 25.0 * state_.load();
}

// What the counters and the start/stop times hold when the capture begins: the same daylight
// curve run backwards (this morning at today's clouds, earlier days at kMeanCloud).
void PlantModel::set_history(Micros start) {
  const Micros today = start - start % kDay;
  const double hour = hour_of_day(start);
  const double up = startup_hour(), down = shutdown_hour();
  const double produced_hours = sun_hours_until(std::min(hour, down)) - sun_hours_until(up);
  state_.energy_today_kwh = state_.rated_kw * cloud_ * std::max(0.0, produced_hours);
  state_.connected_today_h = std::clamp(hour, up, down) - up;
  const double daily_kwh = state_.rated_kw * daily_full_load_hours(kMeanCloud);
  state_.energy_year_kwh = day_of_year(start) * daily_kwh + state_.energy_today_kwh;
  const double years_before = static_cast<double>(random_.between(1, 6));
  state_.energy_total_kwh = years_before * 365.0 * daily_kwh + state_.energy_year_kwh;
  // A few seconds apart from plant to plant: each inverter measures its own input.
  const auto jitter = static_cast<Micros>(random_.between(0, 90)) * 1'000'000;
  state_.last_startup = at_hour(hour >= up ? today : today - kDay, up) + jitter;
  state_.last_shutdown = at_hour(hour >= down ? today : today - kDay, down) + jitter;
  state_.producing = hour >= up && hour < down;
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

// An alarm trips the inverter off the grid like dusk does; it reconnects when both clear.
void PlantModel::switch_state(bool producing) {
  if (producing == state_.producing) return;
  state_.producing = producing;
  (producing ? state_.last_startup : state_.last_shutdown) = now_;
}

void PlantModel::add_energy(double kwh, double seconds) {
  state_.energy_total_kwh += kwh;
  state_.energy_year_kwh += kwh;
  state_.energy_today_kwh += kwh;
  if (state_.producing) state_.connected_today_h += seconds / 3600.0;
}

void PlantModel::advance(Micros now) {
  const double seconds = static_cast<double>(std::max<Micros>(0, now - now_)) / 1e6;
  const Micros before = now_;
  now_ = std::max(now_, now);
  if (now_ / kDay != before / kDay) {  // midnight: the day's counters start again
    state_.energy_today_kwh = 0;
    state_.connected_today_h = 0;
    if (civil_time(now_).year != civil_time(before).year) state_.energy_year_kwh = 0;
  }
  drift_weather(seconds);
  step_alarm(seconds);
  const double sun = daylight(now_);
  switch_state(sun > kStartSun && !state_.alarm);
  state_.pv_kw = state_.producing ? state_.rated_kw * sun * cloud_ : 0.0;
  state_.pv_voltage = sun > 0 ? 300.0 + 80.0 * sun + (random_.unit() - 0.5) * 4.0 : 0.0;
  add_energy(state_.pv_kw * seconds / 3600.0, seconds);
  // cos phi: close to 1 under load, a little lower at low load (the filter's reactive share).
  state_.power_factor = state_.producing
                            ? std::min(0.999, 0.975 + 0.022 * std::sqrt(state_.load()) +
                                                  (random_.unit() - 0.5) * 0.002)
                            : 0.0;
  // The heat sink warms towards air temperature plus what the load dissipates, slowly.
  state_.ambient_c = ambient_at(now_);
  const double target = state_.ambient_c + 25.0 * state_.load();
  state_.temperature_c += (target - state_.temperature_c) * std::min(1.0, seconds / 600.0);
  state_.temperature_c += (random_.unit() - 0.5) * 0.2;
}

}  // namespace pvtap::sim
