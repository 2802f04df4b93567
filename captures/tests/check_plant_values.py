#!/usr/bin/env python3
"""Checks that the simulator's plants behave like plants, from a ground truth it wrote:
energy counters never fall, PV power is zero at night and follows the daylight curve by
day, temperatures drift without jumping, and alarm bits both set and clear.

usage: check_plant_values.py TRUTH_DAY TRUTH_NIGHT
"""
import json
import sys

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


def main():
    failures = []
    with open(sys.argv[1], encoding="utf-8") as f:
        check_day(json.load(f), failures)
    with open(sys.argv[2], encoding="utf-8") as f:
        check_night(json.load(f), failures)
    for text in failures:
        print(text)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
