#!/usr/bin/env python3
"""End-to-end checks of `pvtap audit` on logic-analyzer recordings.

    check_logic_audit.py --pvtap PVTAP --real DIR --scratch DIR MODE

sessions: each real flow-meter session gives the frames its source counts, requests = replies,
every check good, no noise, 9600 baud found, timing judged at the sample clock. channels:
--channels picks a channel, names one that is not there or one without traffic. vcd: the
session exported by sigrok-cli reads the same through libsigrok's VCD input, and through its
CSV input with --samplerate (refused in one line without). synthetic: a VCD
written here of an inverted 19200 8E1 line with one reply too early (t3.5) and one request with
a pause inside (t1.5) gives its settings and exactly those violations; on the same line, a
parity error, a framing error and a break are each a line_error event (jsonl) and a text
line, at their times. bad_inputs: a file
that is no recording, a recording without UART traffic, a sample rate under 4 per bit.
Exit 0 when every check holds, 1 with the failures listed, 77 when a needed input is missing.
"""

import argparse
import json
import os
import shutil
import re
import subprocess
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "support"))
from checks import Checks  # noqa: E402

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


def audit(pvtap, *args):
    return subprocess.run([pvtap, "audit", *args], capture_output=True, text=True, timeout=120)


def summary(result):
    lines = [line for line in result.stdout.splitlines() if line.startswith('{"type":"summary"')]
    return json.loads(lines[-1]) if lines else None


def check_session(checks, pvtap, path, frames, extra=(), bus_name="RXTX"):
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
    checks.equal(f"{name}: bus name", bus["bus"], bus_name)
    serial = bus.get("serial", {})
    checks.equal(f"{name}: baud", serial.get("baud"), 9600)
    checks.true(f"{name}: measured baud {serial.get('measured_baud')} within 2 % of 9600",
                abs(serial.get("measured_baud", 0) / 9600 - 1) <= 0.02)
    checks.equal(f"{name}: parity", serial.get("parity"), "none")
    checks.equal(f"{name}: inverted", serial.get("inverted"), False)
    checks.equal(f"{name}: detected", serial.get("detected"), True)
    checks.equal(f"{name}: line errors", bus.get("line"),
                 {"framing_errors": 0, "parity_errors": 0, "breaks": 0, "driver_glitches": 0,
                  "clock_deviations": 0})
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
    # A recording has no wall clock: its event lines count from its start, never a time of day.
    events = audit(args.pvtap, os.path.join(args.sigrok, GRAPH)).stdout.splitlines()
    event_lines = [line for line in events if "  RXTX  " in line]
    checks.true("event lines: some", len(event_lines) > 0)
    checks.true(f"event lines: times from the recording's start ({event_lines[:1]})",
                all(re.match(r"\+\d+\.\d{6} s ", line) for line in event_lines))


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
    # A CSV export names no channels (libsigrok's CSV input numbers them: RXTX is the third)
    # and gives no rate it can read: --samplerate gives it, and without it the file is refused.
    out = os.path.join(args.scratch, "graph.csv")
    subprocess.run([sigrok_cli, "-i", os.path.join(args.sigrok, GRAPH), "-o", out, "-O", "csv"],
                   check=True, timeout=120)
    check_session(checks, args.pvtap, out, 18, extra=("--samplerate", "4M"), bus_name="2")
    bad = audit(args.pvtap, out)
    checks.equal("csv without --samplerate: exit status", bad.returncode, 2)
    checks.true(f"csv without --samplerate: one line naming it ({bad.stderr!r})",
                bad.stderr.count("\n") == 1 and "--samplerate" in bad.stderr and bad.stdout == "")


def write_vcd(path, timescale_us, edges, end, idle_high=True):
    """A one-wire VCD: `edges` are (time in timescale units, level) after the idle level."""
    idle = 1 if idle_high else 0
    with open(path, "w") as f:
        f.write(f"$timescale {timescale_us} us $end\n$scope module t $end\n")
        f.write(f"$var wire 1 ! TX $end\n$upscope $end\n$enddefinitions $end\n#0 {idle}!\n")
        for time, level in edges:
            f.write(f"#{time} {level}!\n")
        f.write(f"#{end} {idle}!\n")


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


def crc16(data):
    crc = 0xFFFF
    for byte in data:
        crc ^= byte
        for _ in range(8):
            crc = (crc >> 1) ^ 0xA001 if crc & 1 else crc >> 1
    return bytes(data) + bytes([crc & 0xFF, crc >> 8])


class Line:
    """A UART line written bit by bit into VCD edges at 1 us: 8E1, idle low (inverted)."""

    def __init__(self, baud):
        self.bit = 1e6 / baud
        self.t = 100 * self.bit
        self.level = 0  # the line idles low
        self.edges = []

    def hold(self, mark, bits):
        level = 0 if mark else 1
        if level != self.level:
            self.edges.append((round(self.t), level))
            self.level = level
        self.t += bits * self.bit

    def frame(self, data, pause_after=None, pause_chars=0.0, damage=None):
        """`damage`: {index: "parity" or "framing"}, that character's parity or stop bit wrong."""
        damage = damage or {}
        for i, v in enumerate(data):
            data_bits = [(v >> k) & 1 for k in range(8)]
            parity = sum(data_bits) % 2 ^ (damage.get(i) == "parity")
            stop = 0 if damage.get(i) == "framing" else 1
            for b in [0] + data_bits + [parity, stop]:
                self.hold(b == 1, 1)
            if stop == 0:
                self.hold(True, 1)
            if i == pause_after:
                self.hold(True, 11 * pause_chars)

    def idle(self, chars):
        self.hold(True, 11 * chars)

    def line_break(self, chars):
        self.hold(False, 11 * chars)


def synthetic(checks, args):
    line = Line(19200)
    line.idle(10)
    for i in range(5):
        request = crc16([0x11, 0x03, 0x00, 0x20 + i, 0x00, 0x02])
        reply = crc16([0x11, 0x03, 0x04, 0x00, i, 0x12, 0x34])
        # The third request pauses 2 characters after its function code (over t1.5).
        line.frame(request, pause_after=1 if i == 2 else None, pause_chars=2.0)
        # The fourth reply comes 2.5 characters after its request (under t3.5).
        line.idle(2.5 if i == 3 else 5)
        line.frame(reply)
        line.idle(500)
    path = os.path.join(args.scratch, "inverted_8e1.vcd")
    write_vcd(path, 1, line.edges, round(line.t), idle_high=False)
    result = audit(args.pvtap, "--format", "jsonl", path)
    checks.equal("synthetic: exit status", result.returncode, 0)
    s = summary(result)
    if s is None:
        checks.true(f"synthetic: a summary line (stderr: {result.stderr.strip()})", False)
        return
    checks.equal("synthetic: frames", (s["frames"], s["requests"], s["responses"], s["bad_checks"]),
                 (10, 5, 5, 0))
    bus = s["buses"][0]
    serial = bus["serial"]
    checks.equal("synthetic: settings",
                 (serial["baud"], serial["parity"], serial["stop_bits"], serial["inverted"]),
                 (19200, "even", 1, True))
    checks.equal("synthetic: line errors", bus["line"],
                 {"framing_errors": 0, "parity_errors": 0, "breaks": 0, "driver_glitches": 0,
                  "clock_deviations": 0})
    checks.equal("synthetic: t3.5 violations", bus["timing"]["t35_violations"], 1)
    checks.equal("synthetic: t1.5 violations", bus["timing"]["t15_violations"], 1)
    checks.equal("synthetic: timed by", bus["timing"].get("timed_by"), "logic analyzer at 1 MS/s")
    line_errors(checks, args)
    two_channel_line_errors(checks, args)


def line_errors(checks, args):
    """After clean frames that set the format: a reply with a parity error in its 4th byte, one
    with a framing error in its 2nd, and a break; each a line_error event with its time."""
    line = Line(19200)
    line.idle(10)
    damaged = {2: {3: "parity"}, 4: {1: "framing"}}
    expected = []
    for i in range(6):
        line.frame(crc16([0x11, 0x03, 0x00, 0x20 + i, 0x00, 0x02]))
        line.idle(5)
        start = line.t
        line.frame(crc16([0x11, 0x03, 0x04, 0x00, i, 0x12, 0x34]), damage=damaged.get(i))
        for index, kind in damaged.get(i, {}).items():
            expected.append((kind, round((start + index * 11 * line.bit) / 1e6, 4)))
        line.idle(500)
    expected.append(("break", round(line.t / 1e6, 4)))
    line.line_break(3)
    line.idle(500)
    path = os.path.join(args.scratch, "line_errors.vcd")
    write_vcd(path, 1, line.edges, round(line.t), idle_high=False)
    result = audit(args.pvtap, "--format", "jsonl", path)
    events = [json.loads(l) for l in result.stdout.splitlines() if '"type":"line_error"' in l]
    checks.equal("line errors: events (kind, time)",
                 [(e["error"], round(e["ts"], 4)) for e in events], expected)
    s = summary(result) or {"buses": [{}]}
    checks.equal("line errors: counts", s["buses"][0].get("line", {}).get("parity_errors"), 1)
    # The damaged bits are parity and stop bits: the values, and so the frames, still check.
    checks.equal("line errors: frames", s.get("frames"), 12)
    text = audit(args.pvtap, path).stdout
    event_lines = [l.split("  line")[1].split() for l in text.splitlines() if "  TX  line  " in l]
    checks.equal("line errors: text lines", event_lines,
                 [["00", "parity"], ["03", "framing"], ["break"]])


def write_vcd_pair(path, first, second, end):
    """A two-wire VCD at 1 us, TX then RX, both idling low: `first` and `second` are their
    edges, (time, level) after the idle level."""
    changes = sorted([(t, level, "!") for t, level in first] +
                     [(t, level, '"') for t, level in second])
    with open(path, "w") as f:
        f.write("$timescale 1 us $end\n$scope module t $end\n")
        f.write('$var wire 1 ! TX $end\n$var wire 1 " RX $end\n')
        f.write("$upscope $end\n$enddefinitions $end\n")
        f.write('#0\n0!\n0"\n')
        for time, level, wire in changes:
            f.write(f"#{time}\n{level}{wire}\n")
        f.write(f'#{end}\n0!\n0"\n')


def two_channel_line_errors(checks, args):
    """A master's TX and RX recorded apart, one bus named TX,RX: the line errors of its replies
    are events of that bus, counted on it, whichever channel they came on."""
    tx, rx = Line(19200), Line(19200)

    def together(ahead, behind):
        behind.hold(True, (ahead.t - behind.t) / behind.bit)

    tx.idle(10)
    together(tx, rx)
    damaged = {2: {3: "parity"}, 4: {1: "framing"}}
    for i in range(6):
        tx.frame(crc16([0x11, 0x03, 0x00, 0x20 + i, 0x00, 0x02]))
        tx.idle(5)
        together(tx, rx)
        rx.frame(crc16([0x11, 0x03, 0x04, 0x00, i, 0x12, 0x34]), damage=damaged.get(i))
        rx.idle(500)
        together(rx, tx)
    path = os.path.join(args.scratch, "tx_rx_line_errors.vcd")
    write_vcd_pair(path, tx.edges, rx.edges, round(tx.t))
    result = audit(args.pvtap, "--format", "jsonl", path)
    events = [json.loads(l) for l in result.stdout.splitlines() if '"type":"line_error"' in l]
    checks.equal("two channels: line error events (kind, bus)",
                 [(e["error"], e["bus"]) for e in events],
                 [("parity", "TX,RX"), ("framing", "TX,RX")])
    s = summary(result) or {"buses": [{}]}
    checks.equal("two channels: one bus", [b.get("bus") for b in s["buses"]], ["TX,RX"])
    line = s["buses"][0].get("line", {})
    checks.equal("two channels: its counts",
                 (line.get("parity_errors"), line.get("framing_errors")), (1, 1))


def bad_inputs(checks, args):
    not_a_recording = os.path.join(args.scratch, "notes.sr")
    with open(not_a_recording, "w") as f:
        f.write("not a recording\n")
    one_line_refusal(checks, "a file that is no recording", audit(args.pvtap, not_a_recording),
                     "not a sigrok session")
    one_line_refusal(checks, "a missing file",
                     audit(args.pvtap, os.path.join(args.scratch, "missing.sr")),
                     "No such file or directory")
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
    parser.add_argument("mode", choices=["sessions", "channels", "vcd", "synthetic", "bad_inputs"])
    args = parser.parse_args()
    args.sigrok = os.path.join(args.real, "sigrok")
    if args.mode in ("sessions", "channels", "vcd") and not os.path.isfile(os.path.join(args.sigrok, GRAPH)):
        print(f"the real recordings are not in {args.sigrok}")
        return SKIP
    os.makedirs(args.scratch, exist_ok=True)
    checks = Checks()
    modes = {"sessions": sessions, "channels": channels, "vcd": vcd, "synthetic": synthetic,
             "bad_inputs": bad_inputs}
    modes[args.mode](checks, args)
    return checks.finish()


if __name__ == "__main__":
    sys.exit(main())
