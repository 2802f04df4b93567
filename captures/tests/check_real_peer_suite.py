#!/usr/bin/env python3
"""Records a library test suite's exchanges made entirely by Debian's libmodbus (its master and
its server, through socat pseudo-terminals and ser2net; `record ... suite`) and checks that
pvtap audit gives exactly what the master put on the wire: one good request and one paired
reply per call, none read in the Hybrid dialect (libmodbus's report server ID and read/write
multiple registers replies fit Hybrid's 0x11 and 0x17 byte for byte), no timeout, no
unsolicited reply, no noise, no dialect change, and the station named by its server ID text.

usage: check_real_peer_suite.py PVTAP RECORD_SCRIPT SCRATCH_DIR
"""
import json
import os
import shutil
import subprocess
import sys


def main():
    pvtap, record, scratch = sys.argv[1:4]
    shutil.rmtree(scratch, ignore_errors=True)
    subprocess.run([record, scratch, "suite"], check=True)
    with open(os.path.join(scratch, "real-peer.polls.json"), encoding="utf-8") as f:
        master = json.load(f)
    failures = []
    calls = master["exchanges"]
    if any(c["returned"] < 0 for c in calls):
        failures.append(f"a libmodbus call failed: {calls}")
    run = subprocess.run([pvtap, "audit", "--format", "jsonl",
                          os.path.join(scratch, "real-peer.pcap")],
                         capture_output=True, text=True, check=True)
    events = [json.loads(line) for line in run.stdout.splitlines()]
    frames = [e for e in events if e["type"] == "frame"]
    summary = events[-1]
    want = {"frames": 2 * len(calls), "requests": len(calls), "responses": len(calls),
            "bad_checks": 0, "timeouts": 0, "unsolicited": 0, "noise_bytes": 0,
            "exceptions": 0}
    for key, value in want.items():
        if summary.get(key) != value:
            failures.append(f"audit summary {key} = {summary.get(key)}, expected {value}")
    if summary.get("dialect_changes", 0) != 0:
        failures.append(f"dialect changes: {summary.get('dialect_changes')}")
    functions = [f["function"] for f in frames]
    expected = [f for c in calls for f in (c["function"], c["function"])]
    if functions != expected:
        failures.append(f"functions {functions}, the master's calls {expected}")
    for f in frames:
        if f["dialect"] == "hybrid" or f["check"] != "ok" or f["issues"]:
            failures.append(f"frame {f['raw']}: {f['dialect']}, {f['check']}, {f['issues']}")
    station = summary.get("stations", {}).get(str(master["station"]), {})
    name = station.get("device", {}).get("name")
    if name != master["server_id_text"]:
        failures.append(f"station name {name!r}, server ID text {master['server_id_text']!r}")
    for line in failures:
        print(line)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
