#!/usr/bin/env python3
"""Checks that the simulator's plants behave like plants, from a ground truth it wrote:
energy counters never fall (the runs do not cross midnight, when the day's counters restart),
PV power is zero at night and follows the daylight curve by day, temperatures drift without
jumping and are higher under the midday load than at night, alarm bits both set and clear,
the power factor is near 1 whenever the plant feeds the grid, the energy counters agree with
the power curve (the day's energy with the curve since sunrise, its growth with the power
over the run, total >= this year >= today), and the last start-up was this morning.

usage: check_plant_values.py TRUTH_DAY TRUTH_NIGHT
"""
import json
import math
import sys
from datetime import datetime, timezone

ENERGY = {"total_energy", "energy_today", "cumulative_energy", "total_discharge_energy"}
POWER = {"pv_input_power", "pv_power", "pv_charging_power"}
TEMPERATURE = {"inverter_temperature", "heatsink_temperature"}
ALARM = {"alarm_word_1", "solar_fault", "pv_controller_fault"}


def series(truth):
    """(station, key) -> [(ts, raw, value)] over the good replies, in time order."""
    out = {}
    for e in truth["events"]:
        if e["type"] != "frame" or e["role"] != "response" or e["check"] != "ok":
            continue
        for v in e.get("values", []):
            out.setdefault((e["station"], v["key"]), []).append((e["ts"], v["raw"],
                                                                 v.get("value")))
    return out


def check_day(truth, failures):
    s = series(truth)
    for (station, key), points in s.items():
        values = [p[2] for p in points]
        if key in ENERGY and any(b < a for a, b in zip(values, values[1:])):
            failures.append(f"station {station}: {key} fell: {values}")
        if key in TEMPERATURE and any(abs(b - a) > 3.0 for a, b in zip(values, values[1:])):
            failures.append(f"station {station}: {key} jumps: {values}")
    if not any(k in POWER and max(p[2] for p in pts) > 0 for (st, k), pts in s.items()):
        failures.append("no plant produced PV power by day")
    alarms = [p[1] for (st, k), pts in s.items() if k in ALARM for p in pts]
    if not any(alarms) or all(alarms):
        failures.append("alarm bits never both set and clear")


def check_night(truth, failures):
    for (station, key), points in series(truth).items():
        if key in POWER and any(p[2] != 0 for p in points):
            failures.append(f"station {station}: {key} is not zero at night")
        if key in POWER_FACTOR and any(p[2] != 0 for p in points):
            failures.append(f"station {station}: {key} is not 0 while nothing is fed")


POWER_FACTOR = {"power_factor_a", "power_factor_b", "power_factor_c", "total_power_factor",
                "power_factor"}


def replies(truth):
    """{key: value} of every good reply, with its station and time."""
    for e in truth["events"]:
        if e["type"] != "frame" or e["role"] != "response" or e["check"] != "ok":
            continue
        values = {v["key"]: v.get("value") for v in e.get("values", [])}
        yield e["station"], e["ts"], values


def check_power_factor(truth, failures):
    fed = 0
    for station, ts, v in replies(truth):
        power = v.get("pv_input_power", v.get("pv_power"))
        for key in POWER_FACTOR & v.keys():
            pf = v[key] / (100 if key == "power_factor" else 1)
            if power and power > 0:
                fed += 1
                if not 0.95 <= pf <= 1.0:
                    failures.append(f"station {station} at {ts}: {key} {pf} at {power} kW")
    if fed == 0:
        failures.append("no power factor read while a plant produced")


def sun_hours_until(hour):
    """Hours at rated power of the clear-sky daylight curve from 06:00 to `hour`."""
    h = min(max(hour, 6.0), 20.0)
    return 14 / math.pi * (1 - math.cos(math.pi * (h - 6) / 14))


def check_energy(truth, failures):
    first = {}
    power = {}
    for station, ts, v in replies(truth):
        hour = (ts % 86400) / 3600
        if {"energy_today", "energy_this_year", "total_energy"} <= v.keys():
            if not v["total_energy"] >= v["energy_this_year"] >= v["energy_today"] - 100:
                failures.append(f"station {station}: total {v['total_energy']} >= year "
                                f"{v['energy_this_year']} >= today {v['energy_today']} fails")
        if {"energy_today", "inverter_max_output_power"} <= v.keys():
            curve = v["inverter_max_output_power"] * sun_hours_until(hour)
            if not 0.3 * curve - 0.1 <= v["energy_today"] <= curve + 0.1:
                failures.append(f"station {station} at {hour:.2f} h: energy today "
                                f"{v['energy_today']} kWh does not fit the curve ({curve:.1f})")
        if "cumulative_energy" in v and "pv_power" in v:
            first.setdefault(station, (ts, v["cumulative_energy"]))
            power.setdefault(station, []).append((ts, v["pv_power"], v["cumulative_energy"]))
    for station, points in power.items():
        produced = sum((b[0] - a[0]) * (a[1] + b[1]) / 2 for a, b in zip(points, points[1:]))
        grown = points[-1][2] - points[0][2]
        if abs(grown - produced / 3600) > 0.15 * produced / 3600 + 0.01:
            failures.append(f"station {station}: energy grew {grown:.3f} kWh, the power curve "
                            f"gives {produced / 3600:.3f} kWh")
    if not power:
        failures.append("no ASCII plant to compare energy with power")


def check_start_stop(truth, failures):
    seen = 0
    for station, ts, v in replies(truth):
        if "last_startup_hour" not in v:
            continue
        seen += 1
        try:
            up, down = start_stop_times(v)
        except ValueError as error:
            failures.append(f"station {station} at {ts}: start-up/shut-down time: {error}")
            continue
        morning = ts - ts % 86400 + 6 * 3600
        if not morning <= up <= ts or not ts - 86400 <= down <= ts:
            failures.append(f"station {station} at {ts}: start-up {up}, shut-down {down}")
    if seen == 0:
        failures.append("no start-up time read")


def start_stop_times(v):
    """The last start-up and shut-down as epoch seconds (ValueError for an impossible date)."""
    up = datetime(int(v["last_startup_year"]), int(v["last_startup_month"]),
                  int(v["last_startup_day"]), int(v["last_startup_hour"]),
                  int(v["last_startup_minute"]), int(v["last_startup_second"]),
                  tzinfo=timezone.utc).timestamp()
    down = datetime(int(v["last_shutdown_year"]), int(v["last_shutdown_month"]),
                    int(v["last_shutdown_day"]), int(v["last_shutdown_hour"]),
                    int(v["last_shutdown_minute"]), int(v["last_shutdown_second"]),
                    tzinfo=timezone.utc).timestamp()
    return up, down


def mean_temperature(truth):
    values = [p[2] for (st, k), pts in series(truth).items() if k in TEMPERATURE for p in pts]
    return sum(values) / len(values) if values else None


def main():
    failures = []
    with open(sys.argv[1], encoding="utf-8") as f:
        day = json.load(f)
    with open(sys.argv[2], encoding="utf-8") as f:
        night = json.load(f)
    check_day(day, failures)
    check_night(night, failures)
    check_power_factor(day, failures)
    check_energy(day, failures)
    check_start_stop(day, failures)
    warm, cool = mean_temperature(day), mean_temperature(night)
    if warm is None or cool is None or warm < cool + 5:
        failures.append(f"temperatures do not follow the load: {warm} by day, {cool} at night")
    for text in failures:
        print(text)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
