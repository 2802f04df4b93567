#!/usr/bin/env python3
"""No false alarm of a shared bus on real recordings: every recording others made of a real
bus (../shared/real: serial taps, logic sessions, a plain dump) has one master on each bus
that carried requests, no collision, no address conflict and no echo. Their buses are known
to have one master each (the folder's README).

Usage: check_real_shared_bus.py PVTAP REAL_DIR
"""
import glob
import json
import os
import subprocess
import sys

RUN_GUARD_S = 300
SKIP = 77


def summary_of(pvtap, path):
    args = ["--raw", path] if path.endswith(".bin") else [path]
    run = subprocess.run([pvtap, "audit", "--summary-only", "--format", "jsonl", *args],
                         capture_output=True, text=True, timeout=RUN_GUARD_S)
    if run.returncode not in (0, 1):
        raise RuntimeError(f"pvtap audit {path} exited {run.returncode}: {run.stderr.strip()}")
    return json.loads(run.stdout.splitlines()[-1])


def main():
    pvtap, real = sys.argv[1:3]
    paths = sorted(glob.glob(os.path.join(real, "taps", "*.pcap")) +
                   glob.glob(os.path.join(real, "sigrok", "*.sr")) +
                   glob.glob(os.path.join(real, "raw", "*.bin")))
    if not paths:
        print(f"no recordings under {real}")
        return SKIP
    bad = []
    for path in paths:
        s = summary_of(pvtap, path)
        name = os.path.relpath(path, real)
        for bus in s["buses"]:
            masters = len(bus.get("masters", []))
            if masters > 1 or (bus.get("requests", 0) > 0 and masters != 1):
                bad.append(f"{name}: bus {bus.get('bus')} has {masters} masters")
        for key in ("collisions", "address_conflicts", "echoes"):
            if s.get(key, 0) != 0:
                bad.append(f"{name}: {key} {s[key]}")
    for line in bad:
        print("FAIL:", line)
    print(f"{len(paths)} recordings, {len(bad)} false alarms")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
