#!/usr/bin/env python3
"""Opens every link-type-252 and gateway sample with tshark and pvtap's plugin and checks its
frame count and check verdicts against the ground truth (USER0 samples need a per-user
DLT table and are left to pvtap audit; so are gateway samples of a mixed ASCII/RTU bus,
see below). Exits 77 (skipped) when the plugin is not built.

usage: check_sample_plugin.py SAMPLES_DIR PVTAP_PLUGIN
"""
import glob
import json
import os
import shutil
import sys

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")
sys.dont_write_bytecode = True  # leave no __pycache__ in the dissector tests' folder
sys.path.insert(0, os.path.join(ROOT, "tests", "dissector"))
GATEWAY_PORT = 4001  # pvtap-sim's gateway
FIELDS = ["invrtu.crc.status", "invascii.checksum.status"]


def verdicts(home, capture, dialects):
    # A port belongs to one protocol; a mixed bus is left to the plugin's heuristics.
    options = []
    if capture.endswith(".gateway.pcap") and len(set(dialects)) == 1:
        protocol = "invascii" if dialects[0] == "ascii" else "invrtu"
        options = ["-o", f"{protocol}.tcp.port:{GATEWAY_PORT}"]
    name = os.path.basename(capture)
    shutil.copy(capture, home.path(name))
    home._hand_over()
    rows = home.fields(home.path(name), FIELDS, options=options)
    return [v for row in rows for cell in row for v in cell]


def main():
    samples, plugin = sys.argv[1:3]
    if not os.path.isfile(plugin):
        print("pvtap plugin not built: skipped")
        return 77
    os.environ["PVTAP_PLUGIN"] = plugin
    from tshark_runner import TsharkHome
    home = TsharkHome()
    failures = []
    try:
        for capture in sorted(glob.glob(os.path.join(samples, "*.pdu.pcap")) +
                              glob.glob(os.path.join(samples, "*.gateway.pcap"))):
            scenario = os.path.basename(capture).split(".")[0]
            with open(os.path.join(samples, scenario + ".truth.json"), encoding="utf-8") as f:
                truth = json.load(f)
            summary = truth["summary"]
            if capture.endswith(".gateway.pcap") and len(set(truth["dialects"])) > 1:
                # The plugin binds a TCP conversation to one protocol (invrtu or invascii),
                # so a gateway carrying ASCII and RTU stations at once is beyond it.
                print(f"{os.path.basename(capture)}: mixed ASCII/RTU over one TCP "
                      "connection, not checked")
                continue
            found = verdicts(home, capture, truth["dialects"])
            if len(found) != summary["frames"] or found.count("0") != summary["bad_checks"]:
                failures.append(f"{os.path.basename(capture)}: plugin {len(found)} frames, "
                                f"{found.count('0')} bad; truth {summary['frames']} frames, "
                                f"{summary['bad_checks']} bad")
    finally:
        home.close()
    for text in failures:
        print(text)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
