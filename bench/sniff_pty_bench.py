#!/usr/bin/env python3
"""Live sniffing at full speed: a simulated bus at 115200 baud is paced onto a real
pseudo-terminal for a minute while `pvtap sniff --format jsonl` reads the other side.

Measures what a field engineer cares about on a small logger box:
- lost bytes and frames (must be none: every byte in a frame or noise, every frame found);
- pvtap's CPU time as a share of the wall time, and its peak memory;
- latency from the write of a frame's last byte to its jsonl line on pvtap's stdout.

With --mqtt, pvtap also publishes to a mosquitto broker the script starts on a free loopback
port (tests/analyzer/mqtt/mqtt_broker.py; run with Debian's /usr/bin/python3 for its paho),
and the script counts the messages a subscriber receives.

usage: sniff_pty_bench.py --pvtap build/analyzer/pvtap --sim build/captures/pvtap-sim
       [--baud 115200] [--duration 60] [--inverters 16] [--period 0.2] [--busy]
       [--faults none|all] [--mqtt] [--mqtt-interval 10]
"""
import argparse
import bisect
import json
import os
import resource
import signal
import subprocess
import sys
import tempfile
import threading
import time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tests",
                                "analyzer", "sniff"))
sys.dont_write_bytecode = True  # no __pycache__ in the source tree
import pty_bus  # noqa: E402

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tests",
                                "analyzer", "mqtt"))


def read_lines(stream, lines):
    for line in stream:
        lines.append((time.monotonic(), line))


def peak_rss_kib(pid):
    """pvtap's peak resident memory so far. (The rusage of a forked child also counts the
    forking Python's memory from before the exec, which here holds the whole ground truth.)"""
    with open(f"/proc/{pid}/status", encoding="ascii") as f:
        for line in f:
            if line.startswith("VmHWM:"):
                return int(line.split()[1])
    return 0


def percentile(values, p):
    values = sorted(values)
    return values[min(len(values) - 1, int(p / 100.0 * len(values)))]


def last_byte_write_times(events, writes):
    """For each frame event, when the write holding its last byte returned."""
    ends, total = [], 0
    for event in events:
        total += len(event["hex"]) // 2
        if event["type"] == "frame":
            ends.append(total)
    written = [n for n, _ in writes]
    return [writes[bisect.bisect_left(written, end)][1] for end in ends]


def squeeze(events, baud, bits_per_char=10):
    """The same frames with every silence cut to just over t3.5 (4 character times; 2 ms
    above 19200 baud, where Modbus fixes t3.5 at 1.75 ms): the busiest line a master that
    keeps the rules can make."""
    char_s = bits_per_char / baud
    silence = max(4 * char_s, 2e-3 if baud > 19200 else 0.0)
    out, end = [], None
    for event in events:
        event = dict(event)
        if end is not None:
            event["ts"] = end + silence
        end = event["ts"] + len(event["hex"]) // 2 * char_s
        out.append(event)
    return out


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--pvtap", required=True)
    parser.add_argument("--sim", required=True)
    parser.add_argument("--baud", type=int, default=115200)
    parser.add_argument("--duration", type=float, default=60)
    parser.add_argument("--inverters", type=int, default=16)
    parser.add_argument("--period", type=float, default=0.2)
    parser.add_argument("--busy", action="store_true",
                        help="squeeze the silences to just over t3.5; "
                             "the simulated duration is then cut to fill --duration")
    parser.add_argument("--faults", default="none", help="pvtap-sim's --faults")
    parser.add_argument("--mqtt", action="store_true", help="also publish to a local broker")
    parser.add_argument("--mqtt-interval", default="10")
    args = parser.parse_args()
    scratch = tempfile.mkdtemp(prefix="pvtap-sniff-bench-")
    # Squeezed, a simulated minute lasts about a tenth of one.
    sim_seconds = args.duration * (15 if args.busy else 1)
    truth = pty_bus.simulate(args.sim, scratch, "bench",
                             ["--dialect", "gsl,hybrid,ascii", "--inverters",
                              str(args.inverters), "--duration", str(sim_seconds), "--period",
                              str(args.period), "--baud", str(args.baud), "--seed", "1",
                              "--faults", args.faults])
    events = truth["events"]
    if args.busy:
        events = squeeze(events, args.baud)
        while len(events) > 1 and events[-1]["ts"] - events[0]["ts"] > args.duration:
            events.pop()
    pty = pty_bus.Pty()
    mqtt, broker, sub = [], None, None
    if args.mqtt:
        import mqtt_broker
        broker = mqtt_broker.Broker(scratch, "bench")
        sub = mqtt_broker.Subscriber(broker)
        mqtt = ["--mqtt", broker.url(), "--mqtt-user", mqtt_broker.USER, "--mqtt-password-file",
                broker.password_file, "--mqtt-topic", "bench", "--mqtt-interval",
                args.mqtt_interval, "--mqtt-discovery"]
    proc = subprocess.Popen([args.pvtap, "sniff", "--device", pty.path, "--baud",
                             str(args.baud), "--format", "jsonl", "--timeout",
                             str(truth["timeout_s"]), *mqtt],
                            stdout=subprocess.PIPE, text=True)
    lines = []
    reader = threading.Thread(target=read_lines, args=(proc.stdout, lines))
    reader.start()
    time.sleep(1.0)  # let pvtap open the device
    writes = []
    started = time.monotonic()
    late = pty_bus.play(pty.master, pty_bus.byte_schedule(events, args.baud, bursts=False), started, writes)
    time.sleep(1.5)
    wall = time.monotonic() - started
    peak_kib = peak_rss_kib(proc.pid)
    proc.send_signal(signal.SIGTERM)
    _, status, usage = os.wait4(proc.pid, 0)
    proc.returncode = os.waitstatus_to_exitcode(status)
    reader.join()
    pty.close()

    parsed = [(t, json.loads(line)) for t, line in lines if line.strip()]
    frames = [(t, e) for t, e in parsed if e["type"] == "frame"]
    summary = parsed[-1][1]
    truth_frames = [e for e in events if e["type"] == "frame"]
    same = [e["raw"] for _, e in frames] == [e["hex"] for e in truth_frames]
    due = last_byte_write_times(events, writes)
    latency_ms = [(t - d) * 1e3 for (t, _), d in zip(frames, due)]
    cpu = usage.ru_utime + usage.ru_stime
    bus_bytes = sum(len(e["hex"]) // 2 for e in events)
    print(f"exit status {proc.returncode}; writer at most {late * 1e3:.1f} ms late")
    print(f"bus: {bus_bytes} bytes, {len(truth_frames)} frames in {args.duration:.0f} s at "
          f"{args.baud} baud ({bus_bytes / args.duration:.0f} B/s, "
          f"{bus_bytes * 10 / args.baud / args.duration * 100:.0f} % of the line)")
    print(f"pvtap: {summary['bytes']} bytes, {len(frames)} frames, lost bytes "
          f"{summary['lost_bytes']}, noise bytes {summary['noise_bytes']}, "
          f"frames identical to the bus: {same}, reads {summary['devices'][0]['reads']}")
    print(f"pvtap CPU: {cpu:.2f} s over {wall:.1f} s wall = {cpu / wall * 100:.2f} % of one "
          f"core (user {usage.ru_utime:.2f} s, system {usage.ru_stime:.2f} s); peak RSS while "
          f"capturing {peak_kib / 1024:.1f} MiB")
    print(f"latency, last byte written to jsonl line read (ms): p50 "
          f"{percentile(latency_ms, 50):.2f}, p99 {percentile(latency_ms, 99):.2f}, max "
          f"{max(latency_ms):.2f}")
    ok = proc.returncode == 0 and same and summary["bytes"] == bus_bytes
    if sub is not None:
        ok = report_mqtt(sub, parsed, wall) and ok
        sub.close()
        broker.stop()
    return 0 if ok else 1


def report_mqtt(sub, parsed, wall):
    """Messages the broker passed on, by kind; the events must be all of jsonl's."""
    time.sleep(1.0)
    messages = sub.snapshot()
    kinds = {}
    for topic, _, _ in messages:
        kind = ("discovery" if topic.startswith("homeassistant/") else topic.rsplit("/", 1)[-1]
                if topic.endswith(("/events", "/health", "/state", "/status", "/availability"))
                else "value")
        kinds[kind] = kinds.get(kind, 0) + 1
    events = [m for m in messages
              if m[0].endswith("/events") and '"type":"station_' not in m[1]]
    want = [e for _, e in parsed if e["type"] in ("timeout", "gap") or
            (e["type"] == "frame" and (e["check"] == "bad" or any(
                i.startswith(("malformed", "unsolicited", "late reply", "exception",
                              "error reply")) for i in e["issues"])))]
    print(f"MQTT: {len(messages)} messages in {wall:.1f} s = {len(messages) / wall:.1f}/s "
          f"({', '.join(f'{k} {n}' for k, n in sorted(kinds.items()))}); events "
          f"{len(events)} of {len(want)} jsonl events")
    return len(events) == len(want)


if __name__ == "__main__":
    sys.exit(main())
