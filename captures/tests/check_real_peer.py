#!/usr/bin/env python3
"""Records the real-peer capture (mbpoll, pymodbus, ser2net, socat, tcpdump) and checks that
pvtap audit, Wireshark's built-in Modbus RTU dissector and, when built, pvtap's plugin all
see every frame good and the values the pymodbus server held.

usage: check_real_peer.py PVTAP RECORD_SCRIPT SCRATCH_DIR [PVTAP_PLUGIN]
"""
import json
import os
import shutil
import subprocess
import sys
import tomllib

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")
MAP_FILE = os.path.join(ROOT, "protocols", "maps", "gsl.toml")
sys.dont_write_bytecode = True  # leave no __pycache__ in the dissector tests' folder
sys.path.insert(0, os.path.join(ROOT, "tests", "dissector"))


def expected_values(held):
    """Register ID -> (key, scaled value) for the map's number entries the server holds."""
    with open(MAP_FILE, "rb") as f:
        entries = tomllib.load(f)["register"]
    out = {}
    for e in entries:
        kind = e.get("kind", "enum" if "values" in e else ("bits" if "bits" in e else "number"))
        first = held.get(str(e["address"]))
        if kind != "number" or first is None or "last" in e:
            continue
        raw = first
        if e.get("words", 1) == 2:
            raw = first * 65536 + held[str(e["address"] + 1)]
        elif e.get("signed") and raw >= 0x8000:
            raw -= 0x10000
        out[e["address"]] = (e["key"], raw * e.get("scale", 1.0))
    return out


def close(a, b):
    return abs(a - b) <= 1e-6 * max(1.0, abs(b))


def check_audit(pvtap, capture, polls, held, failures):
    run = subprocess.run([pvtap, "audit", "--format", "jsonl", capture], capture_output=True,
                         text=True, check=True)
    events = [json.loads(line) for line in run.stdout.splitlines()]
    frames = [e for e in events if e["type"] == "frame"]
    summary = events[-1]
    want = {"frames": 2 * len(polls), "requests": len(polls), "responses": len(polls),
            "bad_checks": 0, "timeouts": 0, "noise_bytes": 0, "exceptions": 0}
    for key, value in want.items():
        if summary.get(key) != value:
            failures.append(f"audit summary {key} = {summary.get(key)}, expected {value}")
    expected = expected_values(held)
    for f in frames:
        if f["check"] != "ok":
            failures.append(f"audit: bad check on {f['raw']}")
        for v in f.get("values", []):
            exp = expected.get(int(v["register"]))
            if exp and not (isinstance(v["value"], (int, float)) and close(v["value"], exp[1])):
                failures.append(f"audit: {v['register']} = {v['value']}, server held {exp[1]}")
    return len(frames)


def check_mbrtu(capture, port, held, frame_count, failures):
    """Wireshark's own Modbus RTU dissector, CRC verification on."""
    run = subprocess.run(["tshark", "-r", capture, "-o", "mbrtu.crc_verification:TRUE",
                          "-d", f"tcp.port=={port},mbrtu", "-Y", "mbrtu", "-T", "fields",
                          "-e", "mbrtu.crc16.status", "-e", "modbus.regnum16",
                          "-e", "modbus.regval_uint16", "-E", "occurrence=a",
                          "-E", "aggregator=,"], capture_output=True, text=True, check=True)
    rows = [line.split("\t") for line in run.stdout.splitlines()]
    if len(rows) != frame_count:
        failures.append(f"mbrtu found {len(rows)} frames, pvtap audit {frame_count}")
    for status, refs, values in rows:
        if status != "1":
            failures.append(f"mbrtu CRC status {status} (1 = good)")
        for ref, value in zip(refs.split(",") if values else [], values.split(",") if values else []):
            if held.get(ref) != int(value):
                failures.append(f"mbrtu: register {ref} = {value}, server held {held.get(ref)}")


def check_plugin(plugin, capture, port, held, frame_count, failures):
    os.environ["PVTAP_PLUGIN"] = plugin
    from tshark_runner import TsharkHome
    home = TsharkHome()
    try:
        shutil.copy(capture, home.path("real-peer.pcap"))
        home._hand_over()
        expected = expected_values(held)
        fields = ["invrtu.crc.status"] + [f"invrtu.gsl.{k}" for k, _ in expected.values()]
        rows = home.fields(home.path("real-peer.pcap"), fields,
                           options=["-o", f"invrtu.tcp.port:{port}"])
        statuses = [s for row in rows for s in row[0]]
        if len(statuses) != frame_count or any(s != "1" for s in statuses):
            failures.append(f"plugin CRC verdicts {statuses}, expected {frame_count} good")
        for column, (key, value) in enumerate(expected.values(), start=1):
            seen = [float(x) for row in rows for x in row[column]]
            if not seen or any(not close(x, value) for x in seen):
                failures.append(f"plugin: invrtu.gsl.{key} = {seen}, server held {value}")
    finally:
        home.close()


def main():
    pvtap, record, scratch = sys.argv[1:4]
    plugin = sys.argv[4] if len(sys.argv) > 4 else ""
    shutil.rmtree(scratch, ignore_errors=True)
    subprocess.run([record, scratch], check=True)
    capture = os.path.join(scratch, "real-peer.pcap")
    with open(os.path.join(scratch, "real-peer.server.json"), encoding="utf-8") as f:
        held = json.load(f)["holding_registers"]
    with open(os.path.join(scratch, "real-peer.polls.json"), encoding="utf-8") as f:
        polls = json.load(f)
    failures = []
    frames = check_audit(pvtap, capture, polls["polls"], held, failures)
    check_mbrtu(capture, polls["gateway_port"], held, frames, failures)
    if plugin and os.path.isfile(plugin):
        check_plugin(plugin, capture, polls["gateway_port"], held, frames, failures)
    else:
        print("pvtap plugin not built: its check is skipped")
    for text in failures[:20]:
        print(text)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
