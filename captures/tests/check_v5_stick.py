#!/usr/bin/env python3
"""pvtap audit on a Solarman V5 stick that behaves as real ones do (issue 35), against the
simulator's ground truth: the capture of check_lan_samples.STICK_FAULTS (codes 05 and 06, a
client with a wrong serial, heartbeats where a reply was due, replies after the client's
next request, and the carrier faults of the samples).

- Frames, timeouts, noise, stations and totals: check_sample_audit.py's comparison.
- Replies pair by the sequence byte: each late reply answers its own request, with the
  truth's LAN latency (less the reply's own time on the wire at the bus's baud, as pvtap
  times a stick's frames).
- Code 05: its request is a timeout whose reason names the code, counted in
  gateway_timeouts. Code 06: no bus frame, no timeout, one bus only, said plainly.
- The summary's network.solarman_v5 counts are the truth's.

usage: check_v5_stick.py PVTAP PVTAP_SIM SCRATCH
"""
import json
import os
import subprocess
import sys

from check_lan_samples import STICK_FAULTS

HERE = os.path.dirname(os.path.abspath(__file__))
# The truth's count and the summary's name for it.
COUNTS = {"frames": "frames", "heartbeats": "heartbeats", "client_answers": "stick_answers",
          "carrier_bytes": "carrier_bytes", "rtu_bytes": "rtu_bytes",
          "quirk_bytes": "quirk_bytes", "bad_checksums": "bad_checksums",
          "stick_codes": "stick_codes", "stick_timeouts": "stick_timeouts",
          "refused_requests": "refused_requests",
          "replies_after_next_request": "replies_after_next_request"}


def main():
    pvtap, sim, scratch = sys.argv[1:4]
    os.makedirs(scratch, exist_ok=True)
    capture, truth_path = os.path.join(scratch, "stick.v5.pcap"), os.path.join(scratch, "t.json")
    subprocess.run([sim, "--seed", "35", "--dialect", "gsl,hybrid", "--inverters", "4",
                    "--duration", "120", "--period", "5", "--faults", "missing=10,corrupt=3",
                    "--v5", capture, "--v5-faults", STICK_FAULTS, "--truth", truth_path],
                   check=True)
    with open(truth_path, encoding="utf-8") as f:
        truth = json.load(f)
    bad = []
    same = subprocess.run([sys.executable, os.path.join(HERE, "check_sample_audit.py"), pvtap,
                           capture, truth_path], capture_output=True, text=True)
    if same.returncode != 0:
        bad.append(same.stdout.strip() or "check_sample_audit.py: " + same.stderr.strip())
    run = subprocess.run([pvtap, "audit", "--format", "jsonl", capture], capture_output=True,
                         text=True, check=True)
    events = [json.loads(line) for line in run.stdout.splitlines() if line.strip()]
    frames = [e for e in events if e["type"] == "frame"]
    summary = events[-1]
    check_late_replies(truth, frames, bad)
    check_codes(truth, events, summary, bad)
    v5 = summary["network"]["solarman_v5"]
    for theirs, ours in COUNTS.items():
        if v5.get(ours) != truth["v5"][theirs]:
            bad.append(f"solarman_v5 {ours}: {v5.get(ours)}, truth {truth['v5'][theirs]}")
    for key in ("other_stick_codes", "unpaired_replies"):
        if v5.get(key) != 0:
            bad.append(f"solarman_v5 {key}: {v5.get(key)}, truth 0")
    for line in bad:
        print(line)
    print(f"{capture}: {len(bad)} problems")
    return 1 if bad else 0


def check_late_replies(truth, frames, bad):
    """The audit's frames are the truth's events in order (check_sample_audit.py says so)."""
    wire_ms = 10 * 1000 / truth["baud"]  # 8N1
    late = [t for t in truth["v5_frames"] if t.get("late")]
    if not late:
        bad.append("no late reply in the truth")
    for t in late:
        f = frames[t["event"]] if t["event"] < len(frames) else {}
        want = t["latency_ms"] - len(truth["events"][t["event"]]["hex"]) // 2 * wire_ms
        if f.get("late_by_ms") is not None or abs(f.get("latency_ms", -1) - want) > 0.002:
            bad.append(f"reply at {t['ts']}: latency {f.get('latency_ms')} ms "
                       f"(late by {f.get('late_by_ms')}), truth {want:.3f}")


def check_codes(truth, events, summary, bad):
    coded = [t for t in truth["timeouts"] if t.get("reason")]
    said = [e for e in events if e["type"] == "timeout" and e["reason"] == "carrier_no_reply"]
    if [(e["station"], e["function"], e.get("carrier_reason")) for e in said] != \
            [(t["station"], t["function"], t["reason"]) for t in coded] or not coded:
        bad.append(f"code 05 timeouts: audit {said}, truth {coded}")
    if summary.get("gateway_timeouts", 0) != len(coded):
        bad.append(f"gateway_timeouts {summary.get('gateway_timeouts')}, truth {len(coded)}")
    buses = [b["bus"] for b in summary["buses"]]
    if buses != ["v5:%d" % truth["v5"]["logger_serial"]]:
        bad.append(f"buses {buses}: one, of the stick's serial, expected")
    findings = summary["network"]["solarman_v5"].get("stick_findings", [])
    said = "the client addressed logger 2111130827; the stick is %d" % truth["v5"]["logger_serial"]
    if findings != [said]:
        bad.append(f"stick findings {findings}, expected {said!r}")


if __name__ == "__main__":
    sys.exit(main())
