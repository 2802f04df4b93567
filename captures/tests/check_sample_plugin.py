#!/usr/bin/env python3
"""Opens every link-type-252 and gateway sample (mixed ASCII/RTU buses included) with tshark
and pvtap's plugin, and checks that Wireshark shows the same frames as pvtap audit on the same
capture: for each protocol and role, the same sequence of check verdicts; and the frame count
and bad checks of the ground truth. (USER0 samples need a per-user DLT table and are left to
pvtap audit.) Exits 77 (skipped) when the plugin is not built.

usage: check_sample_plugin.py SAMPLES_DIR PVTAP_PLUGIN PVTAP
"""
import glob
import json
import os
import shutil
import subprocess
import sys

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")
sys.dont_write_bytecode = True  # leave no __pycache__ in the dissector tests' folder
sys.path.insert(0, os.path.join(ROOT, "tests", "dissector"))
PROTOCOLS = {"invrtu": "crc", "invascii": "checksum"}
ROLES = {"0": "request", "1": "response"}


def plugin_frames(home, capture):
    """{(protocol, role): [check verdict, ...]} in the order Wireshark shows the frames."""
    name = os.path.basename(capture)
    shutil.copy(capture, home.path(name))
    home._hand_over()
    fields = []
    for protocol, check in PROTOCOLS.items():
        fields += [f"{protocol}.role", f"{protocol}.{check}.status"]
    seen = {}
    for row in home.fields(home.path(name), fields):
        for i, protocol in enumerate(PROTOCOLS):
            roles, statuses = row[2 * i], row[2 * i + 1]
            if len(roles) != len(statuses):
                sys.exit(f"{name}: a frame without a {PROTOCOLS[protocol]} status")
            for role, status in zip(roles, statuses):
                verdict = {"1": "ok", "0": "bad"}.get(status, status)
                seen.setdefault((protocol, ROLES[role]), []).append(verdict)
    return seen


def audit_frames(pvtap, capture):
    run = subprocess.run([pvtap, "audit", "--format", "jsonl", capture], capture_output=True,
                         text=True, check=True)
    seen = {}
    for line in run.stdout.splitlines():
        event = json.loads(line)
        if event["type"] != "frame":
            continue
        protocol = "invascii" if event["dialect"] == "ascii" else "invrtu"
        seen.setdefault((protocol, event["role"]), []).append(event["check"])
    return seen


def compare(capture, truth, found, audited):
    name = os.path.basename(capture)
    problems = []
    for key in sorted(set(found) | set(audited)):
        ours, theirs = found.get(key, []), audited.get(key, [])
        if ours != theirs:
            first = next((i for i, (a, b) in enumerate(zip(ours, theirs)) if a != b),
                         min(len(ours), len(theirs)))
            problems.append(f"{name}: {key[0]} {key[1]}s: plugin {len(ours)}, audit "
                            f"{len(theirs)}, first difference at #{first}")
    frames = sum(len(v) for v in found.values())
    bad = sum(v.count("bad") for v in found.values())
    summary = truth["summary"]
    if frames != summary["frames"] or bad != summary["bad_checks"]:
        problems.append(f"{name}: plugin {frames} frames, {bad} bad; truth "
                        f"{summary['frames']} frames, {summary['bad_checks']} bad")
    return problems


def main():
    samples, plugin, pvtap = sys.argv[1:4]
    if not os.path.isfile(plugin):
        print("pvtap plugin not built: skipped")
        return 77
    os.environ["PVTAP_PLUGIN"] = plugin
    from tshark_runner import TsharkHome
    home = TsharkHome()
    failures = []
    checked = 0
    try:
        for capture in sorted(glob.glob(os.path.join(samples, "*.pdu.pcap")) +
                              glob.glob(os.path.join(samples, "*.gateway.pcap"))):
            scenario = os.path.basename(capture).split(".")[0]
            with open(os.path.join(samples, scenario + ".truth.json"), encoding="utf-8") as f:
                truth = json.load(f)
            failures += compare(capture, truth, plugin_frames(home, capture),
                                audit_frames(pvtap, capture))
            checked += 1
    finally:
        home.close()
    for text in failures:
        print(text)
    print(f"{checked} captures checked, {len(failures)} disagreement(s)")
    return 1 if failures or checked == 0 else 0


if __name__ == "__main__":
    sys.exit(main())
