#!/usr/bin/env python3
"""End-to-end checks of `pvtap sniff --interface` on the loopback interface.

gateway: pvtap-sim plays a simulated bus in real time onto a pseudo-terminal. This script is
the master's and the bus's wiring: it sends each request over TCP to a serial-to-TCP gateway
(socat, bridging a TCP port on 127.0.0.1 to a second pseudo-terminal) and writes each reply
into that terminal, so that the gateway sends it back. Real TCP segments cross lo both ways
while `pvtap sniff --interface lo --port P` and `tcpdump -i lo` capture them. After SIGTERM,
pvtap must exit 0, and its frames and summary counts must equal both `pvtap audit --port P`
on tcpdump's file and the simulator's ground truth.

no-such-interface, bad-filter: the capture cannot start; pvtap exits 2 with the reason.

usage: check_live_interface.py --pvtap PVTAP [--sim PVTAP_SIM --scratch DIR] CHECK

Exits 77 (skipped) when capturing on lo is impossible because the test does not run as root.
"""
import argparse
import json
import os
import select
import shutil
import signal
import socket
import struct
import subprocess
import sys
import time
import tty

# The longest one program this test runs may take: a guard, not a timing check. On expiry
# subprocess raises TimeoutExpired, which names the command that was waited for.
RUN_GUARD_S = 120

SKIP = 77
# Waits are for processes to get somewhere; running out of one is a failure, never a pass.
PATIENCE_S = 30.0
SUMMARY_KEYS = ("bytes", "frames", "requests", "responses", "bad_checks", "timeouts",
                "noise_bytes", "exceptions")
FRAME_FIELDS = ("role", "station", "function", "check")
# A mixed bus with bad checks, missing replies (timeouts), error replies and noise. Its last
# request is answered: one left waiting at the end would become a timeout in the live capture
# or not, depending on how long after it the capture stops.
SIM_ARGS = ["--seed", "23", "--dialect", "gsl,hybrid,ascii", "--inverters", "3",
            "--duration", "4", "--period", "1", "--baud", "19200",
            "--faults", "corrupt=15,missing=10,error_reply=10,noise=10"]


class Failure(Exception):
    pass


def wait_for(condition, what):
    deadline = time.monotonic() + PATIENCE_S
    while not condition():
        if time.monotonic() > deadline:
            raise Failure(f"gave up after {PATIENCE_S:.0f} s waiting for {what}")
        time.sleep(0.05)


def read_text(path):
    try:
        with open(path, encoding="utf-8", errors="replace") as f:
            return f.read()
    except FileNotFoundError:
        return ""


def jsonl(text):
    return [json.loads(line) for line in text.splitlines() if line.strip()]


def capture_refused_for_privilege(pvtap):
    """True when this user may not capture on lo (not root, no capabilities)."""
    if os.geteuid() == 0:
        return False
    run = subprocess.run([pvtap, "sniff", "--interface", "lo", "--duration", "0.1",
                          "--summary-only"], capture_output=True, text=True, check=False,
                         timeout=RUN_GUARD_S)
    return run.returncode == 2 and "permission denied" in run.stderr


class Processes:
    """The background processes of a check, each stopped by its own id at the end."""

    def __init__(self):
        self.procs = []

    def start(self, args, **kwargs):
        proc = subprocess.Popen(args, **kwargs)
        self.procs.append(proc)
        return proc

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        for proc in self.procs:
            if proc.poll() is None:
                proc.kill()
            proc.wait()


def listening(port):
    """A TCP socket in state LISTEN on 127.0.0.1:port, read from the kernel."""
    needle = f"0100007F:{port:04X} 00000000:0000 0A"
    return needle in read_text("/proc/net/tcp").upper()


def time_wait(local_port, remote_port):
    """The connection 127.0.0.1:local_port -> 127.0.0.1:remote_port is in TIME_WAIT."""
    needle = f"0100007F:{local_port:04X} 0100007F:{remote_port:04X} 06"
    return needle in read_text("/proc/net/tcp").upper()


def free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def pcap_records(path):
    """Number of records in a classic pcap file."""
    with open(path, "rb") as f:
        data = f.read()
    magic = data[:4]
    endian = "<" if magic in (b"\xd4\xc3\xb2\xa1", b"\x4d\x3c\xb2\xa1") else ">"
    count, at = 0, 24
    while at + 16 <= len(data):
        at += 16 + struct.unpack(endian + "I", data[at + 8:at + 12])[0]
        if at > len(data):
            break  # tcpdump is still writing this one
        count += 1
    return count


def audit(pvtap, capture, port):
    run = subprocess.run([pvtap, "audit", "--format", "jsonl", "--port", str(port), capture],
                         capture_output=True, text=True, check=False, timeout=RUN_GUARD_S)
    if run.returncode != 0:
        raise Failure(f"pvtap audit exited {run.returncode}: {run.stderr.strip()}")
    return jsonl(run.stdout)


def frames_of(events):
    return [e for e in events if e["type"] == "frame"]


def byte_sides(events):
    """For each bus byte in order: True when the master sends it (requests), False when the
    bus side does (replies and noise, which reach the master through the gateway)."""
    sides = []
    for e in events:
        sides.extend([e.get("role") == "request"] * (len(e["hex"]) // 2))
    return sides


def request_ends(events):
    """The bus offsets just past each request: where the master has a whole request to send."""
    ends, at = set(), 0
    for e in events:
        at += len(e["hex"]) // 2
        if e.get("role") == "request":
            ends.add(at)
    return ends


class Rig:
    """The simulated bus wired through a socat gateway on 127.0.0.1.

    Each side's bytes are passed on only once the other side's earlier bytes have crossed the
    gateway, so the TCP segments reach lo in bus order however the processes are scheduled."""

    def __init__(self, procs, sim, scratch, port):
        self.procs, self.sim, self.scratch, self.port = procs, sim, scratch, port
        self.got = {"gateway": bytearray(), "master": bytearray()}  # what each end received
        self.sent = {"gateway": 0, "master": 0}  # what was sent towards each end
        self.request = bytearray()

    def start_gateway(self):
        tty_path = os.path.join(self.scratch, "tty-gateway")
        self.procs.start(["socat", f"pty,raw,echo=0,link={tty_path}",
                          f"tcp-listen:{self.port},bind=127.0.0.1,reuseaddr"])
        wait_for(lambda: os.path.exists(tty_path) and listening(self.port),
                 "socat's gateway to listen")
        self.serial = os.open(tty_path, os.O_RDWR | os.O_NOCTTY)
        self.client = socket.create_connection(("127.0.0.1", self.port))
        self.client.setsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1)

    def play(self, truth_events):
        """Plays the bus and relays it; returns the simulator's ground truth of the run and
        the number of bus bytes it played."""
        master, slave = os.openpty()
        tty.setraw(slave)
        played = os.path.join(self.scratch, "played.truth.json")
        sim = self.procs.start([self.sim, *SIM_ARGS, "--truth", played,
                                "--device", os.ttyname(slave)])
        sides = byte_sides(truth_events)
        ends = request_ends(truth_events)
        at = 0
        while sim.poll() is None or select.select([master], [], [], 0)[0]:
            ready = select.select([master, self.serial, self.client], [], [], 0.2)[0]
            if master in ready:
                at = self._relay(os.read(master, 4096), sides, ends, at)
                # Relaying may have read what was ready: look again rather than block.
                ready = select.select([self.serial, self.client], [], [], 0)[0]
            self._receive(ready)
        os.close(slave)
        os.close(master)
        if sim.returncode != 0:
            raise Failure(f"pvtap-sim exited {sim.returncode}")
        return played, at

    def _relay(self, chunk, sides, ends, at):
        """Replies and noise go into the gateway's line as they come; a request goes over TCP
        when the master has all of it (a master writes a request in one piece)."""
        if at + len(chunk) > len(sides):
            raise Failure(f"the simulator played more than the {len(sides)} bytes it planned")
        reply = bytearray()
        for i, byte in enumerate(chunk):
            if not sides[at + i]:
                reply.append(byte)
                continue
            self._to_master(reply)
            self.request.append(byte)
            if at + i + 1 in ends:
                self._to_gateway(self.request)
        self._to_master(reply)
        return at + len(chunk)

    def _to_master(self, reply):
        """Writes bus bytes into the gateway's line, once the requests before them crossed."""
        if not reply:
            return
        self.await_crossing()
        os.write(self.serial, reply)
        self.sent["master"] += len(reply)
        reply.clear()

    def _to_gateway(self, request):
        """Sends a request over TCP, once the bus bytes before it crossed."""
        self.await_crossing()
        self.client.sendall(request)
        self.sent["gateway"] += len(request)
        request.clear()

    def await_crossing(self):
        """Until each end has received everything sent towards it."""
        def crossed():
            if all(len(self.got[k]) >= self.sent[k] for k in self.got):
                return True
            self._receive(select.select([self.serial, self.client], [], [], 0.01)[0])
            return False
        wait_for(crossed, "the gateway to pass bytes on")

    def _receive(self, ready):
        if self.serial in ready:
            self.got["gateway"] += os.read(self.serial, 4096)
        if self.client in ready:
            self.got["master"] += self.client.recv(4096)

    def close(self):
        self.client.close()
        os.close(self.serial)


def sim_truth(sim, scratch):
    path = os.path.join(scratch, "truth.json")
    run = subprocess.run([sim, *SIM_ARGS, "--truth", path], capture_output=True, text=True,
                         check=False, timeout=RUN_GUARD_S)
    if run.returncode != 0:
        raise Failure(f"pvtap-sim exited {run.returncode}: {run.stderr.strip()}")
    with open(path, encoding="utf-8") as f:
        truth = json.load(f)
    if truth["unanswered_at_end"]:
        raise Failure("the simulated bus ends with a request unanswered: choose other SIM_ARGS")
    return truth


def start_capturers(procs, pvtap, scratch, port):
    paths = {k: os.path.join(scratch, k) for k in
             ("capture.pcap", "tcpdump.err", "sniff.out", "sniff.err")}
    with open(paths["tcpdump.err"], "w") as err:
        tcpdump = procs.start(["tcpdump", "-i", "lo", "-U", "-n", "-s", "0", "-w",
                               paths["capture.pcap"], f"tcp port {port}"],
                              stdout=subprocess.DEVNULL, stderr=err)
    with open(paths["sniff.out"], "w") as out, open(paths["sniff.err"], "w") as err:
        sniff = procs.start([pvtap, "sniff", "--interface", "lo", "--port", str(port),
                             "--format", "jsonl"], stdout=out, stderr=err)
    wait_for(lambda: "listening on" in read_text(paths["tcpdump.err"]) or
             tcpdump.poll() is not None, "tcpdump to listen")
    wait_for(lambda: "pvtap: capturing on lo" in read_text(paths["sniff.err"]) or
             sniff.poll() is not None, "pvtap sniff to start capturing")
    for name, proc in (("tcpdump", tcpdump), ("pvtap sniff", sniff)):
        if proc.poll() is not None:
            err = read_text(paths["sniff.err" if proc is sniff else "tcpdump.err"]).strip()
            raise Failure(f"{name} exited {proc.returncode} at the start: {err}")
    return tcpdump, sniff, paths


def stop(proc, name):
    proc.send_signal(signal.SIGTERM)
    try:
        return proc.wait(timeout=PATIENCE_S)
    except subprocess.TimeoutExpired:
        raise Failure(f"{name} did not stop within {PATIENCE_S:.0f} s of SIGTERM") from None


def run_session(args, procs, truth, port):
    """Plays the bus through the gateway while both capture; returns their outputs."""
    tcpdump, sniff, paths = start_capturers(procs, args.pvtap, args.scratch, port)
    rig = Rig(procs, args.sim, args.scratch, port)
    rig.start_gateway()
    played, sent = rig.play(truth["events"])
    rig.await_crossing()
    client_port = rig.client.getsockname()[1]
    rig.close()  # the master hangs up: the gateway's flow ends with FINs
    check_rig(truth, played, sent, rig.got)
    # The master's side enters TIME_WAIT right after it acknowledged the gateway's FIN: then
    # the flow's last packet has crossed lo, and both capturers have it in their buffers.
    wait_for(lambda: time_wait(client_port, port), "the TCP connection to close")
    status = stop(sniff, "pvtap sniff")  # it reads what it captured before it exits
    # tcpdump is stopped once its file holds as many packets as pvtap saw; with fewer, the
    # comparison below says what is missing.
    events = jsonl(read_text(paths["sniff.out"]))
    seen = ((events[-1] if events else {}).get("interface") or {}).get("packets", 0)
    try:
        wait_for(lambda: pcap_records(paths["capture.pcap"]) >= seen,
                 f"tcpdump to write the {seen} packets pvtap sniff saw")
    except Failure as e:
        print(f"note: {e}")
    stop(tcpdump, "tcpdump")
    return status, paths


def check_rig(truth, played, sent, got):
    """The wiring itself: the bus was played as planned and the gateway passed it on."""
    with open(played, encoding="utf-8") as f:
        if json.load(f)["events"] != truth["events"]:
            raise Failure("pvtap-sim played another bus than its ground truth run described")
    stream = bytes.fromhex("".join(e["hex"] for e in truth["events"]))
    sides = byte_sides(truth["events"])
    if sent != len(stream):
        raise Failure(f"the simulator played {sent} of {len(stream)} bytes")
    requests = bytes(b for b, s in zip(stream, sides) if s)
    replies = bytes(b for b, s in zip(stream, sides) if not s)
    if bytes(got["gateway"]) != requests or bytes(got["master"]) != replies:
        raise Failure("the gateway did not pass the bytes on unchanged")


def compare_frames(name, found, expected, expected_raw, bad):
    if len(found) != len(expected):
        bad.append(f"{name}: {len(found)} frames against {len(expected)}")
    for i, (f, e) in enumerate(zip(found, expected)):
        a = (f["raw"],) + tuple(f[k] for k in FRAME_FIELDS)
        b = (e[expected_raw],) + tuple(e[k] for k in FRAME_FIELDS)
        if a != b:
            bad.append(f"{name}: frame {i}: sniff {a} != {b}")
            return


def compare_summary(name, found, expected, bad):
    for key in SUMMARY_KEYS:
        if found.get(key) != expected.get(key):
            bad.append(f"{name}: summary {key}: sniff {found.get(key)}, {expected.get(key)}")


def check_interface(summary, port, records, bad):
    i = summary.get("interface") or {}
    want = {"name": "lo", "filter": f"(tcp port {port} or udp port {port})",
            "packets": records, "dropped": 0}
    for key, value in want.items():
        if i.get(key) != value:
            bad.append(f"interface {key}: {i.get(key)!r}, expected {value!r}")
    if summary.get("stopped_by_signal") is not True:
        bad.append("the report does not say the capture was stopped by a signal")
    if (summary.get("network") or {}).get("flows_analyzed") != 1:
        bad.append(f"network: {summary.get('network')}, expected one flow analyzed")


def check_gateway(args):
    for tool in ("socat", "tcpdump"):
        if shutil.which(tool) is None:
            raise Failure(f"{tool} is not installed (Debian: apt-get install {tool})")
    os.makedirs(args.scratch, exist_ok=True)
    truth = sim_truth(args.sim, args.scratch)
    port = free_port()
    with Processes() as procs:
        status, paths = run_session(args, procs, truth, port)
    bad = []
    if status != 0:
        bad.append(f"pvtap sniff exited {status}: {read_text(paths['sniff.err']).strip()}")
    events = jsonl(read_text(paths["sniff.out"]))
    summary = events[-1] if events and events[-1]["type"] == "summary" else {}
    audited = audit(args.pvtap, paths["capture.pcap"], port)
    compare_frames("vs audit", frames_of(events), frames_of(audited), "raw", bad)
    compare_frames("vs truth", frames_of(events), frames_of(truth["events"]), "hex", bad)
    compare_summary("vs audit", summary, audited[-1], bad)
    compare_summary("vs truth", summary, truth["summary"], bad)
    if summary.get("unanswered_at_end") != 0:
        bad.append(f"unanswered at end: {summary.get('unanswered_at_end')}, expected 0")
    timeouts = [(e["station"], e["function"]) for e in events if e["type"] == "timeout"]
    if timeouts != [(t["station"], t["function"]) for t in truth["timeouts"]]:
        bad.append(f"timeouts: sniff {timeouts}, truth {truth['timeouts']}")
    check_interface(summary, port, pcap_records(paths["capture.pcap"]), bad)
    return bad


def check_no_such_interface(args):
    run = subprocess.run([args.pvtap, "sniff", "--interface", "no-such-if0", "--port", "4001"],
                         capture_output=True, text=True, check=False, timeout=RUN_GUARD_S)
    bad = []
    if run.returncode != 2:
        bad.append(f"exit status {run.returncode}, expected 2")
    if "cannot capture on no-such-if0" not in run.stderr:
        bad.append(f"the message does not name the interface: {run.stderr.strip()!r}")
    # Without the right to capture, that reason comes first.
    if os.geteuid() == 0 and "no such interface" not in run.stderr:
        bad.append(f"the message does not say there is no such interface: {run.stderr.strip()!r}")
    if run.stdout:
        bad.append(f"output on stdout: {run.stdout[:200]!r}")
    return bad


def check_bad_filter(args):
    bogus = "tcp port and nonsense ((("
    run = subprocess.run([args.pvtap, "sniff", "--interface", "lo", "--port", "4001",
                          "--filter", bogus], capture_output=True, text=True, check=False,
                         timeout=RUN_GUARD_S)
    bad = []
    if run.returncode != 2:
        bad.append(f"exit status {run.returncode}, expected 2")
    if bogus not in run.stderr or "cannot capture on lo" not in run.stderr:
        bad.append(f"the message does not quote the filter: {run.stderr.strip()!r}")
    if run.stdout:
        bad.append(f"output on stdout: {run.stdout[:200]!r}")
    return bad


CHECKS = {"gateway": (check_gateway, True), "no-such-interface": (check_no_such_interface, False),
          "bad-filter": (check_bad_filter, True)}


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--pvtap", required=True)
    parser.add_argument("--sim", help="pvtap-sim (gateway)")
    parser.add_argument("--scratch", help="a folder for the files of the run (gateway)")
    parser.add_argument("check", choices=sorted(CHECKS))
    args = parser.parse_args()
    check, needs_capture = CHECKS[args.check]
    if args.check == "gateway" and not (args.sim and args.scratch):
        parser.error("gateway needs --sim and --scratch")
    if needs_capture and capture_refused_for_privilege(args.pvtap):
        print("skipped: capturing on lo needs root (or CAP_NET_RAW and CAP_NET_ADMIN)")
        return SKIP
    try:
        bad = check(args)
    except Failure as e:
        bad = [str(e)]
    for text in bad[:20]:
        print(f"{args.check}: {text}")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
