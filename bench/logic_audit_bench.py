#!/usr/bin/env python3
"""Speed of `pvtap audit SESSION.sr` against sigrok-cli's own UART and Modbus decoders on the
same session, side by side in one run: rounds alternate the two programs, the median wall and
CPU times are reported, and samples per second are the session's samples over pvtap's (or
sigrok-cli's) CPU time. pvtap's peak memory is printed too.

    bench/logic_audit_bench.py [--pvtap PVTAP] [--runs N] SESSION.sr [SESSION.sr ...]

sigrok-cli runs as `sigrok-cli -i SESSION -P uart:baudrate=BAUD:rx=CHANNEL,modbus` (without
rx= its UART decoder is given no channel and decodes nothing). Both programs' start (loading
libsigrok, and for sigrok-cli Python and its decoders) is a fixed cost that dominates a short
session: each program also reads a copy of the session cut to its first 4096 samples, and the
"net" columns are the CPU time beyond that start. Figures go to stdout; record them in
bench/README.md with the date, machine and commit.
"""

import argparse
import os
import statistics
import subprocess
import sys
import tempfile
import time
import zipfile

START_SAMPLES = 4096


def session_samples(path):
    """Samples in a sigrok session: its logic-1-* chunks' bytes over its unit size."""
    with zipfile.ZipFile(path) as z:
        meta = z.read("metadata").decode()
        unitsize = int(next(line.split("=")[1] for line in meta.splitlines()
                            if line.startswith("unitsize=")))
        data = sum(i.file_size for i in z.infolist() if i.filename.startswith("logic-1"))
    return data // unitsize


def cut_session(path, folder):
    """A copy of the session with only its first START_SAMPLES samples."""
    out = os.path.join(folder, "start-" + os.path.basename(path))
    with zipfile.ZipFile(path) as z, zipfile.ZipFile(out, "w", zipfile.ZIP_DEFLATED) as w:
        meta = z.read("metadata").decode()
        unitsize = int(next(line.split("=")[1] for line in meta.splitlines()
                            if line.startswith("unitsize=")))
        w.writestr("version", z.read("version"))
        w.writestr("metadata", meta)
        first = sorted((i.filename for i in z.infolist() if i.filename.startswith("logic-1")),
                       key=lambda n: int(n.rsplit("-", 1)[1]))[0]
        w.writestr("logic-1-1", z.read(first)[:START_SAMPLES * unitsize])
    return out


def timed(command, must_succeed=True):
    """Wall seconds, CPU seconds and peak RSS (KiB) of one run, its output thrown away."""
    start = time.perf_counter()
    with open(os.devnull, "w") as null:
        child = subprocess.Popen(command, stdout=null, stderr=null)
        _, status, usage = os.wait4(child.pid, 0)
    wall = time.perf_counter() - start
    if status != 0 and must_succeed:
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
          "sigrok-cli MS/s (cpu) | ratio | pvtap / sigrok-cli start cpu s | net ratio | "
          "pvtap peak RSS MiB")
    folder = tempfile.mkdtemp(prefix="pvtap-logic-bench-")
    for path in args.sessions:
        samples = session_samples(path)
        start = cut_session(path, folder)

        def pvtap(session):
            return [args.pvtap, "audit", "--summary-only", session]

        def sigrok(session):
            return ["sigrok-cli", "-i", session, "-P",
                    f"uart:baudrate={args.baud}:rx={args.channel},modbus"]
        ours, theirs, our_start, their_start = [], [], [], []
        for _ in range(args.runs):
            ours.append(timed(pvtap(path)))
            theirs.append(timed(sigrok(path)))
            # The cut session may hold no whole frame: pvtap then says so and exits 2.
            our_start.append(timed(pvtap(start), must_succeed=False))
            their_start.append(timed(sigrok(start), must_succeed=False))
        ow, oc = (statistics.median(r[i] for r in ours) for i in (0, 1))
        tw, tc = (statistics.median(r[i] for r in theirs) for i in (0, 1))
        os_, ts_ = (statistics.median(r[1] for r in runs) for runs in (our_start, their_start))
        net = (tc - ts_) / (oc - os_) if oc > os_ else float("inf")
        rss = max(r[2] for r in ours) / 1024
        print(f"{os.path.basename(path)} | {samples} | {ow:.3f} / {oc:.3f} | {tw:.3f} / {tc:.3f} | "
              f"{samples / oc / 1e6:.0f} | {samples / tc / 1e6:.0f} | {tc / oc:.1f}x | "
              f"{os_:.3f} / {ts_:.3f} | {net:.1f}x | {rss:.1f}")


if __name__ == "__main__":
    main()
