#!/usr/bin/env python3
"""Several capture files are one capture, whatever order they are given in.

For every sample capture (and the real taps when their folder is given): the capture cut into
2 to 5 files given in a shuffled order, its records dealt alternately into two files that
overlap in time, and the capture converted to pcapng give the same output, event for event
and in the summary, as the capture whole (only the summary's list of inputs differs). Then
the bad mixes: the same file twice, and two copies that overlap, are refused with one line
naming both files; a clock stepping back inside a file is a finding and no latency runs
backwards; a truncated file and a missing file among good ones are named, the other files are
read, and the exit status is 2.

Usage: check_several_files.py --pvtap PVTAP --samples DIR [--real DIR]
"""

import argparse
import glob
import json
import os
import random
import shutil
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "support"))
from checks import Checks  # noqa: E402
from pcap_records import read_pcap  # noqa: E402

RUN_GUARD_S = 120  # a guard against a hung run, not a timing check
SKIP = 77


def audit(pvtap, files, *extra):
    return subprocess.run([pvtap, "audit", "--format", "jsonl", *extra, *files],
                          capture_output=True, text=True, timeout=RUN_GUARD_S)


def lines_of(stdout):
    return [json.loads(line) for line in stdout.splitlines() if line.strip()]


def without_inputs(lines):
    out = []
    for line in lines:
        if line.get("type") == "summary":
            line = {k: v for k, v in line.items() if k != "inputs"}
        out.append(line)
    return out


def first_difference(a, b):
    for i, (x, y) in enumerate(zip(a, b)):
        if x != y:
            return f"line {i + 1}: {json.dumps(x)[:300]} != {json.dumps(y)[:300]}"
    return f"{len(a)} lines != {len(b)} lines"


def same_output(checks, what, whole, result):
    checks.equal(f"{what}: exit status", result.returncode, 0)
    checks.equal(f"{what}: stderr", result.stderr, "")
    got = without_inputs(lines_of(result.stdout))
    if got != whole:
        checks.true(f"{what}: the same output as the capture whole ({first_difference(whole, got)})",
                    False)


def cut(pcap, parts):
    """The records in `parts` consecutive runs of nearly equal size."""
    n = len(pcap.records)
    bounds = [round(i * n / parts) for i in range(parts + 1)]
    return [pcap.records[bounds[i]:bounds[i + 1]] for i in range(parts)]


def strictly_increasing(pcap):
    times = [pcap.time(r) for r in pcap.records]
    return all(a < b for a, b in zip(times, times[1:]))


def check_orders(options, checks, capture, whole, work, rng):
    name = os.path.basename(capture)
    pcap = read_pcap(capture)
    parts = rng.randint(2, min(5, max(2, len(pcap.records))))
    files = []
    for i, records in enumerate(cut(pcap, parts)):
        path = os.path.join(work, f"part{i}.pcap")
        pcap.write(path, records)
        files.append(path)
    shuffled = files[:]
    while len(shuffled) > 1 and shuffled == files:
        rng.shuffle(shuffled)
    order = ",".join(os.path.basename(f) for f in shuffled)
    result = audit(options.pvtap, shuffled)
    same_output(checks, f"{name} cut into {parts} files given as {order}", whole, result)
    inputs = lines_of(result.stdout)[-1].get("inputs", []) if result.stdout else []
    checks.equal(f"{name}: the report lists the files in the order read",
                 [i["path"] for i in inputs], files)
    if strictly_increasing(pcap):
        dealt = [os.path.join(work, "odd.pcap"), os.path.join(work, "even.pcap")]
        pcap.write(dealt[0], pcap.records[1::2])
        pcap.write(dealt[1], pcap.records[0::2])
        same_output(checks, f"{name} dealt alternately into two files", whole,
                    audit(options.pvtap, dealt))
    pcapng = os.path.join(work, "whole.pcapng")
    converted = subprocess.run(["editcap", "-F", "pcapng", capture, pcapng],
                               capture_output=True, text=True, timeout=RUN_GUARD_S)
    checks.equal(f"{name}: editcap converts it to pcapng", converted.returncode, 0)
    same_output(checks, f"{name} as pcapng", whole, audit(options.pvtap, [pcapng]))


def expect_refusal(checks, what, result, names):
    checks.equal(f"{what}: exit status", result.returncode, 2)
    lines = result.stderr.strip().splitlines()
    checks.equal(f"{what}: one line on stderr ({result.stderr.strip()!r})", len(lines), 1)
    for n in names:
        checks.true(f"{what}: the line names {n}", bool(lines) and n in lines[-1])
    checks.true(f"{what}: the line says the records repeat",
                bool(lines) and "the same records" in lines[-1])


def check_repeats(options, checks, capture, work):
    name = os.path.basename(capture)
    pcap = read_pcap(capture)
    copy = os.path.join(work, "copy.pcap")
    shutil.copy(capture, copy)
    twice = audit(options.pvtap, [capture, capture])
    expect_refusal(checks, f"{name} given twice", twice, [name])
    checks.equal(f"{name} given twice: nothing on stdout", twice.stdout, "")
    expect_refusal(checks, f"{name} and its copy", audit(options.pvtap, [copy, capture]),
                   [name, "copy.pcap"])
    n = len(pcap.records)
    early, late = os.path.join(work, "early.pcap"), os.path.join(work, "late.pcap")
    pcap.write(early, pcap.records[:n * 3 // 5])
    pcap.write(late, pcap.records[n * 2 // 5:])
    expect_refusal(checks, f"{name} in two copies that overlap",
                   audit(options.pvtap, [late, early]), ["early.pcap", "late.pcap"])


def check_clock_step(options, checks, capture, whole, work):
    """The second half of the records 1000 s earlier: one step back, found where it is, and
    no latency below zero."""
    name = os.path.basename(capture)
    pcap = read_pcap(capture)
    middle = len(pcap.records) // 2
    stepped = os.path.join(work, "stepped.pcap")
    pcap.write(stepped, pcap.records[:middle] +
               [pcap.shifted(r, -1000) for r in pcap.records[middle:]])
    result = audit(options.pvtap, [stepped])
    checks.equal(f"{name} with a step back: exit status", result.returncode, 0)
    lines = lines_of(result.stdout)
    if not lines:
        return
    inputs = lines[-1].get("inputs", [{}])
    checks.equal(f"{name} with a step back: steps counted", inputs[0].get("clock_steps_back"), 1)
    checks.equal(f"{name} with a step back: where", inputs[0].get("first_step_back_record"),
                 middle + 1)
    negative = [l for l in lines if l.get("type") != "summary" and (l.get("latency_ms") or 0) < 0]
    checks.equal(f"{name} with a step back: latencies below zero", len(negative), 0)
    checks.true(f"{name} with a step back: the summary's shortest latency is not below zero",
                (lines[-1]["latency_ms"].get("min") or 0) >= 0)
    # The silence at the step is not known (it reads as none): only the frames on either
    # side of it may be read otherwise; every byte is still counted.
    checks.equal(f"{name} with a step back: bytes", lines[-1]["bytes"], whole[-1]["bytes"])
    checks.true(f"{name} with a step back: frames {lines[-1]['frames']} of "
                f"{whole[-1]['frames']}", abs(lines[-1]["frames"] - whole[-1]["frames"]) <= 2)


def check_damaged_mix(options, checks, capture, work):
    name = os.path.basename(capture)
    pcap = read_pcap(capture)
    first, second = cut(pcap, 2)
    good, cut_file = os.path.join(work, "good.pcap"), os.path.join(work, "cut.pcap")
    pcap.write(good, second)
    pcap.write(cut_file, first)
    with open(cut_file, "rb") as f:
        data = f.read()
    with open(cut_file, "wb") as f:
        f.write(data[:len(data) - len(first[-1].data) // 2 - 1])  # inside the last record
    alone = lines_of(audit(options.pvtap, [good]).stdout)
    result = audit(options.pvtap, [good, cut_file])
    checks.equal(f"{name}: truncated file among good ones: exit status", result.returncode, 2)
    lines = result.stderr.strip().splitlines()
    checks.equal(f"{name}: truncated file: one line on stderr ({result.stderr.strip()!r})",
                 len(lines), 1)
    checks.true(f"{name}: the line names the truncated file",
                bool(lines) and "cut.pcap" in lines[0] and "truncated" in lines[0])
    got = lines_of(result.stdout)
    if got and alone:
        checks.true(f"{name}: the good file after the truncated one is read",
                    got[-1]["frames"] > alone[-1]["frames"] or not first)
        checks.equal(f"{name}: both files listed", len(got[-1].get("inputs", [])), 2)
    missing = os.path.join(work, "missing.pcap")
    result = audit(options.pvtap, [missing, good])
    checks.equal(f"{name}: a missing file among good ones: exit status", result.returncode, 2)
    lines = result.stderr.strip().splitlines()
    checks.true(f"{name}: one line names the missing file ({result.stderr.strip()!r})",
                len(lines) == 1 and "missing.pcap" in lines[0])
    got = lines_of(result.stdout)
    if got and alone:
        checks.equal(f"{name}: the good file is read beside the missing one",
                     without_inputs(got), without_inputs(alone))


def captures(options):
    found = sorted(glob.glob(os.path.join(options.samples, "*.pcap")))
    if options.real and os.path.isdir(options.real):
        found += sorted(glob.glob(os.path.join(options.real, "*.pcap")))
    return found


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--pvtap", required=True)
    parser.add_argument("--samples", required=True)
    parser.add_argument("--real")
    options = parser.parse_args()
    if shutil.which("editcap") is None:
        print("editcap is missing (Debian: wireshark-common)")
        return SKIP
    checks = Checks()
    rng = random.Random(35)
    files = captures(options)
    checks.true("sample captures found", len(files) > 10)
    for capture in files:
        work = tempfile.mkdtemp(prefix="pvtap-several-")
        try:
            whole_run = audit(options.pvtap, [capture])
            checks.equal(f"{os.path.basename(capture)} whole: exit status",
                         whole_run.returncode, 0)
            whole = without_inputs(lines_of(whole_run.stdout))
            if not whole:
                continue
            check_orders(options, checks, capture, whole, work, rng)
            check_repeats(options, checks, capture, work)
            check_clock_step(options, checks, capture, whole, work)
            check_damaged_mix(options, checks, capture, work)
        finally:
            shutil.rmtree(work, ignore_errors=True)
    return checks.finish()


if __name__ == "__main__":
    sys.exit(main())
