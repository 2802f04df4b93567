#!/usr/bin/env python3
"""The logic-session sample (pvtap-sim --sr) against its ground truth.

    check_logic_sample.py PVTAP SESSION TRUTH

sigrok-cli reads the session's channels and sample count as the truth gives them. pvtap audit
of the A-B channel finds every frame of the truth (bytes, role, check, start time within a bit
and the jitter), the summary's totals, the line's settings (the format, the clock's
deviation), one framing error per switch-on glitch, every glitch byte as a driver_glitch at
its time with its value and switching (none of them noise, none inside a frame), and
exactly the planted t1.5 and t3.5 violations. The TX channel carries every request, the RX
channel every reply. Exit 0 when every check holds, 1 with the failures listed.
"""
import json
import os
import shutil
import subprocess
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "tests", "support"))
from checks import Checks  # noqa: E402

SUMMARY_KEYS = ("frames", "requests", "responses", "bad_checks", "timeouts", "damaged_replies",
                "exceptions")


def audit(pvtap, session, channel):
    run = subprocess.run([pvtap, "audit", "--format", "jsonl", "--channels", channel, session],
                         capture_output=True, text=True, timeout=120, check=False)
    if run.returncode != 0:
        sys.exit(f"pvtap audit --channels {channel} exited {run.returncode}: {run.stderr.strip()}")
    return [json.loads(line) for line in run.stdout.splitlines() if line.strip()]


def check_sigrok(checks, session, info):
    if not shutil.which("sigrok-cli"):
        print("sigrok-cli missing: the session's reading by sigrok is not checked")
        return
    show = subprocess.run(["sigrok-cli", "-i", session, "--show"], capture_output=True,
                          text=True, timeout=60, check=False).stdout
    names = [line[2:].split(":")[0] for line in show.splitlines() if line.startswith("- ")]
    checks.equal("sigrok-cli: channels", names, info["channels"])
    checks.true(f"sigrok-cli: sample count {info['samples']} in {show!r}",
                f"Logic sample count: {info['samples']}" in show)


def check_frames(checks, rows, truth, info):
    frames = [r for r in rows if r["type"] == "frame"]
    expected = [e for e in truth["events"] if e["type"] == "frame"]
    checks.equal("A-B: frames",
                 [(f["role"], f["check"], f["raw"]) for f in frames],
                 [(e["role"], e["check"], e["hex"]) for e in expected])
    # A frame's time is its first start bit's edge, on the session's clock.
    bit = 1.0 / info["baud"] * (1 + info["clock_deviation_pct"] / 100)
    slack = bit * (0.1 + info["jitter_pct"] / 100) + 2.0 / info["sample_rate"]
    for f, e in zip(frames, expected):
        offset = abs(f["ts"] - (e["ts"] - info["ts"]))
        checks.true(f"A-B: frame at {f['ts']} is {offset * 1e6:.1f} us off its truth",
                    offset <= slack)


def check_glitches(checks, rows, truth, info):
    """Every glitch byte found where the truth put it, none of them in a frame or noise."""
    found = sorted((r["ts"], r["raw"], r["switching"]) for r in rows
                   if r["type"] == "driver_glitch")
    expected = [(e["ts"] - info["ts"], e["value"], e["switching"])
                for e in truth["logic_events"] if e["kind"] == "driver_glitch"]
    checks.equal("A-B: driver glitches (value, switching)", [f[1:] for f in found],
                 [e[1:] for e in expected])
    bit = 1.0 / info["baud"]
    for f, e in zip(found, expected):
        checks.true(f"A-B: glitch at {f[0]} is {abs(f[0] - e[0]) * 1e6:.1f} us off its truth",
                    abs(f[0] - e[0]) <= 0.2 * bit + 2.0 / info["sample_rate"])
    line = rows[-1]["buses"][0]["line"]
    checks.equal("A-B: summary line.driver_glitches", line["driver_glitches"],
                 truth["logic"]["driver_glitches"])


def check_bus(checks, pvtap, session, truth):
    info = truth["logic_events"][0]
    counts = truth["logic"]
    rows = audit(pvtap, session, "A-B")
    summary = rows[-1]
    for key in SUMMARY_KEYS:
        checks.equal(f"A-B: summary {key}", summary[key], truth["summary"][key])
    check_frames(checks, rows, truth, info)
    checks.equal("A-B: noise bytes", summary["noise_bytes"], 0)
    check_glitches(checks, rows, truth, info)
    bus = summary["buses"][0]
    serial, line, timing = bus["serial"], bus["line"], bus["timing"]
    checks.equal("A-B: baud", serial["baud"], info["baud"])
    checks.equal("A-B: format", (serial["data_bits"], serial["parity"], serial["stop_bits"]),
                 (8, "even", 1))
    slow = 100 / (1 + info["clock_deviation_pct"] / 100) - 100
    checks.true(f"A-B: deviation {serial['deviation_percent']} % near {slow:.2f} %",
                abs(serial["deviation_percent"] - slow) < 0.3)
    checks.equal("A-B: framing errors (switch-on glitches)", line["framing_errors"],
                 counts["switch_on_glitches"])
    checks.equal("A-B: t1.5 violations", timing["t15_violations"], counts["pauses_in_frames"])
    checks.equal("A-B: t3.5 violations", timing["t35_violations"], counts["early_replies"])


def check_directions(checks, pvtap, session, truth):
    for channel, role, key in (("TX", "request", "requests"), ("RX", "response", "responses")):
        rows = audit(pvtap, session, channel)
        raws = [r["raw"] for r in rows if r["type"] == "frame"]
        expected = [e["hex"] for e in truth["events"] if e["type"] == "frame" and e["role"] == role]
        checks.equal(f"{channel}: frames", raws, expected)
        checks.equal(f"{channel}: {key}", rows[-1][key], truth["summary"][key])
        checks.equal(f"{channel}: noise bytes", rows[-1]["noise_bytes"], 0)


def main():
    pvtap, session, truth_path = sys.argv[1:4]
    with open(truth_path, encoding="utf-8") as f:
        truth = json.load(f)
    checks = Checks()
    check_sigrok(checks, session, truth["logic_events"][0])
    check_bus(checks, pvtap, session, truth)
    check_directions(checks, pvtap, session, truth)
    return checks.finish()


if __name__ == "__main__":
    sys.exit(main())
