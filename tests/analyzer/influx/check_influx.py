#!/usr/bin/python3
"""`pvtap audit --values FILE --values-format influx` through a real InfluxDB
(influx_server.py): the line protocol of simulated buses is written over HTTP (/write,
precision ns), read back with /query (epoch ns), and every point, its tags, field and time,
is judged against pvtap's jsonl --values of the same captures.

The buses: a Modbus gateway capture (an epoch start with microseconds) of GSL and hybrid
inverters and an energy meter decoded with a map whose register names hold spaces, commas
and '=', and a logic-analyzer recording whose channels, and so bus tags, are named with
spaces, commas, '=' and a backslash.

usage: check_influx.py --pvtap PVTAP --sim PVTAP_SIM --scratch DIR
"""
import argparse
import json
import os
import re
import shutil
import subprocess
import sys
import zipfile
from decimal import Decimal

from influx_server import InfluxServer

RUN_GUARD_S = 120
DB = "plant"
TAGS = ("bus", "dialect", "key", "station")
# Names with every character the line protocol escapes in a tag value, and a backslash,
# which it must keep as it is.
CHANNELS = {b"A-B": b"inverter bus, A=B", b"TX": b"master\\\\TX", b"RX": b"master RX"}
METER_MAP = """dialect = "modbus"
title = "meter, with names = awkward"

[[register]]
address = 0x0000
key = "phase1_voltage"
name = "phase 1, L1=N voltage"
kind = "float32"
unit = "V"
decimals = 1

[[register]]
address = 0x001E
key = "phase1_power_factor"
name = "power factor, cos phi = P/S"
kind = "float32"
decimals = 2

[[register]]
address = 0x0046
key = "frequency"
name = "supply frequency f = 1/T"
kind = "float32"
unit = "Hz"
decimals = 2
"""


def run(args):
    r = subprocess.run(args, capture_output=True, text=True, timeout=RUN_GUARD_S)
    if r.returncode != 0:
        sys.exit(f"FAIL: {' '.join(args)} exited {r.returncode}: {r.stderr}")


def rename_channels(src, dst):
    """The sigrok session `src` with its channels renamed after CHANNELS."""
    with zipfile.ZipFile(src) as zin, zipfile.ZipFile(dst, "w", zipfile.ZIP_DEFLATED) as zout:
        for item in zin.infolist():
            data = zin.read(item.filename)
            if item.filename == "metadata":
                for old, new in CHANNELS.items():
                    data = data.replace(b"=" + old + b"\n", b"=" + new + b"\n")
            zout.writestr(item, data)


def make_inputs(args):
    """[(capture, extra pvtap options)]"""
    gateway = os.path.join(args.scratch, "gateway.pcap")
    run([args.sim, "--seed", "38", "--dialect", "gsl,hybrid", "--inverters", "2",
         "--meter", "10", "--duration", "6", "--start", "1767225600.123457",
         "--faults", "none", "--gateway", gateway])
    meter_map = os.path.join(args.scratch, "meter map.toml")
    with open(meter_map, "w") as f:
        f.write(METER_MAP)
    plain = os.path.join(args.scratch, "logic-plain.sr")
    named = os.path.join(args.scratch, "logic.sr")
    run([args.sim, "--seed", "11", "--dialect", "gsl", "--inverters", "1", "--duration", "4",
         "--sr", plain, "--sr-channels", "bus,tx,rx"])
    rename_channels(plain, named)
    return [(gateway, ["--map", f"10={meter_map}"]), (named, [])]


def expected_points(path):
    """The points the line protocol must hold, from pvtap's jsonl rows: numeric values of
    registers with a key, (tags, time in ns, value); ts read as written, digit for digit."""
    out = []
    with open(path) as f:
        for line in f:
            row = json.loads(line, parse_float=Decimal)
            if row["key"] is None or isinstance(row["value"], str) or row["value"] is None:
                continue
            tags = (row["bus"], row["dialect"], row["key"], str(row["station"]))
            out.append((tags, int(row["ts"] * 10**9), float(row["value"])))
    return out


def leading_zero_times(path):
    """The lines whose time is not an integer as one writes it (no leading zero)."""
    with open(path) as f:
        return [line for line in f if not re.search(r" (?:-?[1-9][0-9]*|0)$", line.rstrip("\n"))]


def stored_points(server):
    series = server.query(DB, "SELECT * FROM pvtap")
    if not series:
        return []
    (only,) = series
    columns = only["columns"]
    if sorted(columns) != sorted(("time", "value") + TAGS):
        sys.exit(f"FAIL: stored columns {columns}")
    out = []
    for values in only["values"]:
        row = dict(zip(columns, values))
        out.append((tuple(row[t] for t in TAGS), row["time"], float(row["value"])))
    return out


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--pvtap", required=True)
    parser.add_argument("--sim", required=True)
    parser.add_argument("--scratch", required=True)
    args = parser.parse_args()
    os.makedirs(args.scratch, exist_ok=True)
    if shutil.which("influxd") is None:
        sys.exit("FAIL: no influxd on the PATH: install Debian's influxdb (scripts/test does)")

    expected = []
    line_files = []
    for n, (capture, extra) in enumerate(make_inputs(args)):
        jsonl, lp = (os.path.join(args.scratch, f"values{n}.{e}") for e in ("jsonl", "lp"))
        run([args.pvtap, "audit", "--summary-only", "--values", jsonl, "--values-format",
             "jsonl", *extra, capture])
        run([args.pvtap, "audit", "--summary-only", "--values", lp, "--values-format",
             "influx", *extra, capture])
        expected += expected_points(jsonl)
        line_files.append(lp)

    server = InfluxServer(args.scratch, "values")
    server.query(DB, f"CREATE DATABASE {DB}")
    for lp in line_files:
        with open(lp, "rb") as f:
            status, text = server.request("POST", "/write", {"db": DB, "precision": "ns"},
                                          f.read())
        if status != 204:
            sys.exit(f"FAIL: /write of {lp}: HTTP {status}: {text[:600]}")
    stored = stored_points(server)
    fields = server.query(DB, "SHOW FIELD KEYS FROM pvtap")[0]["values"]
    server.stop()

    failures = []
    for lp in line_files:
        bad_times = leading_zero_times(lp)
        if bad_times:
            failures.append(f"{lp}: {len(bad_times)} times with leading zeros, "
                            f"e.g. {bad_times[0]!r}")
    if fields != [["value", "float"]]:
        failures.append(f"field keys {fields}, expected value as float")
    buses = {tags[0] for tags, _, _ in expected}
    for name in CHANNELS.values():
        if not any(name.decode().replace("\\\\", "\\") in b for b in buses):
            failures.append(f"no bus named with {name!r} in the jsonl: the test lost its names")
    if not any(tags[2] == "frequency" for tags, _, _ in expected):
        failures.append("no meter value in the jsonl: the map was not used")
    if not any(t % 10**9 for _, t, _ in expected if t > 10**18):
        failures.append("no epoch time with a fraction of a second in the jsonl")
    missing = sorted(set(expected) - set(stored))
    extra = sorted(set(stored) - set(expected))
    if len(set(expected)) != len(expected):
        failures.append(f"the jsonl holds {len(expected) - len(set(expected))} points twice")
    for what, points in (("missing from the database", missing), ("not in the jsonl", extra)):
        if points:
            failures.append(f"{len(points)} points {what}, e.g. {points[:3]}")
    if failures:
        print("\n".join("FAIL: " + f for f in failures))
        return 1
    print(f"ok: {len(stored)} points from {len(line_files)} line protocol files, "
          f"{len(buses)} buses, stored and read back equal")
    return 0


if __name__ == "__main__":
    sys.exit(main())
