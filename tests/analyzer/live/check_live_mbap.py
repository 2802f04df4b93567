#!/usr/bin/env python3
"""`pvtap sniff --interface lo` on real Modbus/TCP: a client here sends ADUs over TCP to a
gateway here (a thread answering on 127.0.0.1), two pipelined in one segment and answered in
the reverse order, one to a silent device behind it (the gateway answers 0x0B), one to an
address it refuses (0x02). After SIGTERM, pvtap's summary must hold the exact counts, equal
to `pvtap audit` on tcpdump's file of the same packets.

usage: check_live_mbap.py --pvtap PVTAP --scratch DIR

Exits 77 (skipped) when capturing on lo is impossible because the test does not run as root.
"""
import argparse
import os
import shutil
import socket
import struct
import sys
import threading

from check_live_interface import (SKIP, Failure, Processes, audit, capture_refused_for_privilege,
                                  free_port, jsonl, pcap_records, read_text, start_capturers,
                                  stop, time_wait, wait_for)

SILENT_UNIT = 7  # the device behind the gateway that never answers it
REFUSED_ADDRESS = 0x9000
EXPECTED = {"frames": 8, "requests": 4, "responses": 4, "exceptions": 1, "gateway_timeouts": 1,
            "timeouts": 1, "bad_checks": 0, "noise_bytes": 0}
EXPECTED_MBAP = {"flows": 1, "adus": 8, "carrier_bytes": 48, "findings": 0, "skipped_bytes": 0}


def adu(tid, unit, pdu):
    return struct.pack("!HHHB", tid, 0, len(pdu) + 1, unit) + pdu


def read_adus(conn, count):
    """`count` whole ADUs from a stream socket, as (tid, unit, pdu)."""
    data, out = b"", []
    while len(out) < count:
        while len(data) >= 6 and len(data) >= 6 + struct.unpack("!H", data[4:6])[0]:
            size = 6 + struct.unpack("!H", data[4:6])[0]
            tid, _, _, unit = struct.unpack("!HHHB", data[:7])
            out.append((tid, unit, data[7:size]))
            data = data[size:]
        if len(out) < count:
            chunk = conn.recv(4096)
            if not chunk:
                raise Failure("the peer closed the connection early")
            data += chunk
    return out


def answer(tid, unit, pdu):
    if unit == SILENT_UNIT:
        return adu(tid, unit, bytes([pdu[0] | 0x80, 0x0B]))
    if struct.unpack("!H", pdu[1:3])[0] == REFUSED_ADDRESS:
        return adu(tid, unit, bytes([pdu[0] | 0x80, 0x02]))
    count = struct.unpack("!H", pdu[3:5])[0]
    return adu(tid, unit, bytes([pdu[0], 2 * count]) + bytes(2 * count))


def gateway(server, errors):
    """Answers 2 pipelined requests in reverse order, then 2 more one by one."""
    try:
        conn, _ = server.accept()
        with conn:
            conn.setsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1)
            for reply in reversed([answer(*a) for a in read_adus(conn, 2)]):
                conn.sendall(reply)
            for _ in range(2):
                conn.sendall(answer(*read_adus(conn, 1)[0]))
            conn.recv(1)  # the client hangs up
    except (OSError, Failure) as e:
        errors.append(f"gateway: {e}")


def client(port):
    conn = socket.create_connection(("127.0.0.1", port))
    conn.setsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1)
    read = lambda start: bytes([3]) + struct.pack("!HH", start, 2)  # noqa: E731
    conn.sendall(adu(1, 3, read(0)) + adu(2, 3, read(10)))  # two ADUs in one segment
    got = read_adus(conn, 2)
    conn.sendall(adu(3, SILENT_UNIT, read(0)))
    got += read_adus(conn, 1)
    conn.sendall(adu(4, 3, read(REFUSED_ADDRESS)))
    got += read_adus(conn, 1)
    local_port = conn.getsockname()[1]
    conn.close()
    if [g[0] for g in got] != [2, 1, 3, 4]:
        raise Failure(f"the rig's replies came as transactions {[g[0] for g in got]}")
    return local_port


def compare(name, found, expected, bad):
    for key, value in expected.items():
        if found.get(key) != value:
            bad.append(f"{name}: {key} {found.get(key)}, expected {value}")


def check(args):
    if shutil.which("tcpdump") is None:
        raise Failure("tcpdump is not installed (Debian: apt-get install tcpdump)")
    os.makedirs(args.scratch, exist_ok=True)
    port = free_port()
    errors = []
    with Processes() as procs, socket.socket() as server:
        server.bind(("127.0.0.1", port))
        server.listen(1)
        tcpdump, sniff, paths = start_capturers(procs, args.pvtap, args.scratch, port)
        thread = threading.Thread(target=gateway, args=(server, errors))
        thread.start()
        client_port = client(port)
        thread.join(timeout=30)
        wait_for(lambda: time_wait(client_port, port), "the TCP connection to close")
        status = stop(sniff, "pvtap sniff")
        # tcpdump is stopped once its file holds the packets pvtap saw.
        events = jsonl(read_text(paths["sniff.out"]))
        seen = ((events[-1] if events else {}).get("interface") or {}).get("packets", 0)
        wait_for(lambda: pcap_records(paths["capture.pcap"]) >= seen,
                 f"tcpdump to write the {seen} packets pvtap sniff saw")
        stop(tcpdump, "tcpdump")
    bad = list(errors)
    if status != 0:
        bad.append(f"pvtap sniff exited {status}: {read_text(paths['sniff.err']).strip()}")
    summary = events[-1] if events and events[-1]["type"] == "summary" else {}
    compare("sniff", summary, EXPECTED, bad)
    compare("sniff mbap", summary.get("network", {}).get("mbap", {}), EXPECTED_MBAP, bad)
    audited = audit(args.pvtap, paths["capture.pcap"], port)[-1]
    compare("audit of tcpdump's file", audited, EXPECTED, bad)
    compare("audit mbap", audited.get("network", {}).get("mbap", {}), EXPECTED_MBAP, bad)
    return bad


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--pvtap", required=True)
    parser.add_argument("--scratch", required=True)
    args = parser.parse_args()
    if capture_refused_for_privilege(args.pvtap):
        print("skipped: capturing on lo needs root (or CAP_NET_RAW and CAP_NET_ADMIN)")
        return SKIP
    try:
        bad = check(args)
    except Failure as e:
        bad = [str(e)]
    for text in bad[:20]:
        print(f"mbap: {text}")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
