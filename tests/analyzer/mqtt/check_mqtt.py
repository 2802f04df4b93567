#!/usr/bin/python3
"""End-to-end checks of `pvtap sniff --mqtt` and `pvtap audit --mqtt` against a real
mosquitto broker (mqtt_broker.py): a bus paced onto a pty (tests/analyzer/sniff/pty_bus.py) is sniffed
with --format jsonl and --mqtt at once, and what reached the broker is judged against the
jsonl lines of the same run.

usage: check_mqtt.py --pvtap PVTAP --sim PVTAP_SIM --scratch DIR CHECK
checks: values availability outage bad_login tls unreachable replay raw shared_bus
"""
import argparse
import json
import os
import re
import signal
import subprocess
import sys
import threading
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "sniff"))
import check_sniff  # noqa: E402
import pty_bus  # noqa: E402
from check_sniff import Failures, Sniffer, frames_of  # noqa: E402
from mqtt_broker import USER, Broker, Subscriber  # noqa: E402

GUARD_S = 20
INTERVAL = "0.5"
# jsonl frames that are MQTT events: a bad check, or one of these findings.
EVENT_ISSUES = ("malformed", "unsolicited", "late reply", "exception", "error reply")
ENERGY_UNITS = ("kWh", "Wh")


def mqtt_args(broker, prefix, *extra):
    return ["--mqtt", broker.url(), "--mqtt-user", USER, "--mqtt-password-file",
            broker.password_file, "--mqtt-topic", prefix, "--mqtt-interval", INTERVAL, *extra]


def node_id(prefix, station):
    return re.sub(r"[^A-Za-z0-9_-]", "_", prefix).strip("_") + f"_bus_{station}"


def expected_events(lines):
    out = []
    for e in lines:
        if e["type"] == "frame" and (e["check"] == "bad" or
                                     any(i.startswith(EVENT_ISSUES) for i in e["issues"])):
            out.append(e)
        elif e["type"] in ("timeout", "gap"):
            out.append(e)
    return out


def mqtt_events(messages, prefix, station_events=False):
    out = []
    for topic, payload, _ in messages:
        if topic == f"{prefix}/bus/events":
            e = json.loads(payload)
            if station_events == e["type"].startswith("station_"):
                out.append(e)
    return out


def latest_jsonl_values(lines):
    """{station: ({register: value object}, ts of its last good reply)} from jsonl."""
    out = {}
    for f in frames_of(lines):
        if f["role"] != "response" or f["check"] != "ok" or not f["values"]:
            continue
        values, _ = out.get(f["station"], ({}, 0))
        for v in f["values"]:
            if v["name"] is not None and v["value"] is not None:
                values[v["register"]] = v
        out[f["station"]] = (values, f["ts"])
    return out


def check_station(latest, prefix, station, values, ts, discovery, bad):
    """State, value topics and discovery configs of one station against jsonl."""
    base = f"{prefix}/bus/{station}"
    if not bad.check(f"{base}/state" in latest, f"no state topic for station {station}"):
        return 0
    state = json.loads(latest[f"{base}/state"])
    by_register = {v["register"]: v for v in state["values"].values()}
    differ = sorted(r for r in set(by_register) | set(values)
                    if by_register.get(r) != values.get(r))
    bad.check(not differ, f"station {station}: registers {differ[:5]} differ from jsonl: "
              f"{[(by_register.get(r), values.get(r)) for r in differ[:2]]}")
    bad.check(state["ts"] == ts, f"station {station}: state ts {state['ts']}, jsonl {ts}")
    bad.check(latest.get(f"{base}/availability") == "online", f"station {station} not online")
    energy = 0
    for key, v in state["values"].items():
        payload = latest.get(f"{base}/{key}")
        want = v["value"]
        same = payload == want if isinstance(want, str) else (
            payload is not None and float(payload) == want)
        bad.check(same, f"{base}/{key}: {payload!r}, jsonl {want!r}")
        if discovery:
            energy += check_discovery(latest, prefix, station, key, v, bad)
    return energy


def check_discovery(latest, prefix, station, key, v, bad):
    topic = f"homeassistant/sensor/{node_id(prefix, station)}/{key}/config"
    if not bad.check(topic in latest, f"no discovery config {topic}"):
        return 0
    cfg = json.loads(latest[topic])
    base = f"{prefix}/bus/{station}"
    bad.check(cfg["state_topic"] in (f"{base}/{key}", f"{base}/state"),
              f"{topic}: state_topic {cfg['state_topic']}")
    if isinstance(v["value"], (int, float)) and "unit" in v:
        bad.check(cfg.get("unit_of_measurement") == v["unit"],
                  f"{topic}: unit {cfg.get('unit_of_measurement')}, jsonl {v['unit']}")
    if v.get("unit") in ENERGY_UNITS:
        bad.check(cfg.get("state_class") == "total_increasing" and
                  cfg.get("device_class") == "energy", f"{topic}: energy sensor {cfg}")
        return 1
    return 0


def check_values_and_events(sub, prefix, lines, bad, discovery=True):
    latest = sub.latest()
    stations = latest_jsonl_values(lines)
    bad.check(len(stations) >= 2, f"only {len(stations)} stations answered")
    energy = 0
    for station, (values, ts) in sorted(stations.items()):
        energy += check_station(latest, prefix, station, values, ts, discovery, bad)
    if discovery:
        bad.check(energy > 0, "no energy sensor among the discovery configs")
    want = expected_events(lines)
    got = mqtt_events(sub.snapshot(), prefix)
    bad.check(len(want) > 0, "the bus had no events to publish")
    bad.check(got == want, f"{len(got)} MQTT events differ from the {len(want)} jsonl events")
    summary = lines[-1] if lines and lines[-1]["type"] == "summary" else None
    health = json.loads(latest.get(f"{prefix}/bus/health", "{}"))
    if summary is not None:
        for key, skey in (("frames", "frames"), ("damaged_frames", "bad_checks"),
                          ("timeouts", "timeouts"), ("noise_bytes", "noise_bytes"),
                          ("address_conflicts", "address_conflicts")):
            bad.check(health.get(key) == summary[skey],
                      f"health {key} {health.get(key)}, summary {skey} {summary[skey]}")
        check_sharing(health, summary, bad)


def check_sharing(health, summary, bad):
    """The health's masters, collisions and echoes are the summary's."""
    want = {key: summary[key] for key in ("collisions", "lost_in_collision", "echoes")}
    want["masters"] = len(summary["buses"][0]["masters"])
    got = {key: health.get(key) for key in want}
    bad.check(got == want, f"health {got}, summary {want}")


def sniff_run(args, broker, prefix, name, *extra, pcap=None):
    pty = pty_bus.Pty()
    more = ["--write", pcap] if pcap else []
    sniffer = Sniffer(args.pvtap, args.scratch, name,
                      ["--device", pty.path, "--format", "jsonl", *more,
                       *mqtt_args(broker, prefix, *extra)])
    sniffer.wait_open(pty.path)
    return pty, sniffer


def check_station_outages(sub, prefix, lines, stations, bad):
    """The bus fell silent between two plays: each station went offline once with its last
    reply's time, then online again."""
    events = mqtt_events(sub.snapshot(), prefix, station_events=True)
    for station in stations:
        seq = [(e["type"], e["last_reply_ts"]) for e in events if e["station"] == station]
        replies = [f["ts"] for f in frames_of(lines) if f["station"] == station and
                   f["role"] == "response" and f["check"] == "ok" and f["values"]]
        before = max((t for t in replies if seq and t <= seq[0][1]), default=None)
        bad.check([t for t, _ in seq] == ["station_offline", "station_online"],
                  f"station {station}: events {seq}")
        bad.check(bool(seq) and seq[0][1] == before,
                  f"station {station}: offline after {seq[:1]}, last reply before it {before}")


def check_availability(args):
    """A master polling every 0.3 s falls silent for 2.5 s, then polls again: each station
    goes offline once (with the time of its last reply) and online again, as events and as
    its availability topic."""
    bad = Failures()
    broker = Broker(args.scratch, "availability")
    sub = Subscriber(broker)
    prefix = "test/availability"
    first, again = (pty_bus.simulate(args.sim, args.scratch, f"mqtt-availability-{seed}",
                                     ["--baud", str(check_sniff.BAUD), "--dialect", "gsl",
                                      "--inverters", "2", "--period", "0.3", "--duration",
                                      duration, "--seed", seed])
                    for seed, duration in (("8", "2.5"), ("9", "1.5")))
    pty, sniffer = sniff_run(args, broker, prefix, "availability")
    check_sniff.play_truth(pty, first)
    time.sleep(2.5)  # over three poll periods, and over the shortest outage (1 s)
    check_sniff.play_truth(pty, again)
    bad.check(sniffer.stop() == 0, f"exit status {sniffer.proc.returncode}: {sniffer.stderr()}")
    pty.close()
    lines = sniffer.events()
    sub.wait_for(lambda m: sub.latest().get(f"{prefix}/status") == "offline")
    stations = sorted(latest_jsonl_values(lines))
    bad.check(stations == [1, 2], f"stations {stations}")
    check_station_outages(sub, prefix, lines, stations, bad)
    for station in stations:
        seq = [p for t, p, _ in sub.snapshot() if t == f"{prefix}/bus/{station}/availability"]
        bad.check("offline" in seq and seq[-1] == "online", f"station {station}: {seq}")
    sub.close()
    broker.stop()
    return bad.exit_status("availability")


def check_values(args):
    """A paced bus with faults: every value topic, the state topics and the discovery configs
    carry what jsonl carries; the events are jsonl's lines, in order; status online, then
    offline after SIGTERM."""
    bad = Failures()
    broker = Broker(args.scratch, "values")
    sub = Subscriber(broker)
    prefix = "test/values"
    truth = check_sniff.simulate(args, "mqtt-values", "--dialect", "gsl,hybrid", "--inverters",
                                 "3", "--duration", "4", "--seed", "3", "--faults", "all")
    pty, sniffer = sniff_run(args, broker, prefix, "values", "--mqtt-discovery",
                             "--timeout", str(truth["timeout_s"]))
    bad.check(sub.wait_for(lambda m: sub.latest().get(f"{prefix}/status") == "online"),
              "no online status")
    check_sniff.play_truth(pty, truth)
    bad.check(sniffer.stop() == 0, f"exit status {sniffer.proc.returncode}: {sniffer.stderr()}")
    pty.close()
    lines = sniffer.events()
    bad.check(sub.wait_for(lambda m: sub.latest().get(f"{prefix}/status") == "offline"),
              "status not offline after SIGTERM")
    check_values_and_events(sub, prefix, lines, bad)
    sub.close()
    broker.stop()
    return bad.exit_status("values")


def check_outage(args):
    """The broker stops for 10 s mid-capture and starts again: stdout and the pcap miss no
    frame, the events of the outage arrive afterwards in order, and SIGKILL fires the will."""
    bad = Failures()
    broker = Broker(args.scratch, "outage")
    sub = Subscriber(broker, client_id="pvtap-test-outage")
    prefix = "test/outage"
    truth = check_sniff.simulate(args, "mqtt-outage", "--dialect", "gsl", "--inverters", "2",
                                 "--duration", "15", "--seed", "7", "--faults", "all")
    pcap = os.path.join(args.scratch, "outage.pcap")
    pty, sniffer = sniff_run(args, broker, prefix, "outage", "--timeout",
                             str(truth["timeout_s"]), pcap=pcap)

    away_times = []

    def outage():
        time.sleep(2.5)
        broker.stop()
        away_times.append(time.time())  # jsonl times of a live capture are wall-clock
        time.sleep(10)
        broker.start()
        away_times.append(time.time())

    away = threading.Thread(target=outage)
    away.start()
    check_sniff.play_truth(pty, truth)
    away.join()
    lines = sniffer.events()
    want = expected_events(lines)
    # The events of the outage reach the broker once pvtap has reconnected (backoff).
    sub.wait_for(lambda m: len(mqtt_events(m, prefix)) >= len(want), timeout=40)
    bad.check(sniffer.stop(signal.SIGKILL) == -signal.SIGKILL, "pvtap outlived SIGKILL")
    pty.close()
    lines = sniffer.events()
    check_sniff.compare_frames(frames_of(lines),
                               [e for e in truth["events"] if e["type"] == "frame"], "stdout",
                               bad)
    read_back = check_sniff.audit_frames(args, pcap)
    bad.check([check_sniff.frame_key(f, "raw") for f in read_back] ==
              [check_sniff.frame_key(f, "raw") for f in frames_of(lines)],
              f"the pcap holds {len(read_back)} frames, stdout {len(frames_of(lines))}")
    got = mqtt_events(sub.snapshot(), prefix)
    want = expected_events(lines)
    outage_events = [e for e in want if away_times[0] < e["ts"] < away_times[1]]
    bad.check(len(outage_events) > 0, "no event fell in the outage")
    bad.check(got == want, f"{len(got)} MQTT events differ from the {len(want)} jsonl events")
    bad.check(sub.wait_for(lambda m: sub.latest().get(f"{prefix}/status") == "offline"),
              "the last will did not mark the site offline after SIGKILL")
    sub.close()
    broker.stop()
    return bad.exit_status("outage")


def check_refused(args, name, broker, extra, want_text, sub):
    """pvtap sniff exits 2 with one clear line, and nothing reached the broker."""
    bad = Failures()
    pty = pty_bus.Pty()
    run = subprocess.run([args.pvtap, "sniff", "--device", pty.path, "--format", "jsonl",
                          *extra], capture_output=True, text=True, timeout=GUARD_S)
    pty.close()
    err = run.stderr.strip()
    bad.check(run.returncode == 2, f"{name}: exit status {run.returncode}, want 2 ({err})")
    bad.check(len(err.splitlines()) == 1 and want_text in err, f"{name}: stderr {err!r}")
    bad.check(run.stdout == "", f"{name}: stdout {run.stdout[:80]!r}")
    if sub is not None:
        time.sleep(0.5)
        bad.check(sub.snapshot() == [], f"{name}: published {sub.snapshot()[:2]}")
    return bad


def check_bad_login(args):
    broker = Broker(args.scratch, "login")
    sub = Subscriber(broker)
    wrong = os.path.join(broker.folder, "wrong.pw")
    with open(wrong, "w") as f:
        f.write("not-the-password\n")
    extra = ["--mqtt", broker.url(), "--mqtt-user", USER, "--mqtt-password-file", wrong]
    bad = check_refused(args, "wrong password", broker, extra, "refused the connection", sub)
    sub.close()
    broker.stop()
    return bad.exit_status("bad_login")


def check_unreachable(args):
    from mqtt_broker import free_port
    extra = ["--mqtt", f"mqtt://127.0.0.1:{free_port()}"]
    bad = check_refused(args, "unreachable", None, extra, "Connection refused", None)
    return bad.exit_status("unreachable")


def check_tls(args):
    """TLS with a CA made here: values flow over mqtts; a CA that did not sign the broker's
    certificate is a clear error, exit 2, nothing published."""
    from mqtt_broker import make_ca
    good, other = make_ca(args.scratch, "good"), make_ca(args.scratch, "other")
    broker = Broker(args.scratch, "tls", tls=good)
    sub = Subscriber(broker)
    extra = ["--mqtt", broker.url(), "--mqtt-user", USER, "--mqtt-password-file",
             broker.password_file, "--mqtt-ca", other["ca"]]
    bad = check_refused(args, "wrong CA", broker, extra, "certificate verify failed", sub)
    prefix = "test/tls"
    truth = check_sniff.simulate(args, "mqtt-tls", "--dialect", "gsl", "--inverters", "2",
                                 "--duration", "2", "--seed", "4")
    pty, sniffer = sniff_run(args, broker, prefix, "tls", "--mqtt-ca", good["ca"])
    check_sniff.play_truth(pty, truth)
    bad.check(sniffer.stop() == 0, f"exit status {sniffer.proc.returncode}: {sniffer.stderr()}")
    pty.close()
    # The site goes offline last, after every value: until it has arrived, the broker may still
    # be delivering the last values to the subscriber.
    bad.check(sub.wait_for(lambda m: sub.latest().get(f"{prefix}/status") == "offline"),
              "status not offline after the sniffer stopped")
    latest = sub.latest()
    stations = latest_jsonl_values(sniffer.events())
    for station, (values, ts) in sorted(stations.items()):
        check_station(latest, prefix, station, values, ts, False, bad)
    bad.check(len(stations) == 2, f"{len(stations)} stations over TLS")
    sub.close()
    broker.stop()
    return bad.exit_status("tls")


def check_no_phantom_station(latest, prefix, capture, bad):
    """A damaged frame's station byte (mixed-faults has damaged frames claiming 0 and 34) makes
    no retained station topic and no Home Assistant device: only the simulated inverters do."""
    truth_path = re.sub(r"\.[a-z0-9]+\.pcap$", ".truth.json", capture)
    with open(truth_path, encoding="utf-8") as f:
        truth = json.load(f)
    inverters = set(range(truth["first_station"], truth["first_station"] + truth["inverters"]))
    inverters |= {d["station"] for d in truth.get("devices", [])}  # plain Modbus devices
    retained = {int(m.group(1)) for m in
                (re.match(re.escape(prefix) + r"/bus/(\d+)/", t) for t in latest) if m}
    devices = {int(m.group(1)) for m in
               (re.match(r"homeassistant/\w+/.*_bus_(\d+)/", t) for t in latest) if m}
    bad.check(retained == inverters, f"retained station topics {sorted(retained)}, "
              f"inverters {sorted(inverters)}")
    bad.check(devices <= inverters, f"Home Assistant devices {sorted(devices)}, "
              f"inverters {sorted(inverters)}")


def check_replay(args):
    """pvtap audit --mqtt replays a capture: events and states carry the capture's times,
    no status is claimed for the site."""
    bad = Failures()
    broker = Broker(args.scratch, "replay")
    sub = Subscriber(broker)
    prefix = "test/replay"
    capture = os.path.join(HERE, "..", "..", "..", "captures", "samples",
                           "mixed-faults.user0.pcap")
    run = subprocess.run([args.pvtap, "audit", "--format", "jsonl", capture,
                          *mqtt_args(broker, prefix, "--mqtt-discovery")],
                         capture_output=True, text=True, timeout=GUARD_S)
    bad.check(run.returncode == 0, f"audit exit {run.returncode}: {run.stderr}")
    lines = [json.loads(line) for line in run.stdout.splitlines()]
    want = expected_events(lines)
    sub.wait_for(lambda m: len(mqtt_events(m, prefix)) >= len(want))
    check_values_and_events(sub, prefix, lines, bad)
    bad.check(f"{prefix}/status" not in sub.latest(), "a replay published the site's status")
    check_no_phantom_station(sub.latest(), prefix, capture, bad)
    sub.close()
    broker.stop()
    return bad.exit_status("replay")


def check_shared_bus(args):
    """On a bus of two masters that collide, and on one whose tap echoes its master, the
    health's masters, collisions and echoes are the audit's summary's, by the same rules."""
    bad = Failures()
    runs = {"masters": ["--seed", "37", "--inverters", "2", "--timeout", "0.3", "--masters", "2"],
            "echo": ["--seed", "5", "--inverters", "3", "--echo"]}
    for name, sim_args in runs.items():
        capture = os.path.join(args.scratch, f"shared-{name}.pdu.pcap")
        subprocess.run([args.sim, *sim_args, "--period", "1", "--duration", "60",
                        "--pdu", capture], check=True, timeout=GUARD_S)
        broker = Broker(args.scratch, "shared-" + name)
        sub = Subscriber(broker)
        prefix = "test/shared"
        run = subprocess.run([args.pvtap, "audit", "--summary-only", "--format", "jsonl", capture,
                              *mqtt_args(broker, prefix)],
                             capture_output=True, text=True, timeout=GUARD_S)
        bad.check(run.returncode == 0, f"{name}: audit exit {run.returncode}: {run.stderr}")
        summary = json.loads(run.stdout.splitlines()[-1])
        topic = f"{prefix}/bus/health"
        sub.wait_for(lambda m: json.loads(dict((t, p) for t, p, _ in m).get(topic, "{}"))
                     .get("frames") == summary["frames"])
        health = json.loads(sub.latest(prefix).get(topic, "{}"))
        check_sharing(health, summary, bad)
        if name == "masters":
            bad.check(health.get("masters") == 2 and health.get("collisions", 0) > 0,
                      f"two masters that collide: health {health}")
        else:
            bad.check(health.get("masters") == 1 and health.get("echoes", 0) > 0,
                      f"an echoing tap: health {health}")
        sub.close()
        broker.stop()
    return bad.exit_status("shared_bus")


def check_raw(args):
    """MQTT publishes mapped values only; --mqtt-raw adds the words no map names (a meter's
    floats, an IO module's registers), keyed by table and address, as the summary has them."""
    bad = Failures()
    capture = os.path.join(HERE, "..", "..", "..", "captures", "samples", "plant-mixed.pdu.pcap")
    raw_key = re.compile(r"/(input_)?reg_0x[0-9a-f]{4}$")
    for extra in ((), ("--mqtt-raw",)):
        broker = Broker(args.scratch, "raw" + "".join(extra))
        sub = Subscriber(broker)
        prefix = "test/raw"
        run = subprocess.run([args.pvtap, "audit", "--summary-only", "--format", "jsonl", capture,
                              *mqtt_args(broker, prefix, *extra)],
                             capture_output=True, text=True, timeout=GUARD_S)
        bad.check(run.returncode == 0, f"audit exit {run.returncode}: {run.stderr}")
        summary = json.loads(run.stdout.splitlines()[-1])
        sub.wait_for(lambda m: any(t.startswith(prefix + "/bus/") for t, _, _ in m))
        time.sleep(1.0)
        latest = sub.latest(prefix)
        raw = {t: p for t, p in latest.items() if raw_key.search(t)}
        if not extra:
            bad.check(not raw, f"without --mqtt-raw, raw words were published: {sorted(raw)[:5]}")
        else:
            want = {f"{prefix}/bus/{station}/{v['key']}": v["value"]
                    for station, st in summary["stations"].items() for v in st["values"]
                    if v["name"] is None and v.get("table") in ("holding", "input")}
            bad.check(want and set(want) == set(raw),
                      f"--mqtt-raw published {len(raw)} raw topics, the summary has {len(want)}")
            wrong = [t for t, p in raw.items() if t in want and float(p) != float(want[t])]
            bad.check(not wrong, f"raw payloads differ from the summary: {wrong[:5]}")
        sub.close()
        broker.stop()
    return bad.exit_status("raw")


CHECKS = {"raw": check_raw, "values": check_values, "availability": check_availability, "outage": check_outage, "bad_login": check_bad_login,
          "tls": check_tls, "unreachable": check_unreachable, "replay": check_replay,
          "shared_bus": check_shared_bus}


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--pvtap", required=True)
    parser.add_argument("--sim", required=True)
    parser.add_argument("--scratch", required=True)
    parser.add_argument("check", choices=sorted(CHECKS))
    args = parser.parse_args()
    os.makedirs(args.scratch, exist_ok=True)
    return CHECKS[args.check](args)


if __name__ == "__main__":
    sys.exit(main())
