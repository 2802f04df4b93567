#!/usr/bin/env python3
"""Speed of `pvtap audit SESSION.sr` against sigrok-cli's own UART and Modbus decoders on the
same session, side by side in one run: rounds alternate the two programs, the median wall and
CPU times are reported, and samples per second are the session's samples over pvtap's (or
sigrok-cli's) CPU time. pvtap's peak memory is printed too.

    bench/logic_audit_bench.py [--pvtap PVTAP] [--runs N] SESSION.sr [SESSION.sr ...]

sigrok-cli runs as `sigrok-cli -i SESSION -P uart:baudrate=BAUD:rx=CHANNEL,modbus` (without
rx= its UART decoder is given no channel and decodes nothing). Figures go to stdout; record
them in bench/README.md with the date, machine and commit.
"""

import argparse
import os
import statistics
import subprocess
import sys
import time
import zipfile


def session_samples(path):
    """Samples in a sigrok session: its logic-1-* chunks' bytes over its unit size."""
    with zipfile.ZipFile(path) as z:
        meta = z.read("metadata").decode()
        unitsize = int(next(line.split("=")[1] for line in meta.splitlines()
                            if line.startswith("unitsize=")))
        data = sum(i.file_size for i in z.infolist() if i.filename.startswith("logic-1"))
    return data // unitsize


def timed(command):
    """Wall seconds, CPU seconds and peak RSS (KiB) of one run, its output thrown away."""
    start = time.perf_counter()
    with open(os.devnull, "w") as null:
        child = subprocess.Popen(command, stdout=null, stderr=null)
        _, status, usage = os.wait4(child.pid, 0)
    wall = time.perf_counter() - start
    if status != 0:
        sys.exit(f"failed ({status}): {' '.join(command)}")
    return wall, usage.ru_utime + usage.ru_stime, usage.ru_maxrss


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--pvtap", default="build/analyzer/pvtap")
    parser.add_argument("--runs", type=int, default=5)
    parser.add_argument("--baud", default="9600")
    parser.add_argument("--channel", default="RXTX")
    parser.add_argument("sessions", nargs="+")
    args = parser.parse_args()
    print("session | samples | pvtap wall / cpu s | sigrok-cli wall / cpu s | pvtap MS/s (cpu) | "
          "sigrok-cli MS/s (cpu) | ratio | pvtap peak RSS MiB")
    for path in args.sessions:
        samples = session_samples(path)
        pvtap = [args.pvtap, "audit", "--summary-only", path]
        sigrok = ["sigrok-cli", "-i", path, "-P",
                  f"uart:baudrate={args.baud}:rx={args.channel},modbus"]
        ours, theirs = [], []
        for _ in range(args.runs):
            ours.append(timed(pvtap))
            theirs.append(timed(sigrok))
        ow, oc = (statistics.median(r[i] for r in ours) for i in (0, 1))
        tw, tc = (statistics.median(r[i] for r in theirs) for i in (0, 1))
        rss = max(r[2] for r in ours) / 1024
        print(f"{os.path.basename(path)} | {samples} | {ow:.3f} / {oc:.3f} | {tw:.3f} / {tc:.3f} | "
              f"{samples / oc / 1e6:.0f} | {samples / tc / 1e6:.0f} | {tc / oc:.1f}x | {rss:.1f}")


if __name__ == "__main__":
    main()
