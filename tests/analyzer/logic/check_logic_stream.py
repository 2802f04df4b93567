#!/usr/bin/env python3
"""End-to-end checks of `pvtap sniff --logic -` on a live stream of logic samples.

    check_logic_stream.py --pvtap PVTAP --real DIR MODE

sessions: each real flow-meter session streamed by `sigrok-cli -i SESSION -O binary` into
pvtap sniff gives the frames its source counts, and the same frames (bytes and sample-clock
times), serial line and timing section as `pvtap audit SESSION`. bad_inputs: a missing
--samplerate or --channels, a rate that is no number, channels without UART traffic, --baud
auto (a serial tap's search): one line on stderr, exit 2. Exit 77 when sigrok-cli or the sessions are
missing.
"""

import argparse
import json
import os
import shutil
import subprocess
import sys

from check_logic_audit import SESSIONS, SKIP, Checks

# sigrok-cli --show names the sessions' eight channels so; the Modbus line is RXTX (bit 2).
CHANNELS = "0,1,RXTX,3,4,5,6,7"
RATE = "4M"
GUARD_S = 120  # a guard against hangs, not a timing requirement


def stream(pvtap, session, *args):
    """`sigrok-cli -i session -O binary | pvtap sniff --logic - args`: pvtap's run."""
    sigrok = subprocess.Popen(["sigrok-cli", "-i", session, "-O", "binary"],
                              stdout=subprocess.PIPE)
    run = subprocess.run([pvtap, "sniff", "--logic", "-", *args], stdin=sigrok.stdout,
                         capture_output=True, text=True, timeout=GUARD_S, check=False)
    sigrok.stdout.close()
    sigrok.wait(GUARD_S)
    return run


def jsonl(text):
    return [json.loads(line) for line in text.splitlines() if line.strip()]


def frames(events):
    return [(e["ts"], e["raw"], e["check"]) for e in events if e["type"] == "frame"]


def check_sessions(args, checks):
    for name, expected in SESSIONS.items():
        session = os.path.join(args.real, "sigrok", name)
        audit = subprocess.run([args.pvtap, "audit", "--format", "jsonl", session],
                               capture_output=True, text=True, timeout=GUARD_S, check=False)
        live = stream(args.pvtap, session, "--samplerate", RATE, "--channels", CHANNELS,
                      "--format", "jsonl")
        checks.equal(f"{name}: exit status", live.returncode, 0)
        checks.equal(f"{name}: stderr", live.stderr, "")
        if audit.returncode != 0 or live.returncode != 0:
            checks.true(f"{name}: audit exit {audit.returncode}: {audit.stderr}",
                        audit.returncode == 0)
            continue
        audited, streamed = jsonl(audit.stdout), jsonl(live.stdout)
        checks.equal(f"{name}: frames", len(frames(streamed)), expected)
        checks.true(f"{name}: the stream's frames differ from the audit's",
                    frames(streamed) == frames(audited))
        bus_a, bus_s = audited[-1]["buses"][0], streamed[-1]["buses"][0]
        checks.equal(f"{name}: serial line", bus_s.get("serial"), bus_a.get("serial"))
        checks.equal(f"{name}: timing", bus_s.get("timing"), bus_a.get("timing"))


def check_bad_inputs(args, checks):
    session = os.path.join(args.real, "sigrok", "flowmeter_flowmeter_graph_tool.sr")
    cases = (
        (["--channels", CHANNELS], "--logic needs --samplerate"),
        (["--samplerate", RATE], "--logic needs --channels"),
        (["--samplerate", "fast", "--channels", CHANNELS], "--samplerate fast"),
        (["--samplerate", RATE, "--channels", "0,1"], "no channel carries UART traffic"),
        (["--samplerate", RATE, "--channels", CHANNELS, "--baud", "auto"], "--baud auto"),
    )
    for extra, words in cases:
        run = stream(args.pvtap, session, *extra)
        lines = run.stderr.strip().splitlines()
        checks.equal(f"{extra}: exit status", run.returncode, 2)
        checks.true(f"{extra}: stderr {run.stderr!r} lacks {words!r}",
                    len(lines) == 1 and words in lines[0])
        checks.equal(f"{extra}: stdout", run.stdout, "")


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--pvtap", required=True)
    parser.add_argument("--real", required=True)
    parser.add_argument("mode", choices=["sessions", "bad_inputs"])
    args = parser.parse_args()
    if not shutil.which("sigrok-cli") or not os.path.isdir(os.path.join(args.real, "sigrok")):
        print("sigrok-cli or the real sessions are missing")
        return SKIP
    checks = Checks()
    {"sessions": check_sessions, "bad_inputs": check_bad_inputs}[args.mode](args, checks)
    return checks.finish()


if __name__ == "__main__":
    sys.exit(main())
