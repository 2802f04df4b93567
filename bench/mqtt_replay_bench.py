#!/usr/bin/python3
"""How many messages a second pvtap hands to a local mosquitto broker: `pvtap audit --mqtt`
replays a simulated capture with faults as fast as it reads it (every event a QoS 1 message,
values and states every --mqtt-interval of capture time), and a subscriber counts what the
broker passes on. The run counts only when every event of `--format jsonl` arrived.

usage: mqtt_replay_bench.py --pvtap build/analyzer/pvtap --sim build/captures/pvtap-sim
       [--duration 3600] [--inverters 16] [--period 1] [--mqtt-interval 1]
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile
import time

sys.dont_write_bytecode = True  # no __pycache__ in the source tree
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tests",
                                "analyzer", "mqtt"))
import mqtt_broker  # noqa: E402


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--pvtap", required=True)
    parser.add_argument("--sim", required=True)
    parser.add_argument("--duration", default="3600")
    parser.add_argument("--inverters", default="16")
    parser.add_argument("--period", default="1")
    parser.add_argument("--mqtt-interval", default="1")
    args = parser.parse_args()
    scratch = tempfile.mkdtemp(prefix="pvtap-mqtt-bench-")
    capture = os.path.join(scratch, "bench.pcap")
    subprocess.run([args.sim, "--dialect", "gsl,hybrid,ascii", "--inverters", args.inverters,
                    "--duration", args.duration, "--period", args.period, "--seed", "1",
                    "--faults", "all", "--pdu", capture], check=True, capture_output=True)
    jsonl = subprocess.run([args.pvtap, "audit", "--format", "jsonl", capture],
                           capture_output=True, text=True, check=True).stdout
    lines = [json.loads(line) for line in jsonl.splitlines()]
    want = sum(1 for e in lines if e["type"] in ("timeout", "gap") or (
        e["type"] == "frame" and (e["check"] == "bad" or any(
            i.startswith(("malformed", "unsolicited", "late reply", "exception", "error reply"))
            for i in e["issues"]))))
    broker = mqtt_broker.Broker(scratch, "bench")
    sub = mqtt_broker.Subscriber(broker)
    started = time.monotonic()
    # Under /usr/bin/time: the rusage of a child forked from this script would count this
    # script's memory from before the exec (which holds the whole jsonl).
    proc = subprocess.Popen(["/usr/bin/time", "-f", "peak RSS %M KiB", args.pvtap, "audit", "--summary-only", capture, "--mqtt", broker.url(),
                          "--mqtt-user", mqtt_broker.USER, "--mqtt-password-file",
                          broker.password_file, "--mqtt-topic", "bench", "--mqtt-interval",
                          args.mqtt_interval, "--mqtt-discovery"],
                            stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    _, status, usage = os.wait4(proc.pid, 0)
    wall = time.monotonic() - started
    returncode = os.waitstatus_to_exitcode(status)
    stderr = proc.stderr.read().strip().splitlines()
    peak = stderr.pop() if stderr else "peak RSS unknown"
    sub.wait_for(lambda m: sum(1 for t, p, _ in m if t.endswith("/events")) >= want, timeout=60)
    messages = sub.snapshot()
    events = sum(1 for t, p, _ in messages
                 if t.endswith("/events") and '"type":"station_' not in p)
    cpu = usage.ru_utime + usage.ru_stime
    frames = sum(1 for e in lines if e["type"] == "frame")
    print(f"capture: {frames} frames, {want} events (jsonl); pvtap exit {returncode} "
          f"{' '.join(stderr)}")
    print(f"pvtap audit --mqtt: {wall:.2f} s wall, CPU {cpu:.2f} s (user {usage.ru_utime:.2f} "
          f"s, system {usage.ru_stime:.2f} s), {peak}")
    print(f"broker passed on {len(messages)} messages ({events} events of {want}): "
          f"{len(messages) / wall:.0f} messages/s while pvtap ran")
    sub.close()
    broker.stop()
    return 0 if returncode == 0 and events == want else 1


if __name__ == "__main__":
    sys.exit(main())
