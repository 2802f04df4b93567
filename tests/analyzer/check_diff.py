#!/usr/bin/env python3
"""`pvtap diff BEFORE AFTER` (issue 38, item 8): the bus before and after a fix. pvtap-sim
writes the same bus (plan and seed) twice: before, with the line damaging replies (a missing
terminator's reflections: bad checks), and after, clean. The diff names the bad checks of
exactly the stations the simulator damaged and no other counted difference, and exits 1; each
register range move it reports (not counted by default) is one the ground truth shows; text
and jsonl carry the same differences; the HTML page is written. A capture against itself exits
0 with no difference; a vanished station is named; a damaged or unreadable side exits 2 with a
`pvtap:` line.

Usage: check_diff.py PVTAP PVTAP_SIM WORK_DIR
"""
import json
import os
import re
import subprocess
import sys
from collections import Counter

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "support"))
from checks import Checks  # noqa: E402

RUN_GUARD_S = 60
PLAN = ["--dialect", "gsl", "--meter", "10", "--duration", "300", "--seed", "7"]
DAMAGE = "corrupt=15"  # replies damaged on the line, as reflections do


def run(*args):
    return subprocess.run(list(args), capture_output=True, text=True, timeout=RUN_GUARD_S)


def simulate(sim, path, faults, inverters=3):
    truth = path + ".truth.json"
    result = run(sim, *PLAN, "--inverters", str(inverters), "--faults", faults, "--pdu", path,
                 "--truth", truth)
    if result.returncode != 0:
        sys.exit("pvtap-sim failed: " + result.stderr)
    with open(truth, encoding="utf-8") as f:
        return json.load(f)


def jsonl(text):
    return [json.loads(line) for line in text.splitlines() if line.strip()]


def truth_ranges(truth):
    """{(station, GSL register ID): (min, max)} of the good replies' raw values."""
    ranges = {}
    for event in truth["events"]:
        if event.get("type") != "frame" or event.get("check") != "ok":
            continue
        for value in event.get("values", []):
            if "raw" not in value:
                continue
            key = (event["station"], value["register"])
            low, high = ranges.get(key, (value["raw"], value["raw"]))
            ranges[key] = (min(low, value["raw"]), max(high, value["raw"]))
    return ranges


def text_difference_lines(text):
    """The lines of the text output that name a difference: indented under their bus or
    station ("    bad checks per 1000 frames: 86.79 -> 0.00 ..."), station headings aside."""
    return [line for line in text.splitlines()
            if line.startswith("  ") and not re.fullmatch(r"  station \d+", line)]


def check_fix(checks, pvtap, before, after, truth_before, truth_after, html):
    damaged = Counter(f["station"] for f in truth_before["faults"] if f["kind"] == "corrupt")
    checks.true("the simulator damaged replies of several stations", len(damaged) >= 2)

    text = run(pvtap, "diff", "--html", html, before, after)
    checks.equal("diff before after: exit status", text.returncode, 1)
    checks.equal("diff before after: nothing on stderr", text.stderr, "")
    data = run(pvtap, "diff", "--format", "jsonl", before, after)
    checks.equal("diff --format jsonl: exit status", data.returncode, 1)
    lines = jsonl(data.stdout)
    differences = [d for d in lines if d["type"] == "difference"]
    summary = lines[-1]
    checks.equal("jsonl ends with the summary", summary["type"], "summary")

    counted = sorted((d["bus"], -1 if d["station"] is None else d["station"], d["what"])
                     for d in differences if d["counted"])
    expected = sorted(("serial", station, "bad_checks_per_1000_frames") for station in damaged)
    checks.equal("the counted differences are the damaged stations' bad checks", counted,
                  expected)
    checks.equal("the summary counts them", summary["differences"], len(expected))
    for d in differences:
        if d["what"] == "bad_checks_per_1000_frames":
            checks.true("station %s: bad checks go from some to none" % d["station"],
                        d["before"] > 0 and d["after"] == 0)

    # A register range move (reported, not counted) must be one the simulator's values show.
    ranges_before, ranges_after = truth_ranges(truth_before), truth_ranges(truth_after)
    for d in differences:
        if d["counted"]:
            continue
        checks.equal("an uncounted difference is a register move", d["what"], "register_range")
        address = re.match(r"gsl 0x([0-9A-F]{4})", d["detail"])
        if d["station"] == 10 or address is None:
            continue  # the meter's registers are not GSL IDs
        key = (d["station"], str(int(address.group(1), 16)))
        low, high = ranges_before.get(key, (None, None))
        after_low, after_high = ranges_after.get(key, (None, None))
        checks.true("register %s of station %s moved in the ground truth" % key,
                    low is not None and after_low is not None and
                    (after_low < low or after_high > high))
    checks.equal("text names as many differences as jsonl",
                  len(text_difference_lines(text.stdout)), len(differences))
    for station in damaged:
        checks.true("text names station %d" % station,
                    re.search(r"^  station %d\n    bad checks per 1000 frames: " % station,
                              text.stdout, re.MULTILINE) is not None)
    checks.true("text says how many differences",
                "%d differences beyond the noise of sampling" % len(expected) in text.stdout)

    strict = run(pvtap, "diff", "--format", "jsonl", "--count-values", before, after)
    moves = sum(1 for d in differences if d["what"] == "register_range")
    checks.equal("--count-values counts the register moves too",
                  jsonl(strict.stdout)[-1]["differences"], len(expected) + moves)

    checks.true("the HTML page is written", os.path.getsize(html) > 0)
    with open(html, encoding="utf-8") as f:
        page = f.read()
    checks.true("the page is one HTML document", page.startswith("<!DOCTYPE html>"))
    checks.equal("the page has a row per difference", page.count("<tr><td>"), len(differences))


# The threshold options and the summary's names for them.
THRESHOLDS = {"--noise-sigmas": "noise_sigmas", "--rate-change": "rate_per_1000",
              "--rate-percent": "rate_percent", "--requests-percent": "requests_percent",
              "--latency-ms": "latency_ms", "--latency-percent": "latency_percent",
              "--period-ms": "period_ms", "--period-percent": "period_percent",
              "--jitter-ms": "jitter_ms", "--jitter-percent": "jitter_percent",
              "--value-percent": "value_percent"}


def check_thresholds(checks, pvtap, capture):
    """The defaults --help states are the ones a run applies (the jsonl summary's). CLI11
    writes a default as NAME=3 up to 2.3 (Debian 12) and as NAME [3] from 2.4 (Debian 13)."""
    help_text = run(pvtap, "diff", "--help").stdout
    applied = jsonl(run(pvtap, "diff", "--format", "jsonl", capture, capture).stdout)[-1]
    for option, key in THRESHOLDS.items():
        stated = re.search(r"^ +%s [A-Z_0-9]+(?:=| \[)([0-9.]+)" % re.escape(option), help_text,
                           re.MULTILINE)
        checks.true("--help states the default of " + option, stated is not None)
        if stated:
            checks.equal("the default of %s as applied" % option,
                         applied["thresholds"][key], float(stated.group(1)))


def check_same(checks, pvtap, capture):
    text = run(pvtap, "diff", capture, capture)
    checks.equal("a capture against itself: exit status", text.returncode, 0)
    checks.equal("a capture against itself: no difference lines",
                  text_difference_lines(text.stdout), [])
    checks.true("a capture against itself: says so",
                "no differences beyond the noise of sampling" in text.stdout)
    data = jsonl(run(pvtap, "diff", "--format", "jsonl", capture, capture).stdout)
    checks.equal("a capture against itself: jsonl holds the summary alone",
                 [d["type"] for d in data], ["summary"])


def check_vanished(checks, pvtap, before, fewer):
    data = run(pvtap, "diff", "--format", "jsonl", before, fewer)
    checks.equal("a station gone: exit status", data.returncode, 1)
    named = [(d["station"], d["what"], d["before"], d["after"]) for d in jsonl(data.stdout)
             if d["type"] == "difference" and d["what"] == "station"]
    checks.equal("a station gone: the one station named", [(s, w) for s, w, _, _ in named],
                 [(3, "station")])
    checks.true("a station gone: it had frames before and none after",
                bool(named) and named[0][2] > 0 and named[0][3] is None)


def check_errors(checks, pvtap, capture, work):
    truncated = os.path.join(work, "truncated.pcap")
    with open(capture, "rb") as f:
        data = f.read()
    with open(truncated, "wb") as f:
        f.write(data[: len(data) // 2 + 7])
    not_capture = os.path.join(work, "notes.txt")
    with open(not_capture, "w", encoding="utf-8") as f:
        f.write("not a capture\n")
    for what, before, after in (
            ("a damaged side", truncated, capture),
            ("a missing side", capture, os.path.join(work, "missing.pcap")),
            ("a side that is no capture", not_capture, capture)):
        result = run(pvtap, "diff", before, after)
        checks.equal(what + ": exit status", result.returncode, 2)
        checks.true(what + ": a pvtap: line on stderr",
                    re.search(r"^pvtap: ", result.stderr, re.MULTILINE) is not None)
        checks.equal(what + ": no differences on stdout", result.stdout, "")


def main():
    pvtap, sim, work = sys.argv[1], sys.argv[2], sys.argv[3]
    os.makedirs(work, exist_ok=True)
    before = os.path.join(work, "before.pcap")
    after = os.path.join(work, "after.pcap")
    fewer = os.path.join(work, "fewer.pcap")
    truth_before = simulate(sim, before, DAMAGE)
    truth_after = simulate(sim, after, "none")
    simulate(sim, fewer, DAMAGE, inverters=2)
    checks = Checks()
    check_fix(checks, pvtap, before, after, truth_before, truth_after,
              os.path.join(work, "diff.html"))
    check_same(checks, pvtap, before)
    check_thresholds(checks, pvtap, before)
    check_vanished(checks, pvtap, before, fewer)
    check_errors(checks, pvtap, before, work)
    return checks.finish()


if __name__ == "__main__":
    sys.exit(main())
