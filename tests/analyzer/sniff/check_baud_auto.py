#!/usr/bin/env python3
"""End-to-end checks of `pvtap sniff --baud auto` on real pseudo-terminals.

A pty ignores the rate its reader sets, so the bus is played through pty-line-emulator: before
each transmission it reads back the slave's termios and delivers only what a UART set that way
would receive from the true line (garbage at a wrong rate). pvtap runs under strace, which
shows that the search never writes to the device.

usage: check_baud_auto.py --pvtap PVTAP --sim PVTAP_SIM --emulator EMU --scratch DIR CHECK
checks: rates (4800 and 19200 at once, each on its own pty), 4800, 19200, bad_options
"""
import argparse
import json
import os
import re
import shutil
import signal
import subprocess
import sys
import threading
import time

import pty_bus
from check_sniff import Failures, frame_key, frames_of

GUARD_S = 20  # a guard against hangs, not a timing requirement
# Passive detection must settle within this much traffic (the requirement); the bus
# runs longer, so that frames after the settling are there to be decoded.
SETTLE_WITHIN_S = 30
TRAFFIC_S = 45


def start_emulator(args, baud):
    emu = subprocess.Popen([args.emulator, str(baud), "8N1"], stdin=subprocess.PIPE,
                           stdout=subprocess.PIPE, text=True)
    return emu, emu.stdout.readline().strip()


def wait_for_open(trace_path, device, proc):
    deadline = time.monotonic() + GUARD_S
    while time.monotonic() < deadline:
        if proc.poll() is not None:
            raise RuntimeError(f"pvtap exited {proc.returncode} before opening {device}")
        if os.path.exists(trace_path):
            with open(trace_path, encoding="utf-8", errors="replace") as f:
                if device in f.read():
                    return
        time.sleep(0.05)
    raise RuntimeError(f"pvtap did not open {device} in {GUARD_S} s")


def traced_pid(strace):
    """pvtap's pid: strace's child. Signals go to pvtap itself, as a user's Ctrl-C would."""
    with open(f"/proc/{strace.pid}/task/{strace.pid}/children", encoding="ascii") as f:
        return int(f.read().split()[0])


def device_writes(trace_path, device):
    """(the open call, the write calls on the device's descriptor) from strace's log."""
    with open(trace_path, encoding="utf-8", errors="replace") as f:
        lines = f.read().splitlines()
    opened = [line for line in lines if f'"{device}"' in line and "openat" in line]
    fds = {m.group(1) for line in opened if (m := re.search(r"= (\d+)$", line))}
    writes = [line for line in lines
              if (m := re.search(r"\b(write|writev|pwrite64|pwritev2?)\((\d+),", line))
              and m.group(2) in fds]
    return opened, writes


def feed_lines(truth):
    first = truth["events"][0]["ts"]
    return "".join(f"{e['end'] - first:.6f} {e['hex']}\n" for e in truth["events"])


def check_found_frames(events, truth, bad):
    """Every frame from the settling on, in order, up to the last; settled in time."""
    found = [frame_key(f, "raw") for f in frames_of(events)]
    truth_frames = [e for e in truth["events"] if e["type"] == "frame"]
    expected = [frame_key(t, "hex") for t in truth_frames]
    if not bad.check(found, "no frame decoded"):
        return
    starts = [k for k in range(len(expected)) if expected[k:k + len(found)] == found]
    if not bad.check(starts, f"the {len(found)} frames found are not a run of the bus's frames"):
        return
    k = starts[-1]
    bad.check(k + len(found) == len(expected),
              f"frames after the settling lost: found {len(found)} from frame {k} of "
              f"{len(expected)}")
    settled_at = truth_frames[k]["ts"] - truth["events"][0]["ts"]
    bad.check(settled_at <= SETTLE_WITHIN_S,
              f"the first frame decoded is {settled_at:.1f} s into the traffic")


def check_rate(args, baud):
    bad = Failures()
    args = argparse.Namespace(**vars(args))
    args.scratch = os.path.join(args.scratch, str(baud))
    os.makedirs(args.scratch, exist_ok=True)
    truth = pty_bus.simulate(args.sim, args.scratch, f"auto{baud}",
                             ["--baud", str(baud), "--period", "1", "--duration", str(TRAFFIC_S),
                              "--dialect", "gsl", "--inverters", "2", "--seed", "5",
                              "--faults", "none", "--meter", "10"])
    emu, device = start_emulator(args, baud)
    trace = os.path.join(args.scratch, "strace.txt")
    out_path = os.path.join(args.scratch, "out.jsonl")
    err_path = os.path.join(args.scratch, "err.txt")
    with open(out_path, "w") as out, open(err_path, "w") as err:
        proc = subprocess.Popen(["strace", "-f", "-qq", "-o", trace, "-e",
                                 "trace=openat,write,writev,pwrite64,pwritev,pwritev2",
                                 args.pvtap, "sniff", "--device", device, "--baud", "auto",
                                 "--format", "jsonl", "--timeout", str(truth["timeout_s"])],
                                stdout=out, stderr=err)
        wait_for_open(trace, device, proc)
        played = time.monotonic()
        emu.stdin.write(feed_lines(truth))
        emu.stdin.flush()
        last = truth["events"][-1]["end"] - truth["events"][0]["ts"]
        # The pty stays open until pvtap has stopped: a closed one hangs up under it.
        time.sleep(max(0.0, played + last + 0.5 - time.monotonic()))
        os.kill(traced_pid(proc), signal.SIGTERM)
        bad.check(proc.wait(GUARD_S) == 0, f"exit status {proc.returncode}")
        emu.stdin.close()
        emu.wait(GUARD_S)
    with open(err_path, encoding="utf-8") as f:
        stderr = f.read()
    bad.check(f"{device}: {baud} 8N1 found from the traffic" in stderr, f"stderr: {stderr!r}")
    with open(out_path, encoding="utf-8") as f:
        events = [json.loads(line) for line in f if line.strip()]
    check_found_frames(events, truth, bad)
    summary = events[-1]
    if bad.check(summary.get("type") == "summary", "the last line is not the summary"):
        serial = summary["buses"][0].get("serial", {})
        want = {"baud": baud, "parity": "none", "stop_bits": 1, "detected": True}
        bad.check({k: serial.get(k) for k in want} == want, f"summary serial {serial}")
        line = summary["devices"][0]["line"]
        bad.check(line == f"{baud} 8N1 (found from the traffic)", f"device line {line!r}")
    opened, writes = device_writes(trace, device)
    bad.check(opened and all("O_RDONLY" in line for line in opened), f"opened as {opened}")
    bad.check(not writes, f"writes to the device: {writes[:3]}")
    return bad.exit_status(f"baud auto {baud}")


def check_rates(args, rates):
    """Each rate on a pty of its own, all at once: the traffic is real time and a core
    mostly waits for it. The exit status is the worst of theirs."""
    statuses = {}
    threads = [threading.Thread(target=lambda b=b: statuses.update({b: check_rate(args, b)}))
               for b in rates]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    return max(statuses.get(b, 1) for b in rates)


def check_bad_options(args):
    """--baud auto needs a serial tap; a rate out of range or a word is refused."""
    bad = Failures()
    for extra, words in ((["--interface", "lo", "--baud", "auto"], "--baud auto"),
                         (["--device", "/dev/null", "--baud", "fast"], "neither auto"),
                         (["--device", "/dev/null", "--baud", "600"], "neither auto")):
        run = subprocess.run([args.pvtap, "sniff", *extra], capture_output=True, text=True,
                             check=False, timeout=GUARD_S)
        lines = run.stderr.strip().splitlines()
        bad.check(run.returncode == 2, f"{extra}: exit {run.returncode}")
        bad.check(len(lines) >= 1 and words in lines[0], f"{extra}: stderr {run.stderr!r}")
    return bad.exit_status("bad_options")


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--pvtap", required=True)
    parser.add_argument("--sim", required=True)
    parser.add_argument("--emulator", required=True)
    parser.add_argument("--scratch", required=True)
    parser.add_argument("check", choices=["rates", "4800", "19200", "bad_options"])
    args = parser.parse_args()
    args.scratch = os.path.join(args.scratch, "baud_auto_" + args.check)
    os.makedirs(args.scratch, exist_ok=True)
    if args.check == "bad_options":
        return check_bad_options(args)
    if not shutil.which("strace"):
        print("strace is not installed: the no-write check cannot run")
        return 77
    rates = [4800, 19200] if args.check == "rates" else [int(args.check)]
    return check_rates(args, rates)


if __name__ == "__main__":
    sys.exit(main())
