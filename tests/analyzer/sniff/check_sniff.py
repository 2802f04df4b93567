#!/usr/bin/env python3
"""End-to-end checks of `pvtap sniff --device` on real pseudo-terminals.

The simulator (pvtap-sim) makes a bus and its ground truth; this script paces the bytes onto
the master side of a pty at the bus's baud (pty_bus.py) while pvtap sniffs the slave side,
then compares what pvtap reported with the truth.

usage: check_sniff.py --pvtap PVTAP --sim PVTAP_SIM --scratch DIR CHECK
checks: truth passive killed unplug two_buses stop_conditions status_line bad_devices
"""
import argparse
import json
import os
import re
import signal
import subprocess
import sys
import threading
import time

import pty_bus

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..",
                                "dissector"))
from bus_frames import with_crc  # noqa: E402

# The longest one program this test runs may take: a guard, not a timing check. On expiry
# subprocess raises TimeoutExpired, which names the command that was waited for.
RUN_GUARD_S = 120

BAUD = 9600
# Longest wait for pvtap to open a device or to exit by itself; a guard against hangs, not
# a timing requirement.
GUARD_S = 20


class Failures:
    def __init__(self):
        self.items = []

    def check(self, ok, text):
        if not ok:
            self.items.append(text)
        return ok

    def exit_status(self, name):
        if not self.items:
            print(f"{name}: ok")
            return 0
        print(f"{name}: {len(self.items)} failure(s)")
        for text in self.items[:20]:
            print("  " + text)
        return 1


class Sniffer:
    """One running `pvtap sniff`, its output in files under the scratch folder."""

    def __init__(self, pvtap, scratch, name, args, stderr=None):
        self.out_path = os.path.join(scratch, name + ".out")
        self.err_path = os.path.join(scratch, name + ".err")
        self._stderr_file = None
        if stderr is None:
            self._stderr_file = open(self.err_path, "w")
            stderr = self._stderr_file
        with open(self.out_path, "w") as out:
            self.proc = subprocess.Popen([pvtap, "sniff", *args], stdout=out, stderr=stderr)

    def fds_on(self, path):
        """The descriptors pvtap holds on the device at `path` (after symlinks)."""
        real = os.path.realpath(path)
        fds = []
        fd_dir = f"/proc/{self.proc.pid}/fd"
        for fd in os.listdir(fd_dir):
            try:
                if os.readlink(os.path.join(fd_dir, fd)) == real:
                    fds.append(int(fd))
            except OSError:
                continue
        return fds

    def wait_open(self, path):
        deadline = time.monotonic() + GUARD_S
        while time.monotonic() < deadline:
            if self.proc.poll() is not None:
                raise RuntimeError(f"pvtap sniff exited {self.proc.returncode}: {self.stderr()}")
            if self.fds_on(path):
                return
            time.sleep(0.01)
        raise RuntimeError(f"pvtap sniff did not open {path} in {GUARD_S} s")

    def stop(self, how=signal.SIGTERM):
        """SIGTERM, as a service manager or Wireshark stops a capture (SIGINT: Ctrl-C)."""
        self.proc.send_signal(how)
        return self.wait()

    def wait(self):
        try:
            self.proc.wait(GUARD_S)
        except subprocess.TimeoutExpired:
            self.proc.kill()
            raise RuntimeError("pvtap sniff did not exit")
        if self._stderr_file:
            self._stderr_file.close()
        return self.proc.returncode

    def events(self):
        with open(self.out_path, encoding="utf-8") as f:
            return [json.loads(line) for line in f if line.strip()]

    def stderr(self):
        with open(self.err_path, encoding="utf-8", errors="replace") as f:
            return f.read()


def simulate(args, name, *sim_args):
    return pty_bus.simulate(args.sim, args.scratch, name,
                            ["--baud", str(BAUD), "--period", "1", *sim_args])


def frames_of(events, bus=None):
    return [e for e in events if e["type"] == "frame" and (bus is None or e.get("bus") == bus)]


def frame_key(frame, raw_field):
    return (frame["role"], frame["station"], frame["function"], frame["check"], frame[raw_field])


def compare_frames(found, truth_frames, label, bad):
    bad.check(len(found) == len(truth_frames),
              f"{label}: pvtap reported {len(found)} frames, the bus carried {len(truth_frames)}")
    for i, (f, t) in enumerate(zip(found, truth_frames)):
        if not bad.check(frame_key(f, "raw") == frame_key(t, "hex"),
                         f"{label} frame {i}: {frame_key(f, 'raw')} != {frame_key(t, 'hex')}"):
            return


def stop_offset(truth):
    """When to stop sniffing, in seconds after the first event: after the last byte and after
    every timeout the truth records, before any unanswered request's timeout."""
    events, timeout = truth["events"], truth["timeout_s"]
    first = events[0]["ts"]
    ends = [e.get("end", e["ts"]) - first for e in events]
    ends += [t["request_ts"] + timeout - first for t in truth["timeouts"]]
    stop = max(ends) + 0.3
    for request in truth["unanswered_at_end"]:
        if request["request_ts"] + timeout - first < stop + 0.1:
            raise RuntimeError("the truth's timing leaves no moment to stop; change the seed")
    return stop


def play_truth(pty, truth):
    """Plays the truth's bytes now and returns when the sniffer may be stopped."""
    start = time.monotonic()
    pty_bus.play(pty.master, pty_bus.byte_schedule(truth["events"], BAUD), start)
    time.sleep(max(0.0, start + stop_offset(truth) - time.monotonic()))


def check_summary(summary, truth, bad):
    for key in ("bytes", "frames", "requests", "responses", "bad_checks", "timeouts",
                "noise_bytes"):
        bad.check(summary.get(key) == truth["summary"][key],
                  f"summary {key}: pvtap {summary.get(key)}, truth {truth['summary'][key]}")
    bad.check(summary.get("unanswered_at_end") == len(truth["unanswered_at_end"]),
              f"unanswered at end: {summary.get('unanswered_at_end')}")
    # The byte invariant: every byte read is in a frame, noise, or counted lost.
    bad.check(summary["bytes"] == summary["frame_bytes"] + summary["noise_bytes"],
              f"bytes {summary['bytes']} != frame bytes {summary['frame_bytes']} + noise "
              f"{summary['noise_bytes']}")


def check_events(events, truth, bad, label="bus"):
    compare_frames(frames_of(events), [e for e in truth["events"] if e["type"] == "frame"],
                   label, bad)
    noise = sum(e["bytes"] for e in events if e["type"] == "noise")
    bad.check(noise == truth["summary"]["noise_bytes"], f"noise bytes {noise}")
    timeouts = [(e["station"], e["function"]) for e in events if e["type"] == "timeout"]
    expected = [(t["station"], t["function"]) for t in truth["timeouts"]]
    bad.check(timeouts == expected, f"timeouts: pvtap {timeouts}, truth {expected}")


def audit_frames(args, pcap):
    run = subprocess.run([args.pvtap, "audit", "--format", "jsonl", pcap],
                         capture_output=True, text=True, check=False, timeout=RUN_GUARD_S)
    if run.returncode != 0:
        raise RuntimeError(f"pvtap audit {pcap} exited {run.returncode}: {run.stderr}")
    return frames_of([json.loads(line) for line in run.stdout.splitlines()])


def check_truth(args):
    """All three dialects, a meter and an IO module, every fault kind: the frames, noise, timeouts and totals of the
    truth; the pcap written with --write, cut by SIGTERM, reads back to the same frames (their
    times differ: a record carries the frame's last byte's time, the live line its first's)."""
    bad = Failures()
    truth = simulate(args, "mixed", "--dialect", "gsl,hybrid,ascii", "--inverters", "4",
                     "--duration", "6", "--seed", "3", "--faults", "all", "--meter", "10",
                     "--io-module", "20")
    pcap = os.path.join(args.scratch, "mixed.pcap")
    pty = pty_bus.Pty()
    sniffer = Sniffer(args.pvtap, args.scratch, "mixed",
                      ["--device", pty.path, "--format", "jsonl", "--write", pcap,
                       "--timeout", str(truth["timeout_s"])])
    sniffer.wait_open(pty.path)
    play_truth(pty, truth)
    bad.check(sniffer.stop() == 0, f"exit status {sniffer.proc.returncode}: {sniffer.stderr()}")
    pty.close()
    events = sniffer.events()
    check_events(events, truth, bad)
    summary = events[-1]
    if bad.check(summary["type"] == "summary", "the last line is not the summary"):
        check_summary(summary, truth, bad)
        bad.check(summary.get("stopped_by_signal") is True, "stopped_by_signal is not true")
        device = summary["devices"][0]
        bad.check(device["bytes"] == truth["summary"]["bytes"], f"device bytes {device['bytes']}")
        bad.check(device["line"] == f"{BAUD} 8N1", f"device line {device['line']}")
        bad.check(device["outages"] == 0, f"outages {device['outages']}")
        # A pty has no line error counters: reported as unsupported, never as zeros.
        bad.check(device["line_errors"] is None and "TIOCGICOUNT" in device["line_errors_note"],
                  f"line errors {device['line_errors']}, note {device.get('line_errors_note')}")
    # The one tap's bus is named by its device, live and in the written file alike.
    unnamed = [e["type"] for e in events[:-1] if e.get("bus") != pty.path]
    bad.check(not unnamed, f"{len(unnamed)} events do not name the bus {pty.path}")
    bad.check([b["bus"] for b in summary["buses"]] == [pty.path], f"buses {summary['buses']}")
    read_back = audit_frames(args, pcap)
    bad.check(all(f.get("bus") == pty.path for f in read_back),
              "the written file's frames lose the device's name")
    live = frames_of(events)
    bad.check([frame_key(f, "raw") for f in read_back] == [frame_key(f, "raw") for f in live],
              f"the written pcap holds {len(read_back)} frames that differ from the "
              f"{len(live)} reported live")
    return bad.exit_status("truth")


def check_damaged(args):
    """Damaged frames on a live tap, 30 ms silences around every frame: a GSL read request
    whose count a bit flip changed (02 03 04 06 40 04 with its original CRC) is one frame with
    a bad CRC, not noise, and the slave's silence after it is no timeout; a good request
    answered by a damaged reply is answered (a damaged reply with a latency), not a timeout."""
    bad = Failures()
    request = with_crc(bytes.fromhex("02 03 04 06 00 04"))
    reply = with_crc(bytes.fromhex("02 03 08 09 10 00 7B 00 00 11 94"))
    damaged_request = bytes.fromhex("02 03 04 06 40 04") + request[-2:]
    damaged_reply = bytearray(reply)
    damaged_reply[5] ^= 0x01
    plan = [(request, 0.03), (reply, 0.03), (damaged_request, 1.2), (request, 0.03),
            (bytes(damaged_reply), 0.03), (request, 0.03), (reply, 0.3)]
    events, t = [], 0.0
    for data, silence in plan:
        events.append({"ts": t, "hex": data.hex()})
        t += len(data) * 10 / BAUD + silence
    pty = pty_bus.Pty()
    sniffer = Sniffer(args.pvtap, args.scratch, "damaged",
                      ["--device", pty.path, "--format", "jsonl", "--timeout", "1"])
    sniffer.wait_open(pty.path)
    start = time.monotonic()
    pty_bus.play(pty.master, pty_bus.byte_schedule(events, BAUD), start)
    time.sleep(max(0.0, start + t + 0.3 - time.monotonic()))
    bad.check(sniffer.stop() == 0, f"exit status {sniffer.proc.returncode}: {sniffer.stderr()}")
    pty.close()
    out = sniffer.events()
    frames = frames_of(out)
    got = [(f["raw"], f["check"]) for f in frames]
    want = [(data.hex(), "ok" if data in (request, reply) else "bad") for data, _ in plan]
    bad.check(got == want, f"frames: pvtap {got}, the bus carried {want}")
    bad.check(not [e for e in out if e["type"] == "noise"], "noise reported")
    summary = out[-1]
    for key, value in (("timeouts", 0), ("damaged_replies", 1), ("unanswered_damaged_requests", 1),
                       ("bad_checks", 2), ("noise_bytes", 0)):
        bad.check(summary.get(key) == value, f"summary {key}: {summary.get(key)}, want {value}")
    if len(frames) == len(plan):
        bad.check(frames[4].get("latency_ms", 0) > 0, f"the damaged reply has no latency")
    return bad.exit_status("damaged")


def check_killed(args):
    """An abrupt end (SIGKILL: no handler runs) loses nothing --write already had: the pcap
    reads back whole, holding at least every frame pvtap had reported, in the same order."""
    bad = Failures()
    truth = simulate(args, "killed", "--dialect", "gsl,ascii", "--inverters", "2", "--duration",
                     "2", "--seed", "11")
    pcap = os.path.join(args.scratch, "killed.pcap")
    pty = pty_bus.Pty()
    sniffer = Sniffer(args.pvtap, args.scratch, "killed",
                      ["--device", pty.path, "--format", "jsonl", "--write", pcap])
    sniffer.wait_open(pty.path)
    play_truth(pty, truth)
    bad.check(sniffer.stop(signal.SIGKILL) == -signal.SIGKILL, "pvtap outlived SIGKILL")
    pty.close()
    reported = [frame_key(f, "raw") for f in frames_of(sniffer.events())]
    read_back = [frame_key(f, "raw") for f in audit_frames(args, pcap)]
    bad.check(len(reported) > 0, "pvtap reported no frame before it was killed")
    bad.check(read_back[:len(reported)] == reported,
              f"the pcap holds {len(read_back)} frames that do not start with the "
              f"{len(reported)} reported")
    return bad.exit_status("killed")


def descriptor_flags(pid, fd):
    with open(f"/proc/{pid}/fdinfo/{fd}", encoding="ascii") as f:
        for line in f:
            if line.startswith("flags:"):
                return int(line.split()[1], 8)
    raise RuntimeError("no flags in fdinfo")


def check_passive(args):
    """The device is opened read-only, non-blocking, not as controlling terminal, closed on
    exec; and not one byte comes out of it while pvtap runs."""
    bad = Failures()
    truth = simulate(args, "passive", "--dialect", "gsl", "--inverters", "2", "--duration", "2",
                     "--seed", "4")
    pty = pty_bus.Pty()
    sniffer = Sniffer(args.pvtap, args.scratch, "passive", ["--device", pty.path, "--format",
                                                             "jsonl"])
    sniffer.wait_open(pty.path)
    play_truth(pty, truth)
    fds = sniffer.fds_on(pty.path)
    bad.check(len(fds) == 1, f"pvtap holds {len(fds)} descriptors on the device")
    for fd in fds:
        flags = descriptor_flags(sniffer.proc.pid, fd)
        bad.check(flags & os.O_ACCMODE == os.O_RDONLY, f"fd {fd} flags {flags:o}: not O_RDONLY")
        bad.check(flags & os.O_NONBLOCK, f"fd {fd} flags {flags:o}: not O_NONBLOCK")
        bad.check(flags & 0o2000000, f"fd {fd} flags {flags:o}: not O_CLOEXEC")
    bad.check(sniffer.stop(signal.SIGINT) == 0, f"exit status {sniffer.proc.returncode}")
    written = pty.drain_master()
    bad.check(written == b"", f"the master side received {len(written)} bytes: {written[:32]!r}")
    pty.close()
    events = sniffer.events()
    bad.check(len(frames_of(events)) == truth["summary"]["frames"], "frames missing")
    bad.check(events[-1].get("stopped_by_signal") is True, "Ctrl-C: no summary or not by signal")
    return bad.exit_status("passive")


def check_unplug(args):
    """The pty behind a by-id style link goes away and comes back as another pty: pvtap
    reports the outage as a gap, reopens the link and goes on."""
    bad = Failures()
    before = simulate(args, "before", "--dialect", "hybrid", "--inverters", "2", "--duration",
                      "2", "--seed", "5")
    after = simulate(args, "after", "--dialect", "hybrid", "--inverters", "2", "--duration", "2",
                     "--seed", "6")
    link = os.path.join(args.scratch, "usb-FTDI_tap-if00-port0")
    first = pty_bus.Pty()
    replace_link(link, first.path)
    sniffer = Sniffer(args.pvtap, args.scratch, "unplug", ["--device", link, "--format", "jsonl"])
    sniffer.wait_open(link)
    play_truth(first, before)
    first.unplug()
    time.sleep(0.5)
    second = pty_bus.Pty()
    replace_link(link, second.path)
    sniffer.wait_open(link)
    play_truth(second, after)
    bad.check(sniffer.stop() == 0, f"exit status {sniffer.proc.returncode}")
    second.close()
    events = sniffer.events()
    truth_frames = [e for t in (before, after) for e in t["events"] if e["type"] == "frame"]
    compare_frames(frames_of(events), truth_frames, "unplug", bad)
    gaps = [e for e in events if e["type"] == "gap"]
    bad.check(len(gaps) == 1, f"{len(gaps)} gap events, expected the one outage")
    device = events[-1]["devices"][0]
    bad.check(device["outages"] == 1, f"outages {device['outages']}")
    bad.check(device["outage_seconds"] > 0, "no outage time")
    bad.check(device["lost_at_end"] is False, "reported lost at the end")
    bad.check(events[-1]["gaps"] == 1, f"summary gaps {events[-1]['gaps']}")
    text = sniffer.stderr()
    bad.check("gone" in text and "back after" in text, f"stderr does not tell: {text!r}")
    return bad.exit_status("unplug")


def replace_link(link, target):
    temporary = link + ".new"
    if os.path.lexists(temporary):
        os.unlink(temporary)
    os.symlink(target, temporary)
    os.replace(temporary, link)


def check_two_buses(args):
    """Two taps at once: each is its own bus, named by its path."""
    bad = Failures()
    truths = [simulate(args, "bus_a", "--dialect", "gsl", "--inverters", "2", "--duration", "3",
                       "--seed", "7"),
              simulate(args, "bus_b", "--dialect", "ascii", "--inverters", "3", "--duration",
                       "3", "--seed", "8")]
    ptys = [pty_bus.Pty(), pty_bus.Pty()]
    sniffer = Sniffer(args.pvtap, args.scratch, "two_buses",
                      ["--device", ptys[0].path, "--device", ptys[1].path, "--format", "jsonl"])
    for pty in ptys:
        sniffer.wait_open(pty.path)
    players = [threading.Thread(target=play_truth, args=(pty, truth))
               for pty, truth in zip(ptys, truths)]
    for player in players:
        player.start()
    for player in players:
        player.join()
    bad.check(sniffer.stop() == 0, f"exit status {sniffer.proc.returncode}")
    events = sniffer.events()
    for pty, truth in zip(ptys, truths):
        compare_frames(frames_of(events, pty.path),
                       [e for e in truth["events"] if e["type"] == "frame"], pty.path, bad)
        pty.close()
    devices = [d["path"] for d in events[-1]["devices"]]
    bad.check(devices == [p.path for p in ptys], f"devices in the summary: {devices}")
    buses = [b["bus"] for b in events[-1]["buses"]]
    bad.check(sorted(buses) == sorted(p.path for p in ptys), f"buses in the summary: {buses}")
    return bad.exit_status("two_buses")


def check_stop_conditions(args):
    """--count stops after that many frames, --duration after that long; both exit 0 with
    the summary, not by signal."""
    bad = Failures()
    truth = simulate(args, "count", "--dialect", "gsl", "--inverters", "2", "--duration", "2",
                     "--seed", "9")
    pty = pty_bus.Pty()
    sniffer = Sniffer(args.pvtap, args.scratch, "count",
                      ["--device", pty.path, "--format", "jsonl", "--count", "5"])
    sniffer.wait_open(pty.path)
    play_truth(pty, truth)
    bad.check(sniffer.wait() == 0, f"--count: exit status {sniffer.proc.returncode}")
    events = sniffer.events()
    bad.check(len(frames_of(events)) == 5, f"--count 5 reported {len(frames_of(events))} frames")
    bad.check(events[-1].get("stopped_by_signal") is False, "--count: stopped_by_signal")
    sniffer = Sniffer(args.pvtap, args.scratch, "duration",
                      ["--device", pty.path, "--format", "jsonl", "--duration", "0.5"])
    bad.check(sniffer.wait() == 0, f"--duration: exit status {sniffer.proc.returncode}")
    summary = sniffer.events()[-1]
    bad.check(summary.get("live_seconds", 0) >= 0.5, f"--duration 0.5 ran {summary}")
    bad.check(summary.get("stopped_by_signal") is False, "--duration: stopped_by_signal")
    pty.close()
    return bad.exit_status("stop_conditions")


def check_files(args):
    """--values and --html on a live tap stopped by SIGTERM: the values file holds a row per
    value of every good reply, the HTML page is written at the stop and its tiles show the
    summary's numbers."""
    bad = Failures()
    truth = simulate(args, "files", "--dialect", "gsl,hybrid", "--inverters", "2", "--duration",
                     "3", "--seed", "12", "--faults", "corrupt=10,missing=10")
    values, html = os.path.join(args.scratch, "values.csv"), os.path.join(args.scratch, "bus.html")
    pty = pty_bus.Pty()
    sniffer = Sniffer(args.pvtap, args.scratch, "files",
                      ["--device", pty.path, "--format", "jsonl", "--values", values,
                       "--html", html, "--timeout", str(truth["timeout_s"])])
    sniffer.wait_open(pty.path)
    play_truth(pty, truth)
    # Rows reach the file while the capture runs (a Telegraf tail would read them then).
    deadline = time.monotonic() + 5
    while time.monotonic() < deadline and os.path.getsize(values) < 200:
        time.sleep(0.05)
    bad.check(os.path.getsize(values) >= 200, "no --values rows written before the stop")
    bad.check(sniffer.stop() == 0, f"exit status {sniffer.proc.returncode}: {sniffer.stderr()}")
    pty.close()
    events = sniffer.events()
    expected = sum(len(e["values"]) for e in frames_of(events)
                   if e["role"] == "response" and e["check"] == "ok")
    with open(values, encoding="utf-8") as f:
        rows = f.read().splitlines()
    bad.check(rows and rows[0] == "ts,bus,station,dialect,register,key,name,value,unit",
              f"values header {rows[:1]}")
    bad.check(expected > 0 and len(rows) - 1 == expected,
              f"{len(rows) - 1} value rows, the frames carry {expected} values")
    with open(html, encoding="utf-8") as f:
        page = f.read()
    tiles = dict(re.findall(r'data-key="([a-z_]+)"><span class="value">(\d+)<', page))
    summary = events[-1]
    for key in ("frames", "bad_checks", "timeouts", "exceptions", "noise_bytes"):
        bad.check(tiles.get(key) == str(summary[key]),
                  f"HTML tile {key} {tiles.get(key)}, summary {summary[key]}")
    bad.check("pvtap sniff report" in page, "the page is not titled as a sniff report")
    return bad.exit_status("files")


def check_status_line(args):
    """Text output with stderr on a terminal redraws a status line there; with stderr not a
    terminal there is none."""
    bad = Failures()
    truth = simulate(args, "status", "--dialect", "gsl", "--inverters", "2", "--duration", "2",
                     "--seed", "10")
    pty = pty_bus.Pty()
    terminal = pty_bus.Pty()
    with open(terminal.path, "w") as stderr:
        sniffer = Sniffer(args.pvtap, args.scratch, "status", ["--device", pty.path],
                          stderr=stderr)
    sniffer.wait_open(pty.path)
    play_truth(pty, truth)
    bad.check(sniffer.stop() == 0, f"exit status {sniffer.proc.returncode}")
    shown = terminal.drain_master().decode("utf-8", "replace")
    frames = truth["summary"]["frames"]
    # The line is redrawn as frames complete; the last drawing counts every frame.
    bad.check(f"{frames} frames" in shown, f"no status line with {frames} frames: {shown!r}")
    bad.check("bad checks" in shown and "timeouts" in shown and "last latency" in shown,
              f"status line lacks a count: {shown!r}")
    plain = Sniffer(args.pvtap, args.scratch, "status_plain",
                    ["--device", pty.path, "--duration", "0.3"])
    plain.wait()
    bad.check("frames" not in plain.stderr(), f"status line without a terminal: "
                                              f"{plain.stderr()!r}")
    pty.close()
    terminal.close()
    return bad.exit_status("status_line")


def check_bad_devices(args):
    """Devices that cannot be sniffed: exit 2 with a message that names the problem."""
    bad = Failures()
    regular = os.path.join(args.scratch, "not-a-tty")
    with open(regular, "w") as f:
        f.write("x")
    pty = pty_bus.Pty()
    cases = [
        (["--device", "/dev/ttyUSB-pvtap-missing"], ["/dev/ttyUSB-pvtap-missing",
                                                     "No such file"]),
        (["--device", regular], [regular]),
        (["--device", pty.path, "--baud", "600"], ["600", "1200 to 115200"]),
        (["--device", pty.path, "--parity", "mark"], ["mark"]),
        (["--device", pty.path, "--stop-bits", "3"], ["3"]),
        (["--device", pty.path, "--port", "502"], ["--interface"]),
        ([], ["--device"]),
    ]
    for extra, words in cases:
        run = subprocess.run([args.pvtap, "sniff", "--duration", "0.2", *extra],
                             capture_output=True, text=True, timeout=GUARD_S, check=False)
        bad.check(run.returncode == 2, f"{extra}: exit status {run.returncode}")
        bad.check(all(w in run.stderr for w in words),
                  f"{extra}: the message {run.stderr.strip()!r} does not name {words}")
        bad.check(run.stdout == "", f"{extra}: output on stdout: {run.stdout[:200]!r}")
    pty.close()
    return bad.exit_status("bad_devices")


def check_duplex(args):
    """--duplex: two taps on the two pairs of a 4-wire bus, requests on the first, replies and
    noise on the second, are one bus: the truth's frames in order, its noise, timeouts and
    totals; both devices opened read-only and never written (strace); the options refused
    without two devices or with --baud auto."""
    import check_baud_auto  # noqa: E402 (it imports this module)
    bad = Failures()
    truth = simulate(args, "duplex", "--dialect", "gsl,hybrid", "--inverters", "3",
                     "--duration", "6", "--seed", "3", "--faults", "all", "--meter", "10")
    ptys = [pty_bus.Pty(), pty_bus.Pty()]
    trace = os.path.join(args.scratch, "duplex.strace")
    out_path = os.path.join(args.scratch, "duplex.out")
    with open(out_path, "w") as out, open(os.path.join(args.scratch, "duplex.err"), "w") as err:
        proc = subprocess.Popen(["strace", "-f", "-qq", "-o", trace, "-e",
                                 "trace=openat,write,writev,pwrite64,pwritev,pwritev2",
                                 args.pvtap, "sniff", "--duplex", "--device", ptys[0].path,
                                 "--device", ptys[1].path, "--format", "jsonl",
                                 "--timeout", str(truth["timeout_s"])], stdout=out, stderr=err)
        for pty in ptys:
            check_baud_auto.wait_for_open(trace, pty.path, proc)
        start = time.monotonic()
        pty_bus.play_duplex([p.master for p in ptys], truth["events"], BAUD, start)
        time.sleep(max(0.0, start + stop_offset(truth) - time.monotonic()))
        os.kill(check_baud_auto.traced_pid(proc), signal.SIGTERM)
        bad.check(proc.wait(GUARD_S) == 0, f"exit status {proc.returncode}")
    with open(out_path, encoding="utf-8") as f:
        events = [json.loads(line) for line in f if line.strip()]
    check_events(events, truth, bad, "duplex")
    summary = events[-1]
    name = ptys[0].path + "+" + ptys[1].path
    if bad.check(summary.get("type") == "summary", "the last line is not the summary"):
        check_summary(summary, truth, bad)
        bad.check([b["bus"] for b in summary["buses"]] == [name], f"buses {summary['buses']}")
        bad.check(len(summary["devices"]) == 2, f"devices {summary['devices']}")
    for pty in ptys:
        opened, writes = check_baud_auto.device_writes(trace, pty.path)
        bad.check(opened and all("O_RDONLY" in line for line in opened),
                  f"{pty.path} opened as {opened}")
        bad.check(not writes, f"writes to {pty.path}: {writes[:3]}")
        bad.check(pty.drain_master() == b"", f"{pty.path}: bytes came out of pvtap's side")
        pty.close()
    for extra, words in ((["--device", "/dev/null"], "two --device"),
                         (["--device", "/dev/null", "--device", "/dev/zero", "--baud", "auto"],
                          "--baud")):
        run = subprocess.run([args.pvtap, "sniff", "--duplex", *extra], capture_output=True,
                             text=True, check=False, timeout=GUARD_S)
        bad.check(run.returncode == 2 and words in run.stderr,
                  f"--duplex {extra}: exit {run.returncode}, stderr {run.stderr!r}")
    return bad.exit_status("duplex")


def check_duplex_unplug(args):
    """--duplex: the replies' adapter goes away and comes back as another pty while the
    requests' adapter stays: one gap, of the replies' direction; every frame of the truth before
    and after, the requests' ones read on throughout."""
    bad = Failures()
    before = simulate(args, "dx-before", "--dialect", "gsl", "--inverters", "2", "--duration",
                      "2", "--seed", "5")
    after = simulate(args, "dx-after", "--dialect", "gsl", "--inverters", "2", "--duration", "2",
                     "--seed", "6")
    link = os.path.join(args.scratch, "usb-FTDI_replies-if00-port0")
    requests, replies = pty_bus.Pty(), pty_bus.Pty()
    replace_link(link, replies.path)
    sniffer = Sniffer(args.pvtap, args.scratch, "duplex-unplug",
                      ["--duplex", "--device", requests.path, "--device", link, "--format",
                       "jsonl"])
    sniffer.wait_open(link)
    for truth in (before, after):
        start = time.monotonic()
        pty_bus.play_duplex([requests.master, replies.master], truth["events"], BAUD, start)
        time.sleep(max(0.0, start + stop_offset(truth) - time.monotonic()))
        if truth is before:
            replies.unplug()
            time.sleep(0.5)
            replies = pty_bus.Pty()
            replace_link(link, replies.path)
            sniffer.wait_open(link)
    bad.check(sniffer.stop() == 0, f"exit status {sniffer.proc.returncode}")
    requests.close()
    replies.close()
    events = sniffer.events()
    truth_frames = [e for t in (before, after) for e in t["events"] if e["type"] == "frame"]
    compare_frames(frames_of(events), truth_frames, "duplex unplug", bad)
    gaps = [e for e in events if e["type"] == "gap"]
    bad.check([g["direction"] for g in gaps] == ["from_slave"],
              f"gaps {gaps}, expected one of the replies' direction")
    devices = {d["path"]: d for d in events[-1]["devices"]}
    bad.check(devices[link]["outages"] == 1 and devices[requests.path]["outages"] == 0,
              f"outages {[(p, d['outages']) for p, d in devices.items()]}")
    text = sniffer.stderr()
    bad.check("gone" in text and "back after" in text, f"stderr does not tell: {text!r}")
    return bad.exit_status("duplex_unplug")


CHECKS = {
    "truth": check_truth,
    "passive": check_passive,
    "killed": check_killed,
    "unplug": check_unplug,
    "damaged": check_damaged,
    "two_buses": check_two_buses,
    "stop_conditions": check_stop_conditions,
    "status_line": check_status_line,
    "bad_devices": check_bad_devices,
    "files": check_files,
    "duplex": check_duplex,
    "duplex_unplug": check_duplex_unplug,
}


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--pvtap", required=True)
    parser.add_argument("--sim", required=True)
    parser.add_argument("--scratch", required=True)
    parser.add_argument("check", choices=sorted(CHECKS))
    args = parser.parse_args()
    args.scratch = os.path.join(args.scratch, args.check)
    os.makedirs(args.scratch, exist_ok=True)
    return CHECKS[args.check](args)


if __name__ == "__main__":
    sys.exit(main())
