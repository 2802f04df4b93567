#!/usr/bin/env python3
"""Writes the seed corpus of every fuzz target from the sample library (captures/samples),
the built-in register maps and a few command lines: make_seeds.py OUTDIR [--max-bytes N].

Seeds are small windows of the samples, in each target's input layout (see the targets'
header comments), so that the fuzzer starts from real traffic. Nothing here is committed:
scripts/fuzz regenerates the seeds in its build folder.
"""

import argparse
import hashlib
import os
import struct
import subprocess
import sys
import tempfile

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SAMPLES = os.path.join(REPO, "captures", "samples")


def read_pcap(path):
    """(link type, [(time, bytes)]) of a classic pcap file (both byte orders, us or ns)."""
    with open(path, "rb") as f:
        data = f.read()
    magic = data[:4]
    order = "<" if magic in (b"\xd4\xc3\xb2\xa1", b"\x4d\x3c\xb2\xa1") else ">"
    nanos = magic in (b"\x4d\x3c\xb2\xa1", b"\xa1\xb2\x3c\x4d")
    link = struct.unpack(order + "I", data[20:24])[0]
    records, at = [], 24
    while at + 16 <= len(data):
        sec, frac, caplen, _ = struct.unpack(order + "IIII", data[at:at + 16])
        at += 16
        records.append((sec + frac / (1e9 if nanos else 1e6), data[at:at + caplen]))
        at += caplen
    return link, records


def samples(kind):
    return sorted(os.path.join(SAMPLES, n) for n in os.listdir(SAMPLES) if n.endswith(kind))


class Corpus:
    def __init__(self, out, target):
        self.dir = os.path.join(out, target)
        os.makedirs(self.dir, exist_ok=True)

    def add(self, data):
        name = hashlib.sha1(data).hexdigest()
        with open(os.path.join(self.dir, name), "wb") as f:
            f.write(data)


def pdu_of(record):
    """The dissector name, direction and PDU of a link-type-252 record."""
    at, direction = 0, 0
    while at + 4 <= len(record):
        tag, length = struct.unpack(">HH", record[at:at + 4])
        value = record[at + 4:at + 4 + length]
        at += 4 + length
        if tag == 0:
            break
        if tag == 35 and length == 4:
            direction = 1 if struct.unpack(">i", value)[0] == 0 else 2
    return direction, record[at:]


def script(records, options=0x00):
    """The chunk script of chunk_script.h: options, then (control, time, bytes) steps."""
    out, last = bytearray([options]), None
    for time, direction, data in records:
        tick = 0 if last is None else min(254, max(0, int((time - last) / 0.0002)))
        last = time
        for i in range(0, max(len(data), 1), 63):
            part = data[i:i + 63]
            out += bytes([(len(part) << 2) | direction, tick]) + part
            tick = 0
    return bytes(out)


def windows(items, size, count):
    step = max(1, len(items) // count)
    return [items[i:i + size] for i in range(0, len(items), step)][:count]


def core_seeds(out, max_bytes):
    codec, reasm, session, records = (Corpus(out, t) for t in
                                      ("frame_codec", "stream_reassembler", "bus_session",
                                       "serial_records"))
    for path in samples(".pdu.pcap"):
        _, recs = read_pcap(path)
        frames = [(t, *pdu_of(r)) for t, r in recs]
        for _, _, pdu in frames[:40]:
            codec.add(b"\x07" + pdu)
        for r in [r for _, r in recs][:20]:
            records.add(b"\x00" + r)
        for w in windows(frames, 24, 6):
            session.add(script(w)[:max_bytes])
    for path in samples(".user0.pcap"):
        _, recs = read_pcap(path)
        chunks = [(t, 0, r) for t, r in recs]
        for w in windows(chunks, 40, 6):
            reasm.add(script(w)[:max_bytes])
            reasm.add(script(w, options=0x10)[:max_bytes])  # timestamps not trusted
            session.add(script(w)[:max_bytes])
        for t, r in recs[:10]:
            header = struct.pack(">IIBBH", int(t), int((t % 1) * 1e6), 0, 0, 0)
            records.add(b"\x01" + header + r)


def plan_seeds(out):
    """dissector_plan: a record header (dialect, flags, more flags, counts, latency, packet),
    the request's bytes with their length, then the frame: each reply of a sample with the
    request before it, and each request alone, as the first pass would have recorded them."""
    corpus = Corpus(out, "dissector_plan")
    for path in samples(".pdu.pcap"):
        name = os.path.basename(path)
        dialect = 0 if name.startswith("ascii") else 1 if name.startswith("hybrid") else 2
        _, recs = read_pcap(path)
        pdus = [pdu_of(r) for _, r in recs][:24]
        for (d0, first), (d1, second) in zip(pdus, pdus[1:]):
            if d0 != 1 or d1 != 2:
                continue
            header = struct.pack(">BBBBBII", dialect, 0x0F, 0, 0, 0, 1200, 7)
            corpus.add(header + bytes([min(len(first), 63)]) + first[:63] + second)
            request = struct.pack(">BBBBBII", dialect, 0x0E, 0, 0, 0, 0, 6)
            corpus.add(request + b"\x00" + first)


def tcp_segments(path):
    """The TCP segments (src port, seq, flags, payload, time) of an Ethernet IPv4 capture."""
    _, recs = read_pcap(path)
    for time, p in recs:
        if len(p) < 54 or p[12:14] != b"\x08\x00":
            continue
        ip = p[14:]
        ihl = (ip[0] & 15) * 4
        if ip[9] != 6:
            continue
        total = struct.unpack(">H", ip[2:4])[0]
        tcp = ip[ihl:total]
        sport, _, seq, ack = struct.unpack(">HHII", tcp[:12])
        off = (tcp[12] >> 4) * 4
        yield sport, seq, ack, tcp[13], tcp[off:], time


def tcp_seeds(out, max_bytes):
    corpus = Corpus(out, "tcp_stream")
    for path in samples(".gateway.pcap"):
        segs = list(tcp_segments(path))
        if not segs:
            continue
        port = segs[0][0]
        mine = [s for s in segs if s[0] == port]
        initial = mine[0][1]
        for shift, limits in ((0, 0), (0xFFFFFF00, 3)):  # also a stream that wraps
            data = bytearray(struct.pack(">IB", (initial + shift) & 0xFFFFFFFF, limits))
            last = mine[0][5]
            for _, seq, _, flags, payload, time in mine[:60]:
                ours = (1 if flags & 2 else 0) | (2 if flags & 1 else 0) | (16 if flags & 4 else 0)
                tick = min(254, int((time - last) / 0.01))
                last = time
                data += struct.pack(">BIBBB", ours, (seq - initial) & 0xFFFFFFFF,
                                    min(len(payload), 255), 0, tick) + payload[:255]
            corpus.add(bytes(data[:max_bytes]))


def capture_seeds(out, max_bytes, extra):
    corpus = Corpus(out, "capture_file")
    paths = samples(".pcap")
    if extra:
        paths += sorted(os.path.join(extra, n) for n in os.listdir(extra)
                        if n.endswith(".pcap") or n.endswith(".pcapng"))
    for path in paths:
        with open(path, "rb") as f:
            corpus.add(f.read(max_bytes))
    editcap = "/usr/bin/editcap"
    if os.path.exists(editcap):
        with tempfile.TemporaryDirectory() as tmp:
            for path in paths:
                ng = os.path.join(tmp, "x.pcapng")
                done = subprocess.run([editcap, "-F", "pcapng", "-r", path, ng, "1-20"],
                                      capture_output=True)
                if done.returncode != 0:
                    continue
                with open(ng, "rb") as f:
                    corpus.add(f.read(max_bytes))


def map_seeds(out):
    corpus = Corpus(out, "register_map")
    maps = os.path.join(REPO, "protocols", "maps")
    for name in sorted(os.listdir(maps)):
        if name.endswith(".toml"):
            with open(os.path.join(maps, name), "rb") as f:
                text = f.read()
            corpus.add(text)
            corpus.add(text[:2000])
    corpus.add(b'dialect = "hybrid"\nmode = "extend"\n[[register]]\naddress = 0x1006\n'
               b'key = "v"\nname = "v"\nscale = 0.1\nunit = "V"\n')


EXTCAP_CALLS = [
    ["--extcap-interfaces"],
    ["--extcap-interfaces", "--extcap-version=4.0"],
    ["--extcap-dlts", "--extcap-interface", "pvtap-ttyUSB0"],
    ["--extcap-config", "--extcap-interface", "pvtap-ttyUSB0"],
    ["--extcap-capture-filter", "port 4001", "--extcap-interface", "pvtap-ttyUSB0"],
    ["--capture", "--extcap-interface", "pvtap-ttyUSB0", "--fifo", "/tmp/f", "--baud", "9600",
     "--parity", "even", "--stop-bits", "2", "--dialect", "gsl"],
    ["--capture", "--extcap-interface=pvtap-x", "--fifo=/tmp/f", "--baud=115200",
     "--extcap-control-in", "/tmp/c", "--log-level", "debug", "--unknown"],
]

AUDIT_CALLS = [
    ["audit", "x.pcap"],
    ["audit", "--dialect", "gsl", "--baud", "4800", "--raw", "dump.bin"],
    ["audit", "--format", "jsonl", "--port", "4001,502", "--summary-only", "--fail-on", "errors",
     "--timeout", "0.5", "--gsl-ids", "hex", "x.pcap"],
    ["audit", "--write", "out.pcap", "--map", "none.toml", "x.pcap"],
    ["sniff", "--device", "/dev/ttyUSB0", "--baud", "9600", "--parity", "even", "--duration",
     "10", "--count", "5"],
    ["sniff", "--interface", "lo", "--port", "4001", "--filter", "host 10.0.0.1"],
    ["--help"],
]


def argument_seeds(out):
    for target, calls in (("extcap_arguments", EXTCAP_CALLS), ("command_line", AUDIT_CALLS)):
        corpus = Corpus(out, target)
        for call in calls:
            corpus.add("\0".join(call).encode())


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("out")
    parser.add_argument("--max-bytes", type=int, default=4096)
    parser.add_argument("--test-captures", help="also the captures of this folder "
                        "(pvtap-capture-gen tests DIR)")
    a = parser.parse_args()
    core_seeds(a.out, a.max_bytes)
    tcp_seeds(a.out, a.max_bytes)
    capture_seeds(a.out, a.max_bytes, a.test_captures)
    map_seeds(a.out)
    argument_seeds(a.out)
    plan_seeds(a.out)
    for target in sorted(os.listdir(a.out)):
        print("%-20s %4d seeds" % (target, len(os.listdir(os.path.join(a.out, target)))))
    return 0


if __name__ == "__main__":
    sys.exit(main())
