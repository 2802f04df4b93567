#!/usr/bin/env python3
"""Plays a simulated bus onto a real pseudo-terminal and checks, from the other end, that
every byte arrives in order and at the bus's pace: one character time between the bytes of
a frame, and the silences between frames that the ground truth records.

usage: check_pty_pacing.py PVTAP_SIM SCRATCH_DIR
"""
import os
import select
import subprocess
import sys
import time
import json

BAUD = 9600
CHAR_S = 10.0 / BAUD


def read_all(master, proc):
    """(monotonic time, byte) for everything the pty delivers until the simulator exits."""
    got = []
    while True:
        ready, _, _ = select.select([master], [], [], 0.2)
        if ready:
            now = time.monotonic()
            got.extend((now, b) for b in os.read(master, 4096))
        elif proc.poll() is not None:
            return got


def main():
    sim, scratch = sys.argv[1:3]
    os.makedirs(scratch, exist_ok=True)
    truth_path = os.path.join(scratch, "pty.truth.json")
    master, slave = os.openpty()
    proc = subprocess.Popen([sim, "--dialect", "gsl", "--inverters", "2", "--duration", "3",
                             "--period", "1", "--seed", "9", "--baud", str(BAUD),
                             "--truth", truth_path, "--device", os.ttyname(slave)])
    got = read_all(master, proc)
    os.close(slave)
    if proc.returncode != 0:
        sys.exit(f"pvtap-sim exited {proc.returncode}")
    with open(truth_path, encoding="utf-8") as f:
        events = json.load(f)["events"]
    sent = bytes.fromhex("".join(e["hex"] for e in events))
    if bytes(b for _, b in got) != sent:
        sys.exit(f"the pty delivered {len(got)} bytes, not the {len(sent)} bytes sent")
    # When each byte should be written: its event's start plus one character time per byte.
    due = [e["ts"] - events[0]["ts"] + i * CHAR_S
           for e in events for i in range(len(e["hex"]) // 2)]
    # Reads can only make bytes late, never early: the earliest byte fixes the clock offset,
    # and then no byte may lag its due time by more than a scheduling hiccup. A writer that
    # ignored the baud would deliver a whole frame at once and lag by the frame's length.
    offsets = [t - d for (t, _), d in zip(got, due)]
    origin = min(offsets)
    # A loaded machine delays a few reads; most bytes must still be on time.
    late = sorted(o - origin for o in offsets)
    median, p90 = late[len(late) // 2], late[len(late) * 9 // 10]
    failures = []
    if median > 0.005 or p90 > 0.02:
        failures.append(f"bytes lag their due times: median {median * 1e3:.1f} ms, "
                        f"90th percentile {p90 * 1e3:.1f} ms")
    for text in failures[:10]:
        print(text)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
