#!/usr/bin/env python3
"""End-to-end checks of `pvtap audit` on logic-analyzer recordings.

    check_logic_audit.py --pvtap PVTAP --real DIR --scratch DIR MODE

sessions: each real flow-meter session gives the frames its source counts, requests = replies,
every check good, no noise, 9600 baud found, timing judged at the sample clock. channels:
--channels picks a channel, names one that is not there or one without traffic. vcd: the
session exported by sigrok-cli reads the same through libsigrok's VCD input. bad_inputs: a file
that is no recording, a recording without UART traffic, a sample rate under 4 per bit.
Exit 0 when every check holds, 1 with the failures listed, 77 when a needed input is missing.
"""

import argparse
import json
import os
import shutil
import subprocess
import sys

SKIP = 77

# The flow-meter sessions and their frames, from /work/shared/real/README.md.
SESSIONS = {
    "flowmeter_flowmeter_graph_tool.sr": 18,
    "flowmeter_flowmeter_target0_val0.sr": 74,
    "flowmeter_flowmeter_target_0liter_per_min.sr": 112,
    "flowmeter_flowmeter_target_15liter_per_min.sr": 132,
    "flowmeter_flowmeter_target_20liter_per_min.sr": 66,
}
GRAPH = "flowmeter_flowmeter_graph_tool.sr"


class Checks:
    """Collects failed checks instead of stopping at the first."""

    def __init__(self):
        self.failures = []

    def equal(self, what, actual, expected):
        if actual != expected:
            self.failures.append(f"{what}: got {actual!r}, expected {expected!r}")

    def true(self, what, condition):
        if not condition:
            self.failures.append(what)

    def finish(self):
        for failure in self.failures:
            print("FAIL:", failure)
        if not self.failures:
            print("all checks hold")
        return 1 if self.failures else 0


def audit(pvtap, *args):
    return subprocess.run([pvtap, "audit", *args], capture_output=True, text=True, timeout=120)


def summary(result):
    lines = [line for line in result.stdout.splitlines() if line.startswith('{"type":"summary"')]
    return json.loads(lines[-1]) if lines else None


def check_session(checks, pvtap, path, frames, extra=()):
    name = os.path.basename(path)
    result = audit(pvtap, "--format", "jsonl", *extra, path)
    checks.equal(f"{name}: exit status", result.returncode, 0)
    s = summary(result)
    if s is None:
        checks.true(f"{name}: a summary line (stderr: {result.stderr.strip()})", False)
        return
    checks.equal(f"{name}: frames", s["frames"], frames)
    checks.equal(f"{name}: requests", s["requests"], frames // 2)
    checks.equal(f"{name}: responses", s["responses"], frames // 2)
    checks.equal(f"{name}: bad checks", s["bad_checks"], 0)
    checks.equal(f"{name}: noise bytes", s["noise_bytes"], 0)
    checks.equal(f"{name}: timeouts", s["timeouts"], 0)
    checks.equal(f"{name}: buses", len(s["buses"]), 1)
    bus = s["buses"][0]
    checks.equal(f"{name}: bus name", bus["bus"], "RXTX")
    serial = bus.get("serial", {})
    checks.equal(f"{name}: baud", serial.get("baud"), 9600)
    checks.true(f"{name}: measured baud {serial.get('measured_baud')} within 2 % of 9600",
                abs(serial.get("measured_baud", 0) / 9600 - 1) <= 0.02)
    checks.equal(f"{name}: parity", serial.get("parity"), "none")
    checks.equal(f"{name}: inverted", serial.get("inverted"), False)
    checks.equal(f"{name}: detected", serial.get("detected"), True)
    checks.equal(f"{name}: line errors", bus.get("line"),
                 {"framing_errors": 0, "parity_errors": 0, "breaks": 0})
    timing = bus["timing"]
    checks.equal(f"{name}: timing judged", timing["judged"], True)
    checks.true(f"{name}: timed by the sample clock ({timing.get('timed_by')})",
                timing.get("timed_by", "").startswith("logic analyzer at "))
    # Characters follow each other every 11 bit times: no silence inside a frame.
    checks.equal(f"{name}: t1.5 violations", timing["t15_violations"], 0)
    checks.equal(f"{name}: silences measured", timing["gap_ms"]["count"], frames - 1)


def sessions(checks, args):
    for name, frames in SESSIONS.items():
        check_session(checks, args.pvtap, os.path.join(args.sigrok, name), frames)
    text = audit(args.pvtap, "--summary-only", os.path.join(args.sigrok, GRAPH))
    checks.true("text report: timed by the logic analyzer",
                "  timed by: logic analyzer at 4 MS/s" in text.stdout)
    checks.true("text report: the serial line", "serial line on channel RXTX: 9600 baud 8N2"
                in text.stdout)


def one_line_refusal(checks, what, result, expected_words):
    checks.equal(f"{what}: exit status", result.returncode, 2)
    checks.equal(f"{what}: stdout", result.stdout, "")
    lines = result.stderr.strip().splitlines()
    checks.equal(f"{what}: stderr lines ({result.stderr.strip()!r})", len(lines), 1)
    checks.true(f"{what}: the line says {expected_words!r} ({result.stderr.strip()!r})",
                bool(lines) and expected_words in lines[0])


def channels(checks, args):
    graph = os.path.join(args.sigrok, GRAPH)
    check_session(checks, args.pvtap, graph, 18, ("--channels", "RXTX"))
    one_line_refusal(checks, "a channel that is not there",
                     audit(args.pvtap, "--channels", "RXTX,DE", graph), "no channel DE")
    # The session's other channels are recorded but idle: no UART there.
    one_line_refusal(checks, "a channel without traffic",
                     audit(args.pvtap, "--channels", "3", graph),
                     "channel 3 carries no UART traffic")
    one_line_refusal(checks, "--channels without a logic recording",
                     audit(args.pvtap, "--channels", "RXTX", "--raw", graph), "--channels")


def vcd(checks, args):
    sigrok_cli = shutil.which("sigrok-cli")
    if sigrok_cli is None:
        print("sigrok-cli is not installed")
        sys.exit(SKIP)
    out = os.path.join(args.scratch, "graph.vcd")
    subprocess.run([sigrok_cli, "-i", os.path.join(args.sigrok, GRAPH), "-o", out, "-O", "vcd"],
                   check=True, timeout=120)
    check_session(checks, args.pvtap, out, 18)


def write_vcd(path, timescale_us, edges, end):
    """A one-wire VCD: `edges` are (time in timescale units, level), the line starts high."""
    with open(path, "w") as f:
        f.write(f"$timescale {timescale_us} us $end\n$scope module t $end\n")
        f.write("$var wire 1 ! TX $end\n$upscope $end\n$enddefinitions $end\n#0 1!\n")
        for time, level in edges:
            f.write(f"#{time} {level}!\n")
        f.write(f"#{end} 1!\n")


def uart_edges(values, baud, timescale_us, start_bits=20):
    """8N1 characters from `values`, edges rounded to the timescale."""
    bit = 1e6 / baud / timescale_us
    edges, level, t = [], 1, start_bits * bit
    for v in values:
        bits = [0] + [(v >> i) & 1 for i in range(8)] + [1, 1]
        for b in bits:
            if b != level:
                edges.append((round(t), b))
                level = b
            t += bit
    return edges, round(t + start_bits * bit)


def bad_inputs(checks, args):
    not_a_recording = os.path.join(args.scratch, "notes.sr")
    with open(not_a_recording, "w") as f:
        f.write("not a recording\n")
    one_line_refusal(checks, "a file that is no recording", audit(args.pvtap, not_a_recording),
                     "not a sigrok session")
    one_line_refusal(checks, "a missing file",
                     audit(args.pvtap, os.path.join(args.scratch, "missing.sr")), "no such file")
    quiet = os.path.join(args.scratch, "quiet.vcd")
    write_vcd(quiet, 1, [(500, 0), (501, 1)], 100000)  # a one-sample glitch, no character
    one_line_refusal(checks, "a recording without UART traffic", audit(args.pvtap, quiet),
                     "no channel carries UART traffic")
    # 38400 baud sampled at 100 kS/s: 2.6 samples per bit.
    edges, end = uart_edges([0x01, 0x03, 0x00, 0x00, 0x00, 0x0A, 0xC5, 0xCD] * 20, 38400, 10)
    slow = os.path.join(args.scratch, "slow.vcd")
    write_vcd(slow, 10, edges, end)
    one_line_refusal(checks, "a sample rate under 4 samples per bit", audit(args.pvtap, slow),
                     "samples per bit; at least 4 are needed")


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--pvtap", required=True)
    parser.add_argument("--real", required=True)
    parser.add_argument("--scratch", required=True)
    parser.add_argument("mode", choices=["sessions", "channels", "vcd", "bad_inputs"])
    args = parser.parse_args()
    args.sigrok = os.path.join(args.real, "sigrok")
    if args.mode != "bad_inputs" and not os.path.isfile(os.path.join(args.sigrok, GRAPH)):
        print(f"the real recordings are not in {args.sigrok}")
        return SKIP
    os.makedirs(args.scratch, exist_ok=True)
    checks = Checks()
    {"sessions": sessions, "channels": channels, "vcd": vcd, "bad_inputs": bad_inputs}[
        args.mode](checks, args)
    return checks.finish()


if __name__ == "__main__":
    sys.exit(main())
