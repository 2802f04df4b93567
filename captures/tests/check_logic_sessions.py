#!/usr/bin/env python3
"""pvtap audit on sessions pvtap-sim --sr writes here, against their ground truth.

    check_logic_sessions.py PVTAP PVTAP_SIM SCRATCH MODE

drivers: with every DE channel named (--de), each talker's release after its frames' last stop
bit is the truth's within 3 us, over every frame it sent (per station for the master); a
station that releases half a bit before its last stop bit ends has every one of its frames
truncated, in the summary and as a finding in the text report; --de naming a channel that is
not there is refused in one line with exit 2.
channels: a bus whose directions are on two channels (the master's TX and RX) is found as one
bus without --channels, and with --channels TX,RX: every frame, the truth's requests, replies
and timeouts, the planted t3.5 violations (also where slow replies make the pauses mislead); beside the A-B channel it is a second bus (and the
driver-enable channels none), and
--channels is repeatable for both; three names in one --channels are refused in one line.
clock: every talker's clock 3 % slow is one clock deviation per bus (the A-B channel, and TX,RX),
in the summary's line and the text report's findings, its deviation_percent the simulated one;
1 % slow is none; --fail-on errors does not count them.
matrix: a line as real ones are, all at once (edges jittering 5 % of a bit, clocks 1 % slow,
drivers glitching at 30 % of their switchings, missing, slow and damaged replies, replies too
early), at 4800 8O1, 9600 8N2, 19200 8E1, 38400 8E1 and 115200 8N1, on the A-B line alone, on
the master's TX and RX, and on all of them with driver-enable channels, idling high and low:
every bus has the nominal rate, the format and the idle level; every frame whose check holds
is found, and no other good frame; the planted t3.5 violations, exactly; a damaged frame the
framing cannot tell from noise (a clean glitch byte right after it, a damaged header) is
noise, never lost.
busline: the A-B line probed where no failsafe bias holds it (--undriven space: it falls to
space at every driver's release, a start bit to a receiver, and rests there until a driver
lifts it with a short pulse), beside the master's TX and RX, over the matrix's rates and
formats and both idle levels, found alone and named with --channels A-B: the A-B bus is read
at the polarity its frames check in, never at the level it rests at, at the nominal rate
despite the pulses, and gives every good frame the truth has, as TX,RX does.
long: the same bus sampled at 1 MS/s (about 11 MB of samples, which the audit reads once and
keeps) and at 4 MS/s (about 43 MB, over what it keeps: read a second time) gives the truth's
frames, timeouts and planted t3.5 violations both ways.
Exit 0 when every check holds, 1 with the failures listed.
"""
import json
import os
import subprocess
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "tests", "support"))
from checks import Checks  # noqa: E402

COMMON = ["--dialect", "gsl", "--inverters", "3", "--duration", "15", "--period", "5"]


def simulate(sim, scratch, name, *options):
    session = os.path.join(scratch, name + ".sr")
    truth = os.path.join(scratch, name + ".truth.json")
    subprocess.run([sim, *COMMON, *options, "--sr", session, "--truth", truth], check=True)
    with open(truth, encoding="utf-8") as f:
        return session, json.load(f)


def audit(pvtap, *args):
    return subprocess.run([pvtap, "audit", *args], capture_output=True, text=True, timeout=120,
                          check=False)


def summary(result):
    lines = [l for l in result.stdout.splitlines() if l.startswith('{"type":"summary"')]
    return json.loads(lines[-1]) if lines else None


def expected_turnarounds(truth):
    """(driver channel, station) -> (release_us, frames, truncated) from the truth."""
    drivers = {e["talker"]: e for e in truth["logic_events"] if e["kind"] == "driver"}
    out = {}
    for event in truth["events"]:
        if event["type"] != "frame":
            continue
        talker = "master" if event["role"] == "request" else event["station"]
        name = "DE_M" if talker == "master" else f"DE_{talker}"
        d = drivers[talker]
        key = (name, event["station"])
        release, frames, truncated = out.get(key, (d["release_us"], 0, d["truncated"]))
        out[key] = (release, frames + 1, truncated)
    return out


def check_drivers(checks, pvtap, sim, scratch):
    session, truth = simulate(sim, scratch, "drivers", "--seed", "31", "--baud", "19200",
                              "--sr-channels", "bus,de", "--glitches", "40",
                              "--truncate-last-byte", "--jitter", "2")
    des = [c for c in truth["logic_events"][0]["channels"] if c.startswith("DE_")]
    args = ["--channels", "A-B"] + [a for d in des for a in ("--de", d)]
    result = audit(pvtap, "--format", "jsonl", *args, session)
    checks.equal("drivers: exit status", result.returncode, 0)
    s = summary(result)
    if s is None:
        checks.true(f"drivers: a summary ({result.stderr.strip()})", False)
        return
    found = {(t["driver"], t["station"]): t for t in s["buses"][0]["turnaround"]}
    expected = expected_turnarounds(truth)
    checks.equal("drivers: (channel, station) pairs", sorted(found), sorted(expected))
    bit_us = 1e6 / 19200
    for key, (release, frames, truncated) in expected.items():
        t = found.get(key)
        if t is None:
            continue
        checks.equal(f"drivers: {key} frames", t["frames"], frames)
        checks.true(f"drivers: {key} release {t['release_us']} near {release} us",
                    abs(t["release_us"]["mean"] - release) <= 3.0)
        checks.equal(f"drivers: {key} truncated", t["truncated"], frames if truncated else 0)
        if truncated:
            checks.true(f"drivers: {key} released before the stop bit ended",
                        -0.5 * bit_us - 3 <= t["release_us"]["max"] < 0)
    text = audit(pvtap, *args, session).stdout
    checks.true("drivers: the text report names the truncated last byte",
                "frames: a truncated last byte" in text)
    bad = audit(pvtap, "--channels", "A-B", "--de", "DE_9", session)
    checks.equal("drivers: --de DE_9 exit status", bad.returncode, 2)
    checks.true(f"drivers: --de DE_9 refused in one line ({bad.stderr!r})",
                bad.stderr.count("\n") == 1 and "no channel DE_9" in bad.stderr
                and bad.stdout == "")


SUMMARY_KEYS = ("frames", "requests", "responses", "timeouts", "bad_checks", "noise_bytes")


def check_bus_totals(checks, what, bus_summary, result, truth):
    if bus_summary is None:
        checks.true(f"{what}: the bus is there ({result.stderr.strip()})", False)
        return
    for key in SUMMARY_KEYS:
        checks.equal(f"{what}: {key}", bus_summary.get(key), truth["summary"][key])


def buses_of(result):
    """Each bus of the summary with its own totals, by name."""
    s = summary(result)
    if s is None:
        return {}
    out = {}
    for b in s["buses"]:
        totals = {"frames": b["frames"], "t35": b["timing"]["t35_violations"]}
        out[b["bus"]] = totals
    return out


def check_channels(checks, pvtap, sim, scratch):
    session, truth = simulate(sim, scratch, "channels", "--seed", "41", "--baud", "9600",
                              "--faults", "missing=10,slow=5", "--sr-channels", "tx,rx",
                              "--violations", "2", "--format", "8N2")
    for what, args in (("auto", ()), ("--channels TX,RX", ("--channels", "TX,RX"))):
        result = audit(pvtap, "--format", "jsonl", *args, session)
        checks.equal(f"channels {what}: exit status", result.returncode, 0)
        s = summary(result)
        checks.equal(f"channels {what}: buses", [b["bus"] for b in (s or {}).get("buses", [])],
                     ["TX,RX"])
        check_bus_totals(checks, f"channels {what}", s, result, truth)
        if s:
            checks.equal(f"channels {what}: t3.5 violations",
                         s["buses"][0]["timing"]["t35_violations"], truth["logic"]["early_replies"])
    # A slow reply in the first stretch made the mean wait for replies longer than the
    # master's between polls, and the pauses named RX the requests' channel: the frames' own
    # layouts decide.
    session, truth = simulate(sim, scratch, "slow", "--seed", "104", "--baud", "19200",
                              "--meter", "20", "--faults", "missing=10,slow=5,corrupt=5",
                              "--sr-channels", "tx,rx", "--violations", "2", "--format", "8E1")
    result = audit(pvtap, "--format", "jsonl", session)
    s = summary(result)
    checks.equal("slow replies: buses", [b["bus"] for b in (s or {}).get("buses", [])], ["TX,RX"])
    check_bus_totals(checks, "slow replies", s, result, truth)
    # The DE channels' pulses read as slow characters but never as frames: no buses.
    session, truth = simulate(sim, scratch, "both", "--seed", "42", "--baud", "9600",
                              "--sr-channels", "bus,tx,rx,de")
    frames = truth["summary"]["frames"]
    for what, args in (("auto", ()), ("repeated", ("--channels", "A-B", "--channels", "TX,RX"))):
        result = audit(pvtap, "--format", "jsonl", *args, session)
        buses = {name: b["frames"] for name, b in buses_of(result).items()}
        checks.equal(f"A-B beside TX,RX ({what}): buses and frames", buses,
                     {"A-B": frames, "TX,RX": frames})
    bad = audit(pvtap, "--channels", "TX,RX,A-B", session)
    checks.equal("three names: exit status", bad.returncode, 2)
    checks.true(f"three names refused in one line ({bad.stderr!r})",
                bad.stderr.count("\n") == 1 and bad.stdout == "")


def check_clock(checks, pvtap, sim, scratch):
    """A clock 3 % slow is one finding per bus (A-B and TX,RX); 1 % off is none."""
    for pct, expected in ((3, 1), (1, 0)):
        session, truth = simulate(sim, scratch, f"clock{pct}", "--seed", "51", "--baud", "9600",
                                  "--sr-channels", "bus,tx,rx", "--clock-deviation", str(pct))
        result = audit(pvtap, "--format", "jsonl", "--fail-on", "errors", session)
        # Like the t3.5 violations and the driver glitches, no error of a frame: exit 0.
        checks.equal(f"clock {pct} %: exit status with --fail-on errors", result.returncode, 0)
        s = summary(result) or {"buses": []}
        checks.equal(f"clock {pct} %: buses", sorted(b["bus"] for b in s["buses"]),
                     ["A-B", "TX,RX"])
        # The bits last 1 + pct/100 times as long: the rate is 1 / (1 + pct/100) of 9600.
        deviation = (1 / (1 + pct / 100) - 1) * 100
        for b in s["buses"]:
            checks.true(f"clock {pct} %: {b['bus']} deviation {b['serial']['deviation_percent']}"
                        f" near {deviation:.2f}",
                        abs(b["serial"]["deviation_percent"] - deviation) <= 0.05)
            checks.equal(f"clock {pct} %: {b['bus']} clock deviations",
                         b["line"]["clock_deviations"], expected)
            checks.equal(f"clock {pct} %: {b['bus']} frames", b["frames"],
                         truth["summary"]["frames"])
        text = audit(pvtap, session).stdout
        checks.true(f"clock {pct} %: the findings line counts {2 * expected}",
                    f"exceptions and error replies, {2 * expected} clock deviations over 2 %"
                    in text)
        checks.equal(f"clock {pct} %: lines naming the deviation",
                     text.count("clock deviation: the rate is"), 2 * expected)


MATRIX_LINES = (("4800", "8O1"), ("9600", "8N2"), ("19200", "8E1"), ("38400", "8E1"),
                ("115200", "8N1"))
MATRIX_CHANNELS = ("bus", "tx,rx", "bus,tx,rx,de")
FORMATS = {"8N1": ("none", 1), "8N2": ("none", 2), "8E1": ("even", 1), "8O1": ("odd", 1)}


def check_matrix_bus(checks, what, bus, rows, truth, baud, fmt, inverted):
    serial = bus.get("serial", {})
    checks.equal(f"{what}: line", (serial.get("baud"), serial.get("parity"),
                                   serial.get("stop_bits"), serial.get("inverted")),
                 (int(baud), *FORMATS[fmt], inverted))
    good = sorted(e["hex"] for e in truth["events"] if e["type"] == "frame" and e["check"] == "ok")
    found = sorted(r["raw"] for r in rows if r["type"] == "frame" and r["check"] == "ok")
    checks.equal(f"{what}: good frames", found, good)
    damaged = [e["hex"] for e in truth["events"] if e["type"] == "frame" and e["check"] != "ok"]
    shown = "".join(r["raw"] for r in rows if r["type"] in ("frame", "noise"))
    missing = [h for h in damaged if h not in shown]
    checks.equal(f"{what}: damaged frames as frames or noise", missing, [])
    checks.equal(f"{what}: t3.5 violations", bus["timing"]["t35_violations"],
                 truth["logic"]["early_replies"])


def check_matrix(checks, pvtap, sim, scratch):
    seed = 100
    for baud, fmt in MATRIX_LINES:
        rate = "1000000" if int(baud) <= 19200 else "4000000"
        for channels in MATRIX_CHANNELS:
            for inverted in (False, True):
                seed += 1
                what = f"{baud} {fmt} {channels}{' inverted' if inverted else ''}"
                session, truth = simulate(
                    sim, scratch, "matrix", "--seed", str(seed), "--meter", "20", "--baud", baud,
                    "--format", fmt, "--samplerate", rate, "--sr-channels", channels,
                    "--faults", "missing=10,slow=5,corrupt=5", "--glitches", "30",
                    "--violations", "2", "--jitter", "5", "--clock-deviation", "1",
                    *(("--inverted",) if inverted else ()))
                result = audit(pvtap, "--format", "jsonl", session)
                rows = [json.loads(l) for l in result.stdout.splitlines()]
                s = summary(result) or {"buses": []}
                expected = {"bus": ["A-B"], "tx,rx": ["TX,RX"], "bus,tx,rx,de": ["A-B", "TX,RX"]}
                checks.equal(f"{what}: buses", [b["bus"] for b in s["buses"]], expected[channels])
                for bus in s["buses"]:
                    check_matrix_bus(checks, f"{what}: {bus['bus']}", bus,
                                     [r for r in rows if r.get("bus") == bus["bus"]], truth, baud,
                                     fmt, inverted)


def check_busline(checks, pvtap, sim, scratch):
    """A-B probed on a line without failsafe bias: the polarity its frames check in."""
    seed = 200
    for baud, fmt in MATRIX_LINES:
        rate = "1000000" if int(baud) <= 19200 else "4000000"
        for inverted in (False, True):
            seed += 1
            what = f"bus line {baud} {fmt}{' inverted' if inverted else ''}"
            session, truth = simulate(
                sim, scratch, "busline", "--seed", str(seed), "--meter", "20", "--baud", baud,
                "--format", fmt, "--samplerate", rate, "--sr-channels", "bus,tx,rx",
                "--undriven", "space", "--faults", "missing=10,slow=5,corrupt=5",
                "--violations", "2", "--jitter", "5", "--clock-deviation", "1",
                *(("--inverted",) if inverted else ()))
            # Without --channels a frameless A-B beside TX,RX was no bus at all; named, it was
            # read at the level it rests at: no frame, its bytes noise.
            for args, buses in (((), ["A-B", "TX,RX"]), (("--channels", "A-B"), ["A-B"])):
                result = audit(pvtap, "--format", "jsonl", *args, session)
                rows = [json.loads(l) for l in result.stdout.splitlines()]
                s = summary(result) or {"buses": []}
                named = f"{what}{' ' if args else ''}{' '.join(args)}"
                checks.equal(f"{named}: buses", [b["bus"] for b in s["buses"]], buses)
                for bus in s["buses"]:
                    check_matrix_bus(checks, f"{named}: {bus['bus']}", bus,
                                     [r for r in rows if r.get("bus") == bus["bus"]], truth, baud,
                                     fmt, inverted)


def check_long(checks, pvtap, sim, scratch):
    """A recording kept from the probe's reading and one read twice decode alike."""
    for rate in ("1000000", "4000000"):
        session, truth = simulate(sim, scratch, f"rate{rate}", "--seed", "61", "--baud", "9600",
                                  "--faults", "missing=10", "--violations", "3",
                                  "--samplerate", rate)
        result = audit(pvtap, "--format", "jsonl", session)
        checks.equal(f"{rate} samples/s: exit status", result.returncode, 0)
        s = summary(result)
        check_bus_totals(checks, f"{rate} samples/s", s, result, truth)
        if s:
            checks.equal(f"{rate} samples/s: t3.5 violations",
                         s["buses"][0]["timing"]["t35_violations"], truth["logic"]["early_replies"])


def main():
    pvtap, sim, scratch, mode = sys.argv[1:5]
    os.makedirs(scratch, exist_ok=True)
    checks = Checks()
    modes = {"drivers": check_drivers, "channels": check_channels, "clock": check_clock,
             "long": check_long, "matrix": check_matrix, "busline": check_busline}
    modes[mode](checks, pvtap, sim, scratch)
    return checks.finish()


if __name__ == "__main__":
    sys.exit(main())
