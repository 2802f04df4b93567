#!/usr/bin/env python3
"""pvtap audit and pvtap sniff --interface on Solarman V5 logger-stick flows.

audit: captures written here (tests/dissector/v5_frames.py encodes V5 independently of the
core): 30 reads through a stick, every fifth reply with the two extra zeros, a heartbeat and
its answer, one reply dropped, one V5 checksum broken; the same on a --port; beside an RTU
gateway and other traffic; a stick whose lengths lie and whose last reply is cut. The summary
counts must be exactly the script's. The stick of V5 client libraries' issue threads: replies
paired by sequence byte, the stick's codes 05 and 06, text before a V5 frame. The library's
V5 samples: the stick's counts must be the simulator's truth.

sniff: the same script, and the issue threads' stick, played over real TCP on lo between a
client and a stick written here, while `pvtap sniff --interface lo --port P` captures it;
after SIGTERM its summary must give the same counts and verdicts. Exits 77 (skipped) when
not root (capturing on lo is refused).

usage: check_solarman_v5.py --pvtap PVTAP audit|sniff
"""
import argparse
import glob
import json
import os
import signal
import socket
import subprocess
import sys
import tempfile
import threading
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "dissector"))

from bus_frames import gsl_read_reply, rtu_read_request  # noqa: E402
from pcap_writer import Pcap, TcpFlow  # noqa: E402
from v5_frames import (SERIAL, VERSION_TEXT, broken_stick, stick_reads,  # noqa: E402
                       stick_script, threads_steps, threads_stick)

SKIP = 77
RUN_GUARD_S = 120  # the longest one pvtap run may take: a guard, not a timing check
PATIENCE_S = 30.0  # waits are for processes to get somewhere; running out is a failure
BUS = "v5:%d" % SERIAL


class Failure(Exception):
    pass


def run_audit(pvtap, capture, *args):
    run = subprocess.run([pvtap, "audit", "--format", "jsonl", *args, capture],
                         capture_output=True, text=True, timeout=RUN_GUARD_S)
    if run.returncode != 0:
        raise Failure("pvtap audit exited %d: %s" % (run.returncode, run.stderr.strip()))
    return [json.loads(line) for line in run.stdout.splitlines() if line.strip()]


def expect_counts(name, events, script, bad, rtu_flows=0):
    """The summary's counts are the script's; every frame of the stick is on its bus."""
    summary = events[-1]
    frames = [e for e in events if e.get("type") == "frame"]
    stick = [e for e in frames if e.get("bus") == BUS]
    want = {"requests": script.requests, "responses": script.responses,
            "timeouts": script.timeouts, "noise_bytes": 0, "bad_checks": 0}
    for key, value in want.items():
        extra = rtu_flows if key in ("requests", "responses") else 0
        if summary.get(key) != value + extra:
            bad.append("%s: summary %s %s, expected %s" % (name, key, summary.get(key),
                                                          value + extra))
    if len(stick) != script.requests + script.responses:
        bad.append("%s: %d frames on bus %s, expected %d" % (name, len(stick), BUS,
                                                             script.requests + script.responses))
    v5 = (summary.get("network") or {}).get("solarman_v5") or {}
    for key, value in script.v5.items():
        if v5.get(key) != value:
            bad.append("%s: solarman_v5 %s %s, expected %s" % (name, key, v5.get(key), value))
    timing = [b for b in summary.get("buses", []) if b.get("bus") == BUS]
    reason = timing[0]["timing"].get("reason", "") if timing else ""
    if "latency is measured at the LAN side" not in reason:
        bad.append("%s: bus %s does not say its latency is measured at the LAN side" % (name, BUS))


def write(pcap, directory, name):
    path = os.path.join(directory, name)
    pcap.write(path)
    return path


def rtu_gateway(pcap):
    """A bare RTU gateway beside the stick: two reads answered."""
    flow = TcpFlow(pcap, client=("10.0.0.1", 50400), server=("10.0.0.9", 4001), time=200.0)
    for i in range(2):
        flow.request(rtu_read_request(2, 0x03, 1050, 1), after=0.5)
        flow.reply(gsl_read_reply(2, [2300 + i]), after=0.05)
    return 2


def other_traffic(pcap):
    flow = TcpFlow(pcap, client=("10.0.0.1", 50500), server=("10.0.0.10", 80), time=300.0)
    flow.request(b"GET / HTTP/1.1\r\nHost: x\r\n\r\n")
    flow.reply(b"HTTP/1.1 200 OK\r\nContent-Length: 2\r\n\r\nok")


def check_audit(args):
    bad = []
    with tempfile.TemporaryDirectory() as tmp:
        pcap = Pcap()
        script = stick_reads(pcap)
        reads = write(pcap, tmp, "stick.pcap")
        expect_counts("stick", run_audit(args.pvtap, reads), script, bad)
        expect_counts("stick --port", run_audit(args.pvtap, reads, "--port", "48899"), script,
                      bad)
        text = subprocess.run([args.pvtap, "audit", "--summary-only", reads],
                              capture_output=True, text=True, timeout=RUN_GUARD_S).stdout
        for line in ("Solarman V5 logger sticks: 1 flows, 61 V5 frames (59 with an RTU frame; 1 of the sticks",
                     "12 quirk bytes (two zeros after the RTU CRC) in 6 replies",
                     "V5 findings: 1 bad checksums", "-- bus %s --" % BUS):
            if line not in text:
                bad.append("text report: no line with %r" % line)

        pcap = Pcap()
        script = stick_reads(pcap)
        rtu = rtu_gateway(pcap)
        other_traffic(pcap)
        events = run_audit(args.pvtap, write(pcap, tmp, "mixed.pcap"))
        expect_counts("mixed", events, script, bad, rtu_flows=rtu)
        network = events[-1].get("network", {})
        if (network.get("flows_analyzed"), network.get("flows_ignored")) != (2, 1):
            bad.append("mixed: flows %s analyzed, %s ignored, expected 2 and 1" %
                       (network.get("flows_analyzed"), network.get("flows_ignored")))

        pcap = Pcap()
        script = broken_stick(pcap)
        expect_counts("broken", run_audit(args.pvtap, write(pcap, tmp, "broken.pcap")), script,
                      bad)
        bad += check_threads_stick(args, tmp)
    return bad


def check_threads_stick(args, tmp):
    """Latencies 200, 600 and 600 ms at the LAN side (less each reply's 7 bytes on the wire at
    9600 baud, as pvtap times a stick's frames)."""
    pcap = Pcap()
    threads_stick(pcap)
    events = run_audit(args.pvtap, write(pcap, tmp, "threads.pcap"))
    bad = threads_verdicts("threads", events)
    wire_ms = 7 * 10 * 1000 / 9600
    latencies = [e.get("latency_ms") for e in events
                 if e.get("type") == "frame" and e.get("role") == "response"]
    want = [round(ms - wire_ms, 3) for ms in (200, 600, 600)]
    if [round(x or 0, 3) for x in latencies] != want:
        bad.append("threads: latencies %s, expected %s" % (latencies, want))
    return bad


def threads_verdicts(name, events):
    """Each reply answers its own request; code 05 a timeout with its reason; the refusal said
    plainly, on no bus of its own; the text counted apart."""
    bad = []
    summary = events[-1]
    timeouts = [e for e in events if e.get("type") == "timeout"]
    if [(t["reason"], t.get("carrier_reason")) for t in timeouts] != \
            [("carrier_no_reply", "the stick answered code 05")]:
        bad.append("%s: timeouts %s, expected the one code 05 answered" % (name, timeouts))
    keys = ("timeouts", "gateway_timeouts", "noise_bytes", "requests", "responses",
            "unsolicited", "duplicates")
    if [summary.get(k) for k in keys] != [1, 1, 0, 4, 3, 0, 0]:
        bad.append("%s: summary %s %s" % (name, keys, [summary.get(k) for k in keys]))
    if [b["bus"] for b in summary["buses"]] != ["v5:4068039735"]:
        bad.append("%s: buses %s" % (name, [b["bus"] for b in summary["buses"]]))
    v5 = summary["network"]["solarman_v5"]
    got = {k: v5.get(k) for k in ("stick_codes", "stick_timeouts", "refused_requests",
                                  "replies_after_next_request", "noise_bytes", "stick_findings")}
    expected = {"stick_codes": 2, "stick_timeouts": 1, "refused_requests": 1,
                "replies_after_next_request": 1, "noise_bytes": len(VERSION_TEXT),
                "stick_findings": ["the client addressed logger 2111130827; the stick is "
                                   "4068039735"]}
    if got != expected:
        bad.append("%s: solarman_v5 %s, expected %s" % (name, got, expected))
    return bad


# The simulator's truth of a V5 sample (captures/samples/*.truth.json, "v5") and the summary's
# name for the same count.
TRUTH_COUNTS = {"frames": "frames", "stick_frames": "stick_frames", "heartbeats": "heartbeats",
                "data_reports": "data_reports", "client_answers": "stick_answers",
                "carrier_bytes": "carrier_bytes", "rtu_bytes": "rtu_bytes",
                "quirk_bytes": "quirk_bytes", "bad_checksums": "bad_checksums"}


def check_samples(args):
    """The library's V5 samples: the stick's counts are the simulator's truth."""
    bad = []
    samples = sorted(glob.glob(os.path.join(HERE, "..", "..", "..", "captures", "samples",
                                            "*.v5.pcap")))
    if not samples:
        return ["no V5 sample in captures/samples"]
    for sample in samples:
        with open(sample.replace(".v5.pcap", ".truth.json")) as f:
            truth = json.load(f)["v5"]
        v5 = run_audit(args.pvtap, sample, "--summary-only")[-1]["network"]["solarman_v5"]
        for theirs, ours in TRUTH_COUNTS.items():
            if v5.get(ours) != truth[theirs]:
                bad.append("%s: %s %s, truth %s" % (os.path.basename(sample), ours, v5.get(ours),
                                                    truth[theirs]))
    return bad


class Stick(threading.Thread):
    """The stick's side of the script: answers each request with its step's frame."""

    def __init__(self, steps):
        super().__init__(daemon=True)
        self.server = socket.socket()
        self.server.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
        self.server.bind(("127.0.0.1", 0))
        self.server.listen(1)
        self.port = self.server.getsockname()[1]
        self.steps = steps
        self.error = None

    def run(self):
        try:
            conn, _ = self.server.accept()
            conn.setsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1)
            with conn:
                for step in self.steps:
                    if step.from_stick:
                        time.sleep(0.01)
                        conn.sendall(step.frame)
                    else:
                        receive_exactly(conn, len(step.frame))
                conn.recv(1)  # the client hangs up
        except OSError as e:
            self.error = e
        finally:
            self.server.close()


def receive_exactly(sock, n):
    got = b""
    while len(got) < n:
        chunk = sock.recv(n - len(got))
        if not chunk:
            raise OSError("the peer closed after %d of %d bytes" % (len(got), n))
        got += chunk
    return got


def play_client(port, steps):
    """The client's side: sends its frames in order, reading each of the stick's before the
    next; a request whose reply was dropped is followed by the next after 0.2 s."""
    with socket.create_connection(("127.0.0.1", port), timeout=PATIENCE_S) as c:
        c.setsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1)
        for step in steps:
            if step.from_stick:
                receive_exactly(c, len(step.frame))
            else:
                time.sleep(0.2 if step.name.startswith("request") else 0.01)
                c.sendall(step.frame)


def wait_for(condition, what):
    deadline = time.monotonic() + PATIENCE_S
    while not condition():
        if time.monotonic() > deadline:
            raise Failure("gave up after %.0f s waiting for %s" % (PATIENCE_S, what))
        time.sleep(0.05)


def read_text(path):
    with open(path, errors="replace") as f:
        return f.read()


def sniff_script(args, steps, tmp, name):
    """`steps` played over lo while pvtap sniff --interface captures them: its events."""
    stick = Stick(steps)
    out_path, err_path = os.path.join(tmp, name + ".out"), os.path.join(tmp, name + ".err")
    with open(out_path, "w") as out, open(err_path, "w") as err:
        sniff = subprocess.Popen([args.pvtap, "sniff", "--interface", "lo", "--port",
                                  str(stick.port), "--format", "jsonl"], stdout=out, stderr=err)
    try:
        wait_for(lambda: "pvtap: capturing on lo" in read_text(err_path) or
                 sniff.poll() is not None, "pvtap sniff to start capturing")
        if sniff.poll() is not None:
            raise Failure("pvtap sniff exited %d: %s" % (sniff.returncode,
                                                         read_text(err_path).strip()))
        stick.start()
        play_client(stick.port, steps)
        stick.join(PATIENCE_S)
        if stick.error:
            raise Failure("the stick: %s" % stick.error)
        time.sleep(1.0)  # the last packets cross lo into pvtap's buffer
        sniff.send_signal(signal.SIGTERM)
        status = sniff.wait(timeout=PATIENCE_S)
    finally:
        if sniff.poll() is None:
            sniff.kill()
            sniff.wait()
    if status != 0:
        raise Failure("pvtap sniff exited %d: %s" % (status, read_text(err_path).strip()))
    events = [json.loads(line) for line in read_text(out_path).splitlines() if line.strip()]
    if not events or events[-1].get("type") != "summary":
        raise Failure("pvtap sniff wrote no summary")
    return events


def check_sniff(args):
    if os.geteuid() != 0:
        print("skipped: capturing on lo needs root")
        sys.exit(SKIP)
    bad = []
    with tempfile.TemporaryDirectory() as tmp:
        steps, script = stick_script()
        expect_counts("sniff", sniff_script(args, steps, tmp, "reads"), script, bad)
        bad += threads_verdicts("sniff threads", sniff_script(args, threads_steps(), tmp,
                                                              "threads"))
    return bad


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--pvtap", required=True)
    parser.add_argument("check", choices=["audit", "sniff"])
    args = parser.parse_args()
    try:
        bad = check_audit(args) + check_samples(args) if args.check == "audit" else \
            check_sniff(args)
    except Failure as e:
        bad = [str(e)]
    for line in bad:
        print("FAIL:", line)
    print("ok" if not bad else "%d failures" % len(bad))
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
