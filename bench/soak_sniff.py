#!/usr/bin/env python3
"""The soak: hours of live sniffing through a real pseudo-terminal at 115200 baud, on a bus with
every fault the simulator makes, the adapter unplugged and the MQTT broker restarted on a
schedule, while pvtap's memory and CPU are sampled.

The bus is played in segments of --segment-minutes (default 10), each a fresh simulation
(`--faults all`: damage, noise, silences, missing and late replies, ...). Between two
segments the pty behind a by-id style link is closed (pvtap sees the adapter go away) and a
new one takes its place. The broker (mosquitto on a loopback port) is stopped for 10 s in the
middle of every segment. Every 10 s the script samples pvtap's resident memory and CPU time
and the frames it has written so far: the curve goes to DIR/soak.csv.

Checked at the end, and the exit status says whether all held:
- every frame the bus carried is on pvtap's stdout, in order and byte for byte;
- the summary counts every byte played (in frames or noise) and no byte lost; one gap per
  unplug;
- the MQTT subscriber received every event of jsonl (the broker's outages included);
- peak RSS after the first minute stays flat (the figure printed: growth after minute one).

usage (as root, with Debian's /usr/bin/python3 for its paho-mqtt):
  bench/soak_sniff.py --pvtap build/analyzer/pvtap --sim build/captures/pvtap-sim
      [--hours 2] [--segment-minutes 10] [--inverters 8] [--period 0.5] [--out DIR]
"""
import argparse
import os
import sys
import tempfile
import threading
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.dont_write_bytecode = True  # no __pycache__ in the source tree
sys.path.insert(0, os.path.join(HERE, "..", "tests", "analyzer", "sniff"))
sys.path.insert(0, os.path.join(HERE, "..", "tests", "analyzer", "mqtt"))
# The sniff and MQTT tests' own pieces: the sniffer, the by-id link, which jsonl events MQTT
# carries. check_mqtt needs paho-mqtt (Debian's python3-paho-mqtt).
import check_mqtt  # noqa: E402
import check_sniff  # noqa: E402
import mqtt_broker  # noqa: E402
import pty_bus  # noqa: E402

BAUD = 115200
SAMPLE_S = 10
BROKER_AWAY_S = 10


def proc_figures(pid):
    """(VmRSS KiB, VmHWM KiB, CPU seconds) of a running process."""
    rss = hwm = 0
    with open(f"/proc/{pid}/status", encoding="ascii") as f:
        for line in f:
            if line.startswith("VmRSS:"):
                rss = int(line.split()[1])
            elif line.startswith("VmHWM:"):
                hwm = int(line.split()[1])
    with open(f"/proc/{pid}/stat", encoding="ascii") as f:
        fields = f.read().rsplit(")", 1)[1].split()
    ticks = os.sysconf("SC_CLK_TCK")
    return rss, hwm, (int(fields[11]) + int(fields[12])) / ticks


class FrameCounter:
    """Counts the frame lines pvtap has written to its stdout file so far, reading on from
    where it stopped."""

    def __init__(self, path):
        self.path, self.offset, self.frames, self.rest = path, 0, 0, b""

    def count(self):
        with open(self.path, "rb") as f:
            f.seek(self.offset)
            data = f.read()
        self.offset += len(data)
        lines = (self.rest + data).split(b"\n")
        self.rest = lines.pop()
        self.frames += sum(1 for line in lines if line.startswith(b'{"type":"frame"'))
        return self.frames


class Sampler(threading.Thread):
    def __init__(self, pid, counter, csv_path):
        super().__init__(daemon=True)
        self.pid, self.counter, self.rows = pid, counter, []
        self.csv_path, self.stop_event = csv_path, threading.Event()
        self.started = time.monotonic()

    def run(self):
        with open(self.csv_path, "w", encoding="ascii") as out:
            out.write("seconds,rss_kib,peak_rss_kib,cpu_s,frames\n")
            while not self.stop_event.wait(SAMPLE_S):
                try:
                    rss, hwm, cpu = proc_figures(self.pid)
                except OSError:
                    return
                row = (time.monotonic() - self.started, rss, hwm, cpu, self.counter.count())
                self.rows.append(row)
                out.write("%.0f,%d,%d,%.2f,%d\n" % row)
                out.flush()


def simulate(options, scratch, index):
    """One segment's ground truth: its frames' bytes and every byte it plays."""
    truth = pty_bus.simulate(options.sim, scratch, f"segment{index}",
                             ["--dialect", "gsl,hybrid,ascii", "--inverters",
                              str(options.inverters), "--period", str(options.period),
                              "--duration", str(options.segment_minutes * 60), "--baud",
                              str(BAUD), "--seed", str(700 + index), "--faults", "all"])
    os.remove(os.path.join(scratch, f"segment{index}.truth.json"))
    return truth


def restart_broker_mid_segment(broker, segment_s, stop_event, outages):
    """Stops the broker for BROKER_AWAY_S in the middle of every segment."""
    while not stop_event.wait(segment_s / 2):
        broker.stop()
        outages.append(time.time())
        if stop_event.wait(BROKER_AWAY_S):
            broker.start()
            return
        broker.start()
        if stop_event.wait(segment_s / 2 - BROKER_AWAY_S):
            return


def play_segments(options, segments, scratch, link, sniffer, truth, pty):
    """Plays `segments` segments each onto its own pty behind `link`, the first (`truth`) onto
    `pty`; returns (frames' hex, bytes played, the last pty)."""
    frames, played = [], 0
    sniffer.wait_open(link)
    for index in range(segments):
        events = truth["events"]
        started = time.monotonic()
        late = pty_bus.play(pty.master, pty_bus.byte_schedule(events, BAUD), started)
        frames += [e["hex"] for e in events if e["type"] == "frame"]
        played += sum(len(e["hex"]) // 2 for e in events)
        # The last timeout runs out before the adapter goes.
        time.sleep(truth["timeout_s"] + 1.0)
        print(f"segment {index + 1}/{segments}: {len(events)} events played, writer at most "
              f"{late * 1e3:.1f} ms late", flush=True)
        if index + 1 == segments:
            return frames, played, pty
        pty.unplug()
        truth = simulate(options, scratch, index + 1)  # the adapter is away meanwhile
        pty = pty_bus.Pty()
        check_sniff.replace_link(link, pty.path)
        sniffer.wait_open(link)


def report_memory(rows):
    after_minute = [r for r in rows if r[0] >= 60]
    if not after_minute:
        print("memory: too short a run to judge (under a minute)")
        return
    first, last = after_minute[0], rows[-1]
    print(f"memory: RSS {first[1] / 1024:.1f} MiB at minute 1, {last[1] / 1024:.1f} MiB at the "
          f"end; peak {first[2] / 1024:.1f} MiB at minute 1, {last[2] / 1024:.1f} MiB at the end "
          f"(growth {(last[2] - first[2]) / 1024:.1f} MiB over "
          f"{(last[0] - first[0]) / 60:.0f} min)")
    step = max(1, len(rows) // 12)
    print("  minute  RSS MiB  peak MiB  CPU s  frames  CPU us/frame (since the last line)")
    previous = None
    for row in rows[::step] + ([rows[-1]] if (len(rows) - 1) % step else []):
        per_frame = ""
        if previous and row[4] > previous[4]:
            per_frame = "%.1f" % ((row[3] - previous[3]) * 1e6 / (row[4] - previous[4]))
        print(f"  {row[0] / 60:6.0f}  {row[1] / 1024:7.1f}  {row[2] / 1024:8.1f}  {row[3]:5.1f}"
              f"  {row[4]:6d}  {per_frame}")
        previous = row


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--pvtap", required=True)
    parser.add_argument("--sim", required=True)
    parser.add_argument("--hours", type=float, default=2.0)
    parser.add_argument("--segment-minutes", type=float, default=10.0)
    parser.add_argument("--inverters", type=int, default=8)
    parser.add_argument("--period", type=float, default=0.5)
    parser.add_argument("--out", help="folder for the curve and pvtap's output (default: a "
                                      "temporary folder, kept)")
    options = parser.parse_args()
    segments = max(1, round(options.hours * 60 / options.segment_minutes))
    scratch = options.out or tempfile.mkdtemp(prefix="pvtap-soak-")
    os.makedirs(scratch, exist_ok=True)
    broker = mqtt_broker.Broker(scratch, "soak")
    prefix = "soak"
    sub = mqtt_broker.Subscriber(broker, client_id="pvtap-soak-watcher")
    link = os.path.join(scratch, "usb-FTDI_soak-if00-port0")
    truth = simulate(options, scratch, 0)
    pty = pty_bus.Pty()
    check_sniff.replace_link(link, pty.path)
    sniffer = check_sniff.Sniffer(
        options.pvtap, scratch, "sniff",
        ["--device", link, "--baud", str(BAUD), "--format", "jsonl", "--mqtt", broker.url(),
         "--mqtt-user", mqtt_broker.USER, "--mqtt-password-file", broker.password_file,
         "--mqtt-topic", prefix, "--mqtt-interval", "10"])
    sampler = Sampler(sniffer.proc.pid, FrameCounter(sniffer.out_path),
                      os.path.join(scratch, "soak.csv"))
    sampler.start()
    stop_restarts, outages = threading.Event(), []
    restarts = threading.Thread(target=restart_broker_mid_segment,
                                args=(broker, options.segment_minutes * 60, stop_restarts,
                                      outages), daemon=True)
    restarts.start()
    truth_frames, played, pty = play_segments(options, segments, scratch, link, sniffer, truth,
                                              pty)
    stop_restarts.set()
    restarts.join()
    sampler.stop_event.set()
    sampler.join()
    status = sniffer.stop()
    pty.close()

    lines = sniffer.events()
    frames, summary = check_sniff.frames_of(lines), lines[-1]
    events = check_mqtt.expected_events(lines)
    sub.wait_for(lambda m: len(check_mqtt.mqtt_events(m, prefix)) >= len(events), timeout=60)
    got_mqtt = len(check_mqtt.mqtt_events(sub.snapshot(), prefix))
    sub.close()
    broker.stop()
    same = [f["raw"] for f in frames] == truth_frames
    unplugs = segments - 1
    print(f"pvtap exit status {status}; output in {scratch}")
    print(f"frames: {len(frames)} on stdout, {len(truth_frames)} on the bus, identical: {same}")
    print(f"bytes: {summary['bytes']} read, {played} played; frame bytes "
          f"{summary['frame_bytes']} + noise {summary['noise_bytes']}; lost "
          f"{summary['lost_bytes']}; gaps {summary['gaps']} for {unplugs} unplugs")
    print(f"MQTT: {got_mqtt} events of {len(events)} in jsonl, broker away {len(outages)} times")
    report_memory(sampler.rows)
    ok = (status == 0 and same and summary["bytes"] == played and
          summary["bytes"] == summary["frame_bytes"] + summary["noise_bytes"] and
          summary["lost_bytes"] == 0 and summary["gaps"] == unplugs and got_mqtt == len(events))
    print("soak: " + ("all held" if ok else "FAILED"))
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
