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
import resource
import subprocess
import sys
import tempfile
import time

sys.dont_write_bytecode = True  # no __pycache__ in the source tree
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tests",
                                "mqtt"))
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
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    started = time.monotonic()
    run = subprocess.run([args.pvtap, "audit", "--summary-only", capture, "--mqtt", broker.url(),
                          "--mqtt-user", mqtt_broker.USER, "--mqtt-password-file",
                          broker.password_file, "--mqtt-topic", "bench", "--mqtt-interval",
                          args.mqtt_interval, "--mqtt-discovery"],
                         stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    wall = time.monotonic() - started
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    sub.wait_for(lambda m: sum(1 for t, p, _ in m if t.endswith("/events")) >= want, timeout=60)
    messages = sub.snapshot()
    events = sum(1 for t, _, _ in messages if t.endswith("/events"))
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    frames = sum(1 for e in lines if e["type"] == "frame")
    print(f"capture: {frames} frames, {want} events (jsonl); pvtap exit {run.returncode} "
          f"{run.stderr.strip()}")
    print(f"pvtap audit --mqtt: {wall:.2f} s wall, CPU {cpu:.2f} s, peak RSS "
          f"{after.ru_maxrss / 1024:.1f} MiB (of any child so far)")
    print(f"broker passed on {len(messages)} messages ({events} events of {want}): "
          f"{len(messages) / wall:.0f} messages/s while pvtap ran")
    sub.close()
    broker.stop()
    return 0 if run.returncode == 0 and events == want else 1


if __name__ == "__main__":
    sys.exit(main())
