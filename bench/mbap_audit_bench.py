#!/usr/bin/env python3
"""Throughput of `pvtap audit` on a Modbus/TCP capture beside a serial gateway capture of the
same size: the MBAP capture is written here (a client polling four units through one
gateway on port 502, two requests pipelined per poll, one reply in 50 an exception, one in 200
a gateway's 0x0B), the gateway capture by pvtap-capture-gen. Prints MB of capture per CPU
second (user + system, `--summary-only --threads 1`, median of RUNS) for both.

    bench/mbap_audit_bench.py [MEGABYTES]     (default 10; Release build in build/)

Environment: BUILD (default build), RUNS (default 3).
"""
import os
import resource
import statistics
import struct
import subprocess
import sys

repo = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(repo, "tests", "dissector"))
from pcap_writer import Pcap, TcpFlow  # noqa: E402


def adu(tid, unit, pdu):
    return struct.pack("!HHHB", tid & 0xFFFF, 0, len(pdu) + 1, unit) + pdu


def reply_pdu(n, count):
    if n % 200 == 199:
        return bytes([0x83, 0x0B])
    if n % 50 == 49:
        return bytes([0x83, 0x02])
    return struct.pack("!BB", 3, 2 * count) + bytes(range(2 * count))


def build(path, megabytes):
    pcap = Pcap()
    flow = TcpFlow(pcap, client=("10.0.0.1", 50300), server=("10.0.0.9", 502), time=1000.0)
    tid = n = 0
    size, counted = 24, 0
    while size < megabytes * 1_000_000:
        for unit in (1, 2, 3, 4):
            first, second = tid, tid + 1
            tid += 2
            flow.request(adu(first, unit, struct.pack("!BHH", 3, 0, 10)), after=0.05)
            flow.request(adu(second, unit, struct.pack("!BHH", 3, 100, 20)), after=0.001)
            flow.reply(adu(first, unit, reply_pdu(n, 10)), after=0.02)
            flow.reply(adu(second, unit, reply_pdu(n + 1, 20)), after=0.002)
            n += 2
        size += sum(16 + len(record[1]) for record in pcap.records[counted:])
        counted = len(pcap.records)
    pcap.write(path)


def cpu_seconds(command):
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    subprocess.run(command, check=True, stdout=subprocess.DEVNULL)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def main():
    megabytes = int(sys.argv[1]) if len(sys.argv) > 1 else 10
    build_dir = os.environ.get("BUILD", os.path.join(repo, "build"))
    runs = int(os.environ.get("RUNS", "3"))
    pvtap = os.path.join(build_dir, "analyzer", "pvtap")
    gen = os.path.join(build_dir, "tests", "analyzer", "pvtap-capture-gen")
    mbap = "/tmp/pvtap-bench-mbap-%d.pcap" % megabytes
    gateway = "/tmp/pvtap-bench-gateway-%d.pcap" % megabytes
    if not os.path.exists(mbap):
        build(mbap, megabytes)
    if not os.path.exists(gateway):
        subprocess.run([gen, "bench", gateway, str(megabytes)], check=True,
                       stdout=subprocess.DEVNULL)
    for name, path in (("modbus/tcp", mbap), ("serial gateway", gateway)):
        command = [pvtap, "audit", "--summary-only", "--threads", "1", path]
        times = [cpu_seconds(command) for _ in range(runs)]
        mb = os.path.getsize(path) / 1e6
        cpu = statistics.median(times)
        print("%-15s %7.1f MB  CPU %.3f s (median of %d)  %6.1f MB/s" % (
            name, mb, cpu, runs, mb / cpu))


if __name__ == "__main__":
    main()
