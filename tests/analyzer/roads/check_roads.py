#!/usr/bin/env python3
"""The roads test: the same bus traffic, whatever road it took to pvtap, gives the same verdicts.

For every sample capture and for a bus of every fault class the simulator makes, each capture
is audited whole and then by the other roads, and the verdicts are compared with
compare_verdicts.py (frames with their checks, findings and latencies, damaged replies,
timeouts and their reasons, noise runs and bytes, gaps, duplicates, stations, latency p50 and
max):
  parts    cut into 2 to 5 files given in a shuffled order (event times too, to the us);
  pcapng   converted by editcap (event times too);
  write    written with `pvtap audit --write` and audited again (event times too);
  forms    the USER0 and gateway forms of a bus held against its link type 252 form, which
           keeps the bus timing (the other forms re-time the bytes: latencies and offsets
           are left out there), and its 4-wire form: the requests' and the replies' pairs
           in two USER0 files, audited with --duplex.
Frames and stations are compared with their decoded values: a SunSpec inverter's bus is among
the simulated ones, its model chain learned from a scan that a cut puts in one file only.
The plugin's roads (one pass and two, on the same samples) are plugin.test_sample_library.

Usage: check_roads.py --pvtap PVTAP --sim PVTAP_SIM --samples DIR --work DIR [--only NAME]
"""

import argparse
import glob
import json
import os
import random
import shutil
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
sys.path.insert(0, os.path.join(HERE, "..", "..", "support"))
sys.dont_write_bytecode = True
from compare_verdicts import Options, differences  # noqa: E402
from pcap_records import read_pcap  # noqa: E402

RUN_GUARD_S = 300  # a guard against a hung run, not a timing check
SKIP = 77
FAULT_CLASSES = ("corrupt", "missing", "slow", "noise", "error_reply", "count_mismatch",
                 "duplicate", "corrupt_request", "corrupt_data")
FORMS = ("pdu", "user0", "gateway", "duplex")
STRICT = Options(times=True)
RETIMED = Options(ignore=frozenset({"latency", "offset", "bus"}))


class Report:
    def __init__(self):
        self.failures, self.roads = [], 0

    def compare(self, what, whole, other, options):
        self.roads += 1
        found = differences(whole, other, options)
        if found:
            self.failures.append(f"{what}:\n    " + "\n    ".join(found[:12]))


def audit(pvtap, files, *extra):
    run = subprocess.run([pvtap, "audit", "--format", "jsonl", *extra, *files],
                         capture_output=True, text=True, timeout=RUN_GUARD_S)
    if run.returncode not in (0, 1):
        raise RuntimeError(f"pvtap audit {' '.join(files)} exited {run.returncode}: "
                           f"{run.stderr.strip()}")
    return [json.loads(line) for line in run.stdout.splitlines() if line.strip()]


def road_parts(options, capture, work, rng):
    pcap = read_pcap(capture)
    count = rng.randint(2, max(2, min(5, len(pcap.records))))
    n = len(pcap.records)
    bounds = [round(i * n / count) for i in range(count + 1)]
    files = []
    for i in range(count):
        files.append(os.path.join(work, f"part{i}.pcap"))
        pcap.write(files[-1], pcap.records[bounds[i]:bounds[i + 1]])
    rng.shuffle(files)
    return f"cut into {count} files given as " + ",".join(os.path.basename(f) for f in files), \
        audit(options.pvtap, files)


def road_pcapng(options, capture, work):
    out = os.path.join(work, "whole.pcapng")
    subprocess.run(["editcap", "-F", "pcapng", capture, out], check=True, timeout=RUN_GUARD_S)
    return "as pcapng", audit(options.pvtap, [out])


def road_write(options, capture, work):
    out = os.path.join(work, "written.pcap")
    audit(options.pvtap, [capture], "--summary-only", "--write", out)
    return "written with --write and audited again", audit(options.pvtap, [out])


def check_capture(options, report, capture, rng):
    name = os.path.basename(capture)
    work = os.path.join(options.work, name)
    os.makedirs(work, exist_ok=True)
    whole = audit(options.pvtap, [capture])
    roads = [road_parts(options, capture, work, rng), road_pcapng(options, capture, work)]
    if not capture.endswith(".mbap.pcap"):  # --write leaves MBAP frames out (no CRC)
        roads.append(road_write(options, capture, work))
    for what, lines in roads:
        report.compare(f"{name} {what}", whole, lines, STRICT)
    return whole


def check_forms(options, report, stem, audited):
    """audited: {form: lines} of one bus."""
    if "pdu" not in audited:
        return
    for form in FORMS[1:]:
        if form in audited:
            report.compare(f"{stem}: the {form} form against the link type 252 form",
                           audited["pdu"], audited[form], RETIMED)


def simulated_bus(options, stem, sim_args):
    """{form: path} of one simulated bus written in every form (the duplex form: two files)."""
    folder = os.path.join(options.work, stem)
    os.makedirs(folder, exist_ok=True)
    paths = {form: os.path.join(folder, f"{stem}.{form}.pcap") for form in FORMS}
    pairs = [os.path.join(folder, f"{stem}.{pair}.user0.pcap") for pair in ("req", "rep")]
    subprocess.run([options.sim, *sim_args, "--duration", "90",
                    "--pdu", paths["pdu"], "--gateway", paths["gateway"],
                    "--chunked", paths["user0"], "--duplex", *pairs],
                   check=True, capture_output=True, timeout=RUN_GUARD_S)
    paths["duplex"] = pairs
    return paths


def simulated_buses(options):
    """{stem: {form: path}}: a bus of every fault class, and a SunSpec inverter beside a mapped
    one on a line that damages some replies (its model chain learned from the logger's scan in
    the first file of a cut too, its values named and scaled alike on every road)."""
    buses = {}
    for i, fault in enumerate(FAULT_CLASSES + ("all",)):
        faults = "all" if fault == "all" else f"{fault}=15"
        buses[f"sim-{fault}"] = simulated_bus(
            options, f"sim-{fault}",
            ["--seed", str(350 + i), "--dialect", "gsl,hybrid,ascii", "--inverters", "3",
             "--meter", "20", "--io-module", "21", "--faults", faults])
    buses["sim-sunspec"] = simulated_bus(
        options, "sim-sunspec",
        ["--seed", "361", "--inverters", "1", "--sunspec", "3", "--faults",
         "corrupt=10,missing=10"])
    return buses


def sample_buses(options):
    buses = {}
    for path in sorted(glob.glob(os.path.join(options.samples, "*.pcap"))):
        stem, form = os.path.basename(path).rsplit(".", 2)[:2]
        buses.setdefault(stem, {})[form] = path
    return buses


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--pvtap", required=True)
    parser.add_argument("--sim", required=True)
    parser.add_argument("--samples", required=True)
    parser.add_argument("--work", required=True)
    parser.add_argument("--only", help="only the buses whose name contains this")
    options = parser.parse_args()
    if shutil.which("editcap") is None:
        print("editcap is missing (Debian: wireshark-common)")
        return SKIP
    shutil.rmtree(options.work, ignore_errors=True)
    os.makedirs(options.work)
    report = Report()
    rng = random.Random(35)
    buses = {**sample_buses(options), **simulated_buses(options)}
    for stem, forms in sorted(buses.items()):
        if options.only and options.only not in stem:
            continue
        audited = {form: check_capture(options, report, path, rng)
                   for form, path in sorted(forms.items()) if form != "duplex"}
        if "duplex" in forms:
            audited["duplex"] = audit(options.pvtap, forms["duplex"], "--duplex")
        check_forms(options, report, stem, audited)
    for failure in report.failures:
        print("FAIL:", failure)
    print(f"{report.roads - len(report.failures)} passed, {len(report.failures)} failed")
    return 1 if report.failures else 0


if __name__ == "__main__":
    sys.exit(main())
