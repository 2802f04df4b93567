#!/usr/bin/env python3
"""A shared bus from the simulator (two masters with their own poll plans and periods) and
pvtap audit's reading of it: as many masters as the truth has, each truth master's period
found within 3 %, each truth master's poll blocks in the plan of the master of that period,
the finding in the text report, and requests sent while another's reply was due counted.

usage: check_shared_bus.py PVTAP PVTAP_SIM SCRATCH_DIR
"""
import json
import os
import subprocess
import sys


def main():
    pvtap, sim, scratch = sys.argv[1:4]
    os.makedirs(scratch, exist_ok=True)
    capture = os.path.join(scratch, "shared.pdu.pcap")
    truth_path = os.path.join(scratch, "shared.truth.json")
    subprocess.run([sim, "--seed", "37", "--inverters", "2", "--period", "1", "--timeout", "0.3",
                    "--masters", "2", "--duration", "120", "--pdu", capture,
                    "--truth", truth_path], check=True)
    with open(truth_path, encoding="utf-8") as f:
        truth = json.load(f)
    run = subprocess.run([pvtap, "audit", "--summary-only", "--format", "jsonl", capture],
                         capture_output=True, text=True, check=True)
    summary = json.loads(run.stdout.splitlines()[-1])
    bad = []
    bus = summary["buses"][0]
    masters = bus.get("masters", [])
    if len(masters) != len(truth["masters"]):
        bad.append(f"masters: audit {len(masters)}, truth {len(truth['masters'])}")
    for want in truth["masters"]:
        period = want["period_s"] * 1e3
        found = [m for m in masters if m["period_ms"] and abs(m["period_ms"] / period - 1) < 0.03]
        if len(found) != 1:
            bad.append(f"master {want['master']} (every {period} ms): audit cycles "
                       f"{[m['period_ms'] for m in masters]}")
            continue
        plan = {(p["station"], p["function"], p["start"], p["count"]) for p in found[0]["plan"]}
        # A block the other master's collisions disturbed may go to the busiest master: the
        # blocks with a regular cycle must be in the right one.
        regular = {(p["station"], p["function"], p["start"], p["count"])
                   for m in masters for p in m["plan"] if p["cycle_ms"]}
        for p in want["plan"]:
            block = (p["station"], p["function"], p["start"], p["count"])
            if block in regular and block not in plan:
                bad.append(f"master {want['master']}: block {block} not in its plan {plan}")
    if bus.get("requests_while_reply_due", 0) == 0:
        bad.append("no request sent while another's reply was due")
    text = subprocess.run([pvtap, "audit", "--summary-only", capture], capture_output=True,
                          text=True, check=True).stdout
    if "FINDING: 2 masters on one bus" not in text:
        bad.append("the text report has no finding of two masters")
    for line in bad:
        print("shared bus:", line)
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
