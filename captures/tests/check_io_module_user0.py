#!/usr/bin/env python3
"""An IO module alone on a 19200-baud bus, polled with function codes 1, 2, 3, 4, 5, 6, 15 and
16, captured one frame per USER0 record (as a USB adapter hands short frames over): pvtap audit
must find all 30 frames with good checks, no noise, every request paired with its reply, and
one station.

usage: check_io_module_user0.py PVTAP_SIM PVTAP SCRATCH
"""
import json
import os
import struct
import subprocess
import sys

STATION = 7
FUNCTIONS = {1, 2, 3, 4, 5, 6, 15, 16}


def pcap_records(path):
    with open(path, "rb") as f:
        header = f.read(24)
        magic, _, _, _, _, _, linktype = struct.unpack("<IHHiIII", header)
        if magic != 0xA1B2C3D4:
            sys.exit(f"{path}: not a little-endian microsecond pcap")
        records = []
        while True:
            head = f.read(16)
            if len(head) < 16:
                return linktype, records
            _, _, caplen, _ = struct.unpack("<IIII", head)
            records.append(f.read(caplen))


def main():
    sim, pvtap, scratch = sys.argv[1:4]
    os.makedirs(scratch, exist_ok=True)
    capture, truth_path = os.path.join(scratch, "io.user0.pcap"), os.path.join(scratch, "io.json")
    subprocess.run([sim, "--inverters", "0", "--io-module", str(STATION), "--baud", "19200",
                    "--duration", "12", "--period", "5", "--seed", "11", "--faults", "none",
                    "--chunked", capture, "--truth", truth_path], check=True)
    with open(truth_path, encoding="utf-8") as f:
        truth = [e for e in json.load(f)["events"] if e["type"] == "frame"]
    problems = []
    if len(truth) != 30 or {e["function"] for e in truth} != FUNCTIONS:
        problems.append(f"the simulator played {len(truth)} frames of functions "
                        f"{sorted({e['function'] for e in truth})}")
    linktype, records = pcap_records(capture)
    if linktype != 147 or [r.hex() for r in records] != [e["hex"] for e in truth]:
        problems.append(f"link type {linktype}, {len(records)} records: not one frame per record")
    run = subprocess.run([pvtap, "audit", "--format", "jsonl", "--baud", "19200", capture],
                         capture_output=True, text=True, check=True)
    events = [json.loads(line) for line in run.stdout.splitlines()]
    frames = [e for e in events if e["type"] == "frame"]
    summary = events[-1]
    if [(f["role"], f["raw"], f["check"]) for f in frames] != \
            [(e["role"], e["hex"], "ok") for e in truth]:
        problems.append(f"audit found {len(frames)} frames unlike the 30 on the bus")
    unpaired = [f["raw"] for f in frames if f["role"] == "response" and "latency_ms" not in f]
    if unpaired or summary["requests"] != 15 or summary["responses"] != 15:
        problems.append(f"requests {summary['requests']}, responses {summary['responses']}, "
                        f"replies paired with no request: {unpaired}")
    for key in ("noise_bytes", "bad_checks", "timeouts", "unsolicited", "duplicates"):
        if summary[key] != 0:
            problems.append(f"summary {key}: {summary[key]}")
    if list(summary["stations"]) != [str(STATION)]:
        problems.append(f"stations {list(summary['stations'])}, want [{STATION}]")
    for text in problems:
        print(text)
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
