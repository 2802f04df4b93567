#!/usr/bin/env python3
"""Times tshark over one GSL capture: pvtap's invrtu against Wireshark's Modbus RTU dissector.

Both verify the CRC. The capture (one TCP connection to a gateway on port 4001, one frame
per segment, so that Modbus RTU over TCP can read it) is written by the plugin tests' own
generator. Each figure is the best of --repeat runs; the target is ours <= 1.1 x theirs
(issue 39; it was 1.5 before).
With --instructions each figure is instead tshark's instruction count under callgrind, which
the machine's load does not move (about 50 times slower: use a few thousand pairs).

    bench/dissector_vs_mbrtu.py [--plugin build/dissector/pvtap.so] [--pairs 20000]
    bench/dissector_vs_mbrtu.py --instructions --pairs 2000
"""

import argparse
import os
import re
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.dont_write_bytecode = True  # keep the tests folder free of __pycache__
sys.path.insert(0, os.path.join(ROOT, "tests", "dissector"))

from bus_frames import gsl_read_reply, rtu_read_request  # noqa: E402
from pcap_writer import Pcap, TcpFlow  # noqa: E402
import tshark_runner  # noqa: E402

PORT = 4001
TARGET = 1.1
OURS = ["-o", "invrtu.verify_crc:TRUE"]
THEIRS = ["-d", "tcp.port==%d,mbrtu" % PORT, "-o", "mbrtu.crc_verification:TRUE"]


def polling_capture(pairs):
    """A logger polling IDs 1050..1072 of station 1, every reply with fresh values."""
    pcap = Pcap()
    flow = TcpFlow(pcap, server=("10.0.0.2", PORT))
    for i in range(pairs):
        flow.request(rtu_read_request(1, 0x03, 1050, 23), after=0.05)
        flow.reply(gsl_read_reply(1, [(i * 7 + k * 13) & 0xFFFF for k in range(23)]), after=0.02)
    return pcap


def best_time(home, args, repeat):
    best = None
    for _ in range(repeat):
        start = time.perf_counter()
        home.run(args)
        elapsed = time.perf_counter() - start
        best = elapsed if best is None else min(best, elapsed)
    return best


def instructions(home, args):
    """tshark ARGS's instruction count (valgrind's callgrind, whole process)."""
    command = home.command(args)
    at = command.index("tshark")
    command[at:at] = ["valgrind", "--tool=callgrind", "--callgrind-out-file=/dev/null"]
    result = subprocess.run(command, capture_output=True, text=True, check=True)
    match = re.search(r"refs:\s+([\d,]+)", result.stderr)
    if not match:
        raise SystemExit("no instruction count from callgrind:\n" + result.stderr[-2000:])
    return int(match.group(1).replace(",", ""))


def check_both_dissect_everything(home, capture, frames):
    ours = home.run(["-r", capture] + OURS).stdout.count("invRTU")
    theirs = home.run(["-r", capture] + THEIRS).stdout.count("Modbus RTU")
    if ours != frames or theirs != frames:
        raise SystemExit("frames dissected: ours %d, Modbus RTU %d, expected %d"
                         % (ours, theirs, frames))


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--plugin", default=os.path.join(ROOT, "build", "dissector", "pvtap.so"))
    parser.add_argument("--pairs", type=int, default=20000)
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--instructions", action="store_true",
                        help="count instructions (callgrind) instead of timing")
    options = parser.parse_args()
    os.environ["PVTAP_PLUGIN"] = os.path.abspath(options.plugin)

    home = tshark_runner.TsharkHome()
    try:
        capture = home.write("gsl-bench.pcap", polling_capture(options.pairs))
        check_both_dissect_everything(home, capture, 2 * options.pairs)
        print("capture: %d GSL frames, one per TCP segment" % (2 * options.pairs))
        unit = "M instr" if options.instructions else "s"
        print("%-28s %12s %12s %7s" % ("output", "invrtu (%s)" % unit, "mbrtu (%s)" % unit,
                                       "ratio"))
        worst = 0.0
        for label, mode in (("summary lines", []), ("full tree (-V)", ["-V"]),
                            ("two passes (-2)", ["-2"])):
            if options.instructions:
                ours = instructions(home, ["-r", capture] + OURS + mode) / 1e6
                theirs = instructions(home, ["-r", capture] + THEIRS + mode) / 1e6
            else:
                ours = best_time(home, ["-r", capture] + OURS + mode, options.repeat)
                theirs = best_time(home, ["-r", capture] + THEIRS + mode, options.repeat)
            worst = max(worst, ours / theirs)
            print("%-28s %12.2f %12.2f %7.2f" % (label, ours, theirs, ours / theirs))
        print("target: ratio <= %.1f: %s" % (TARGET, "met" if worst <= TARGET else "NOT met"))
        return 0 if worst <= TARGET else 1
    finally:
        home.close()


if __name__ == "__main__":
    sys.exit(main())
