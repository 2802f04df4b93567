#!/usr/bin/env python3
"""The report's time span runs from the first byte of bus traffic to the last: no frame of the
capture starts before the span's first instant or after its last (issue 38, item 7), on
every sample capture. And every bus has a name: each jsonl event and csv row says its bus,
and the summary names each bus (a serial capture's or plain dump's is "serial", a logic
recording's its channels, a gateway's its endpoint).

Usage: check_time_span.py PVTAP SAMPLES_DIR
"""
import csv
import datetime
import glob
import json
import os
import re
import subprocess
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "support"))
from checks import Checks  # noqa: E402

RUN_GUARD_S = 120
SPAN = re.compile(r"^time: (\S+ \S+) \.\. (\S+ \S+) UTC", re.M)


def epoch(text):
    when = datetime.datetime.strptime(text, "%Y-%m-%d %H:%M:%S.%f")
    return when.replace(tzinfo=datetime.timezone.utc).timestamp()


def check_bus_names(checks, name, jsonl):
    events = [json.loads(l) for l in jsonl.splitlines() if l.strip()]
    unnamed = [e["type"] for e in events if e["type"] != "summary" and not e.get("bus")]
    checks.true(f"{name}: every event names its bus ({len(unnamed)} do not: {unnamed[:3]})",
                not unnamed and len(events) > 1)
    buses = [b.get("bus") for e in events if e["type"] == "summary" for b in e["buses"]]
    checks.true(f"{name}: the summary names every bus: {buses}", buses and all(buses))


def check_other_inputs(checks, pvtap, samples):
    """A plain dump and a logic recording name their buses; csv rows carry the name too."""
    user0 = os.path.join(samples, "demo.user0.pcap")
    raw = subprocess.run([pvtap, "audit", "--format", "jsonl", "--raw", "/dev/stdin"],
                         input=bytes.fromhex("010303e8000a45bd"), capture_output=True,
                         timeout=RUN_GUARD_S).stdout.decode()
    check_bus_names(checks, "--raw", raw)
    logic = os.path.join(samples, "logic-bus.sr")
    if os.path.exists(logic):
        out = subprocess.run([pvtap, "audit", "--format", "jsonl", logic], capture_output=True,
                             text=True, timeout=RUN_GUARD_S).stdout
        check_bus_names(checks, "logic-bus.sr", out)
    rows = subprocess.run([pvtap, "audit", "--format", "csv", user0], capture_output=True,
                          text=True, timeout=RUN_GUARD_S).stdout.splitlines()
    header = rows[0].split(",") if rows else []
    column = header.index("bus") if "bus" in header else None
    checks.true(f"csv has a bus column: {header}", column is not None)
    if column is not None:
        empty = [r for r in csv.reader(rows[1:]) if len(r) > column and not r[column]]
        checks.true(f"every csv row names its bus ({len(empty)} do not)", not empty)


def main():
    pvtap, samples = sys.argv[1], sys.argv[2]
    checks = Checks()
    captures = sorted(glob.glob(os.path.join(samples, "*.pcap")))
    checks.true("sample captures found", len(captures) > 10)
    for capture in captures:
        name = os.path.basename(capture)
        text = subprocess.run([pvtap, "audit", "--summary-only", capture], capture_output=True,
                              text=True, timeout=RUN_GUARD_S).stdout
        lines = subprocess.run([pvtap, "audit", "--format", "jsonl", capture],
                               capture_output=True, text=True, timeout=RUN_GUARD_S).stdout
        span = SPAN.search(text)
        checks.true(f"{name}: the report gives its time span", span is not None)
        starts = [json.loads(l)["ts"] for l in lines.splitlines()
                  if l.strip() and json.loads(l)["type"] == "frame"]
        if span is None or not starts:
            continue
        check_bus_names(checks, name, lines)
        first, last = epoch(span.group(1)), epoch(span.group(2))
        # The span is printed to the microsecond.
        checks.true(f"{name}: the span begins at or before the first frame "
                    f"({span.group(1)} vs {min(starts):.6f})", first <= min(starts) + 1e-6)
        checks.true(f"{name}: the span ends at or after the last frame's start",
                    last + 1e-6 >= max(starts))
    check_other_inputs(checks, pvtap, samples)
    return checks.finish()


if __name__ == "__main__":
    sys.exit(main())
