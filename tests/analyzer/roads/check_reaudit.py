#!/usr/bin/env python3
"""pvtap's own output audits like the original: `pvtap audit --write` (and `pvtap sniff
--write`) writes a capture of link type 252; `pvtap audit` of that file must give the verdicts
of the run that wrote it, frame by frame (compare_verdicts.py judges, times included).

usage: check_reaudit.py --pvtap PVTAP [--sim PVTAP_SIM] --scratch DIR MODE [ARG]
modes:
  samples DIR [NAME...]  every capture of the sample library in DIR (or those named); and
                the link-type-252 samples, written in the format older versions wrote (no
                pvtap tags), hold the noise runs of their ground truth
  faults        every fault class of the simulator, on each of its serial carriers
  sniff         `pvtap sniff --write` on a real pty: a damaged reply with garbage behind it,
                and a simulated bus with every fault
Exit status 0 when every road gives the same verdicts, 1 with the differences listed.
"""
import argparse
import glob
import json
import os
import signal
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
sys.path.insert(0, os.path.join(HERE, "..", "sniff"))
sys.path.insert(0, os.path.join(HERE, "..", "..", "dissector"))
import compare_verdicts  # noqa: E402

# The longest one program this test runs may take: a guard, not a timing check.
RUN_GUARD_S = 120
# Differences shown per road.
SHOWN = 12
# The simulator's fault classes (captures/README.md), each alone at a rate that makes many.
FAULT_CLASSES = ("corrupt", "corrupt_request", "missing", "slow", "noise", "error_reply",
                 "count_mismatch", "duplicate", "corrupt_data")
# Of the simulator's carriers, those whose frames are serial frames with their checks.
SIM_CARRIERS = (("pdu", "--pdu"), ("user0", "--chunked"), ("gateway", "--gateway"))


class Roads:
    def __init__(self, pvtap, scratch):
        self.pvtap, self.scratch = pvtap, scratch
        self.failures = []
        self.roads = 0

    def audit(self, capture, out_jsonl, *extra):
        with open(out_jsonl, "w", encoding="utf-8") as out:
            run = subprocess.run([self.pvtap, "audit", "--format", "jsonl", *extra, capture],
                                 stdout=out, stderr=subprocess.PIPE, text=True,
                                 timeout=RUN_GUARD_S, check=False)
        # 0, or 1 when the audit found faults; 2 and above: the audit could not be done.
        if run.returncode >= 2:
            raise RuntimeError(f"pvtap audit {capture} exited {run.returncode}: {run.stderr}")

    def compare(self, name, first, again):
        """The verdicts of `first` (the run that wrote) against `again` (the re-audit)."""
        self.roads += 1
        lines = compare_verdicts.differences(compare_verdicts.read_jsonl(first),
                                             compare_verdicts.read_jsonl(again),
                                             compare_verdicts.Options(times=True))
        if lines:
            self.failures.append(f"{name}: {len(lines)} difference(s) (A: the run, B: its "
                                 f"file audited again)")
            self.failures += ["  " + line for line in lines[:SHOWN]]

    def reaudit(self, name, capture, *options):
        """audit --write, then audit of what was written, with the same options."""
        stem = os.path.join(self.scratch, name)
        self.audit(capture, stem + ".run.jsonl", "--write", stem + ".written.pcap", *options)
        self.audit(stem + ".written.pcap", stem + ".again.jsonl")
        self.compare(name, stem + ".run.jsonl", stem + ".again.jsonl")

    def exit_status(self, mode):
        if not self.failures:
            print(f"{mode}: ok, {self.roads} roads")
            return 0
        print(f"{mode}: {self.roads} roads, differences:")
        for line in self.failures:
            print(line)
        return 1


# Modbus/TCP gateways' ADUs carry no CRC: --write leaves them out (the capture itself is their
# record, pdu_capture_output.h), so there is nothing to audit again.
NOT_WRITTEN = (".mbap.pcap",)


def check_samples(roads, directory, names):
    if names:
        captures = [os.path.join(directory, name) for name in names]
    else:
        captures = sorted(p for p in glob.glob(os.path.join(directory, "*"))
                          if p.endswith((".pcap", ".pcapng", ".sr")))
    if not captures:
        raise SystemExit(f"no captures in {directory}")
    for capture in captures:
        if capture.endswith(NOT_WRITTEN):
            print(f"{os.path.basename(capture)}: not written by --write (Modbus/TCP ADUs)")
            continue
        roads.reaudit("sample-" + os.path.basename(capture), capture)
        if capture.endswith(".pdu.pcap"):
            check_old_records(roads, capture)
    return roads.exit_status("samples")


def check_old_records(roads, capture):
    """One record is one frame or one noise run: noise between frames stays its own run."""
    truth_path = capture[:-len(".pdu.pcap")] + ".truth.json"
    if not os.path.exists(truth_path):
        return
    with open(truth_path, encoding="utf-8") as f:
        truth = json.load(f)
    stem = os.path.join(roads.scratch, "old-" + os.path.basename(capture))
    roads.audit(capture, stem + ".jsonl")
    found = [e["raw"] for e in compare_verdicts.read_jsonl(stem + ".jsonl")
             if e.get("type") == "noise"]
    want = [e["hex"] for e in truth["events"] if e["type"] == "noise"]
    roads.roads += 1
    if found != want:
        roads.failures.append(f"{os.path.basename(capture)}: {len(found)} noise runs, the "
                              f"truth has {len(want)}")


def simulate(sim, scratch, name, args):
    truth = os.path.join(scratch, name + ".truth.json")
    subprocess.run([sim, *args, "--truth", truth], check=True, timeout=RUN_GUARD_S)
    with open(truth, encoding="utf-8") as f:
        return json.load(f)


def check_faults(roads, sim):
    for fault in FAULT_CLASSES:
        name = f"fault-{fault}"
        outputs = []
        for carrier, option in SIM_CARRIERS:
            outputs += [option, os.path.join(roads.scratch, f"{name}.{carrier}.pcap")]
        truth = simulate(sim, roads.scratch, name,
                         ["--dialect", "gsl,hybrid,ascii", "--inverters", "4", "--duration",
                          "40", "--seed", "5", "--meter", "10", "--faults", f"{fault}=30",
                          "--timeout", "0.4", *outputs])
        timeout = str(truth["timeout_s"])
        for carrier, _ in SIM_CARRIERS:
            capture = os.path.join(roads.scratch, f"{name}.{carrier}.pcap")
            # The run's settings must travel with the file: the re-audit is given none.
            roads.reaudit(f"{name}.{carrier}", capture, "--timeout", timeout)
    return roads.exit_status("faults")


class Sniffer:
    """`pvtap sniff --device PTY --format jsonl --write PCAP` until stopped."""

    def __init__(self, pvtap, stem, device, *options):
        self.stem = stem
        self.out = open(stem + ".run.jsonl", "w", encoding="utf-8")
        self.err = open(stem + ".err", "w", encoding="utf-8")
        self.proc = subprocess.Popen([pvtap, "sniff", "--device", device, "--format", "jsonl",
                                      "--write", stem + ".written.pcap", *options],
                                     stdout=self.out, stderr=self.err)
        deadline = time.monotonic() + 20
        real = os.path.realpath(device)
        while time.monotonic() < deadline:
            if self.proc.poll() is not None:
                raise RuntimeError(f"pvtap sniff exited {self.proc.returncode}")
            fds = f"/proc/{self.proc.pid}/fd"
            if any(os.path.realpath(os.path.join(fds, fd)) == real for fd in os.listdir(fds)):
                return
            time.sleep(0.01)
        raise RuntimeError("pvtap sniff did not open the pty")

    def stop(self):
        self.proc.send_signal(signal.SIGTERM)
        self.proc.wait(20)
        self.out.close()
        self.err.close()
        if self.proc.returncode != 0:
            raise RuntimeError(f"pvtap sniff exited {self.proc.returncode}")


def sniff_road(roads, name, schedule, duration, *options):
    import pty_bus  # noqa: E402  (tests/analyzer/sniff)
    stem = os.path.join(roads.scratch, name)
    pty = pty_bus.Pty()
    sniffer = Sniffer(roads.pvtap, stem, pty.path, *options)
    start = time.monotonic()
    pty_bus.play(pty.master, schedule, start)
    time.sleep(max(0.0, start + duration - time.monotonic()))
    sniffer.stop()
    pty.close()
    roads.audit(stem + ".written.pcap", stem + ".again.jsonl")
    roads.compare(name, stem + ".run.jsonl", stem + ".again.jsonl")


def check_sniff(roads, sim):
    import pty_bus  # noqa: E402
    from bus_frames import with_crc  # noqa: E402
    baud = 9600
    # Two stations polled; station 2's reply damaged and 6 garbage bytes behind it; station 2
    # asked again 1.5 s later and answering.
    read1 = with_crc(bytes.fromhex("01 03 04 06 00 04"))
    reply1 = with_crc(bytes.fromhex("01 03 08 09 10 00 7B 00 00 11 94"))
    read2 = with_crc(bytes.fromhex("02 03 04 06 00 04"))
    reply2 = with_crc(bytes.fromhex("02 03 08 09 10 00 7B 00 00 11 95"))
    damaged = bytearray(reply2)
    damaged[5] ^= 0x01
    garbage = bytes.fromhex("ff 00 f0 0f aa 55")
    plan = [(read1, 0.03), (reply1, 0.2), (read2, 0.03), (bytes(damaged), 0.03), (garbage, 0.6),
            (read1, 0.03), (reply1, 0.8), (read2, 0.03), (reply2, 0.2), (read1, 1.2)]
    events, t = [], 0.0
    for data, silence in plan:
        events.append({"ts": t, "hex": data.hex()})
        t += len(data) * 10 / baud + silence
    sniff_road(roads, "sniff-damaged-reply", pty_bus.byte_schedule(events, baud), t + 0.3,
               "--timeout", "1")
    # A simulated bus with every fault, stopped while requests still wait.
    truth = simulate(sim, roads.scratch, "sniff-all-faults",
                     ["--baud", str(baud), "--period", "1", "--dialect", "gsl,hybrid,ascii",
                      "--inverters", "3", "--duration", "5", "--seed", "3", "--faults", "all",
                      "--meter", "10"])
    first = truth["events"][0]["ts"]
    end = max(e.get("end", e["ts"]) for e in truth["events"]) - first
    sniff_road(roads, "sniff-all-faults", pty_bus.byte_schedule(truth["events"], baud),
               end + 0.3, "--timeout", str(truth["timeout_s"]))
    return roads.exit_status("sniff")


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--pvtap", required=True)
    parser.add_argument("--sim")
    parser.add_argument("--scratch", required=True)
    parser.add_argument("mode", choices=("samples", "faults", "sniff"))
    parser.add_argument("arg", nargs="*")
    args = parser.parse_args()
    os.makedirs(args.scratch, exist_ok=True)
    roads = Roads(args.pvtap, args.scratch)
    if args.mode == "samples":
        if not args.arg:
            parser.error("samples needs a folder")
        return check_samples(roads, args.arg[0], args.arg[1:])
    if args.mode == "faults":
        return check_faults(roads, args.sim)
    return check_sniff(roads, args.sim)


if __name__ == "__main__":
    sys.exit(main())
