#!/usr/bin/env python3
"""A shared bus from the simulator (two masters with their own poll plans and periods) and
pvtap audit's reading of it: as many masters as the truth has, each truth master's period
found within 3 %, each truth master's poll blocks in the plan of the master of that period,
the finding in the text report, and requests sent while another's reply was due counted.
Then a second device answering to one inverter's address: every second reply it gave is an
address conflict of that station (and not a duplicate), whether the bytes come as exported
PDUs or as a USER0 serial stream, with the finding in the text and HTML reports. On busier
shared buses (three inverters, where the poll cycles overrun and only requests sent while a
reply was due show the second master), the collisions: between 90 % of the truth's and the
truth's, by both roads, most timeouts lost in one, and none on the buses of one master below.
Last, a tap whose adapter echoes every request: each echo counted once, as the truth's, by both roads,
and the requests, replies and timeouts those of the truth, as if there were no echo.

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
    collisions = summary.get("collisions", 0)
    if not 0.9 * len(truth["collisions"]) <= collisions <= len(truth["collisions"]):
        bad.append(f"collisions: audit {collisions}, truth {len(truth['collisions'])}")
    listed = subprocess.run([pvtap, "audit", "--format", "jsonl", capture], capture_output=True,
                            text=True, check=True).stdout.splitlines()
    named = [json.loads(l) for l in listed if '"type":"collision"' in l]
    if len(named) != collisions or not all(c["end"] >= c["ts"] for c in named):
        bad.append(f"{len(named)} collision lines, the summary counts {collisions}")
    check_collisions(pvtap, sim, scratch, bad)
    check_address_conflict(pvtap, sim, scratch, bad)
    check_echo(pvtap, sim, scratch, bad)
    for line in bad:
        print("shared bus:", line)
    return 1 if bad else 0


def audit_summary(pvtap, capture):
    run = subprocess.run([pvtap, "audit", "--summary-only", "--format", "jsonl", capture],
                         capture_output=True, text=True, check=True)
    return json.loads(run.stdout.splitlines()[-1])


def check_collisions(pvtap, sim, scratch, bad):
    for seed in ("3", "11"):
        pdu = os.path.join(scratch, f"busy{seed}.pdu.pcap")
        user0 = os.path.join(scratch, f"busy{seed}.user0.pcap")
        truth_path = os.path.join(scratch, f"busy{seed}.truth.json")
        subprocess.run([sim, "--seed", seed, "--inverters", "3", "--period", "1", "--timeout",
                        "0.3", "--masters", "2", "--duration", "120", "--pdu", pdu, "--chunked",
                        user0, "--truth", truth_path], check=True)
        with open(truth_path, encoding="utf-8") as f:
            want = len(json.load(f)["collisions"])
        for capture in (pdu, user0):
            summary = audit_summary(pvtap, capture)
            name = os.path.basename(capture)
            found = summary["collisions"]
            if not 0.9 * want <= found <= want or summary["buses"][0]["collisions"] != found:
                bad.append(f"{name}: {found} collisions, truth {want}")
            lost, timeouts = summary["lost_in_collision"], summary["timeouts"]
            if not 0.8 * timeouts <= lost <= timeouts:
                bad.append(f"{name}: {lost} of {timeouts} timeouts lost in a collision")


def second_replies(truth):
    """The second device's replies by station: those whose bytes differ from the reply before
    them (conflicts), and those that repeat them (a block whose values both devices share:
    duplicates, since nothing on the line tells them apart)."""
    differ, same, last = {}, {}, {}
    for e in truth["events"]:
        if e["type"] != "frame" or e["role"] != "response":
            continue
        if e.get("fault") == "address_conflict":
            into = same if last.get(e["station"]) == e["hex"] else differ
            into[e["station"]] = into.get(e["station"], 0) + 1
        last[e["station"]] = e["hex"]
    return differ, same


def check_address_conflict(pvtap, sim, scratch, bad):
    pdu = os.path.join(scratch, "conflict.pdu.pcap")
    user0 = os.path.join(scratch, "conflict.user0.pcap")
    truth_path = os.path.join(scratch, "conflict.truth.json")
    subprocess.run([sim, "--seed", "11", "--inverters", "3", "--period", "1",
                    "--address-conflict", "2", "--duration", "40", "--pdu", pdu, "--chunked", user0,
                    "--truth", truth_path], check=True)
    with open(truth_path, encoding="utf-8") as f:
        truth = json.load(f)
    want, repeated = second_replies(truth)
    if want.get(2, 0) < 50:
        bad.append(f"the simulator's truth has too few second replies at station 2: {want}")
    if sum(want.values()) + sum(repeated.values()) != truth["address_conflicts"][0]["second_replies"]:
        bad.append("the second replies of the truth's events are not its count")
    for capture in (pdu, user0):
        run = subprocess.run([pvtap, "audit", "--summary-only", "--format", "jsonl", capture],
                             capture_output=True, text=True, check=True)
        summary = json.loads(run.stdout.splitlines()[-1])
        found = {int(k): s["address_conflicts"] for k, s in summary["stations"].items()
                 if s["address_conflicts"]}
        name = os.path.basename(capture)
        if found != want:
            bad.append(f"{name}: address conflicts by station {found}, truth {want}")
        if summary["stations"]["2"]["duplicates"] != repeated.get(2, 0):
            bad.append(f"{name}: station 2 has {summary['stations']['2']['duplicates']} "
                       f"duplicates, truth {repeated.get(2, 0)} second replies of the same bytes")
        if summary["collisions"] != 0 or summary["lost_in_collision"] != 0:
            bad.append(f"{name}: {summary['collisions']} collisions on a bus of one master")
        if summary.get("address_conflicts") != sum(want.values()):
            bad.append(f"{name}: the summary counts {summary.get('address_conflicts')} "
                       "address conflicts")
    page = os.path.join(scratch, "conflict.html")
    text = subprocess.run([pvtap, "audit", "--summary-only", "--html", page, pdu],
                          capture_output=True, text=True, check=True).stdout
    finding = f"FINDING: two devices answer to station 2: {want.get(2)} of its requests"
    if finding not in text:
        bad.append(f"the text report lacks {finding!r}")
    if "other ones" not in text:
        bad.append("the text report's finding does not give the second device's latency")
    with open(page, encoding="utf-8") as f:
        if "Two devices answer to station 2" not in f.read():
            bad.append("the HTML report has no address-conflict finding")


def check_echo(pvtap, sim, scratch, bad):
    pdu = os.path.join(scratch, "echo.pdu.pcap")
    user0 = os.path.join(scratch, "echo.user0.pcap")
    truth_path = os.path.join(scratch, "echo.truth.json")
    subprocess.run([sim, "--seed", "5", "--inverters", "3", "--period", "1", "--echo",
                    "--faults", "missing=5,duplicate=3,corrupt=3", "--duration", "60",
                    "--pdu", pdu, "--chunked", user0, "--truth", truth_path], check=True)
    with open(truth_path, encoding="utf-8") as f:
        truth = json.load(f)
    echoed = sum(1 for e in truth["events"] if e.get("fault") == "echo")
    if echoed != truth["echoes"] or echoed < 100 or truth["summary"]["timeouts"] == 0:
        bad.append(f"the echo run's truth: {echoed} echo events, {truth['echoes']} echoes, "
                   f"{truth['summary']['timeouts']} timeouts")
    for capture in (pdu, user0):
        run = subprocess.run([pvtap, "audit", "--summary-only", "--format", "jsonl", capture],
                             capture_output=True, text=True, check=True)
        summary = json.loads(run.stdout.splitlines()[-1])
        name = os.path.basename(capture)
        found = {key: summary.get(key) for key in ("echoes", "requests", "responses", "timeouts")}
        want = {"echoes": truth["echoes"]}
        want.update({key: truth["summary"][key] for key in ("requests", "responses", "timeouts")})
        if found != want:
            bad.append(f"{name}: {found}, truth {want}")
        if summary["frames"] != truth["summary"]["frames"] + truth["echoes"]:
            bad.append(f"{name}: {summary['frames']} frames on the line, truth "
                       f"{truth['summary']['frames']} and {truth['echoes']} echoes")
        if summary["collisions"] != 0:
            bad.append(f"{name}: {summary['collisions']} collisions of an echo")
        if len(summary["buses"][0].get("masters", [])) != 1:
            bad.append(f"{name}: the echoes made {summary['buses'][0].get('masters')} masters")
    text = subprocess.run([pvtap, "audit", "--summary-only", pdu], capture_output=True,
                          text=True, check=True).stdout
    line = f"echoes: {truth['echoes']} of {truth['summary']['requests']} requests seen twice"
    if line not in text:
        bad.append(f"the text report lacks {line!r}")
    listed = subprocess.run([pvtap, "audit", "--format", "jsonl", pdu], capture_output=True,
                            text=True, check=True).stdout.splitlines()
    echoes = [json.loads(l) for l in listed if '"echo":true' in l]
    if len(echoes) != truth["echoes"] or any(e["role"] != "request" for e in echoes):
        bad.append(f"{len(echoes)} frame records say echo, truth {truth['echoes']}")


if __name__ == "__main__":
    sys.exit(main())
