#!/usr/bin/env python3
"""Runs `pvtap audit --format jsonl` on one sample capture and compares what it finds with
the simulator's ground truth: frames (bytes, roles, check verdicts), timeouts, noise, register
values, the poll blocks, the stations, the masters and the summary's totals. Timestamps,
latencies and poll periods are compared only on the link type 252 carrier, whose records keep
the bus timing; the other carriers re-time the bytes.

usage: check_sample_audit.py PVTAP CAPTURE TRUTH
"""
import itertools
import json
import re
import subprocess
import sys

SUMMARY_KEYS = ("bytes", "frames", "requests", "responses", "bad_checks", "timeouts",
                "damaged_replies", "unanswered_damaged_requests", "noise_bytes", "exceptions")


def audit(pvtap, capture):
    run = subprocess.run([pvtap, "audit", "--format", "jsonl", capture],
                         capture_output=True, text=True, check=False)
    if run.returncode != 0:
        sys.exit(f"pvtap audit exited {run.returncode}: {run.stderr.strip()}")
    return [json.loads(line) for line in run.stdout.splitlines() if line.strip()]


def compare_example_lists(pvtap, capture, bad):
    """The text report's example lists under "bad checks: N" and "timeouts: N" show every one
    or say how many of the N they show."""
    run = subprocess.run([pvtap, "audit", "--summary-only", capture], capture_output=True,
                         text=True, check=False)
    lines = run.stdout.splitlines()
    for i, line in enumerate(lines):
        head = re.match(r"(bad checks|timeouts): (\d+)", line)
        if not head:
            continue
        total = int(head.group(2))
        below = list(itertools.takewhile(lambda x: x.startswith("  "), lines[i + 1:]))
        said = re.fullmatch(r"  (\d+) of (\d+) shown:", below[0]) if below else None
        shown = len(below) - (1 if said else 0)
        if shown < total and not (said and int(said.group(1)) == shown
                                  and int(said.group(2)) == total):
            bad.add(f"{head.group(1)}: {total}, {shown} examples, and no \"{shown} of {total}\"")
        if said and shown >= total:
            bad.add(f"{head.group(1)}: all {total} shown, yet the list says {below[0].strip()!r}")


def frame_key(frame, raw_field):
    return (frame["role"], frame["station"], frame["function"], frame["check"],
            frame[raw_field])


def same_number(a, b):
    return abs(a - b) <= 1e-6 * max(1.0, abs(b))


class Mismatches:
    def __init__(self):
        self.items = []

    def add(self, text):
        self.items.append(text)

    def report(self, capture):
        if not self.items:
            return 0
        print(f"{capture}: {len(self.items)} disagreement(s) with the ground truth")
        for text in self.items[:20]:
            print("  " + text)
        return 1


def compare_frames(found, truth, timed, bad):
    if len(found) != len(truth):
        bad.add(f"frames: audit found {len(found)}, ground truth has {len(truth)}")
    for i, (f, t) in enumerate(zip(found, truth)):
        if frame_key(f, "raw") != frame_key(t, "hex"):
            bad.add(f"frame {i}: audit {frame_key(f, 'raw')} != truth {frame_key(t, 'hex')}")
            break
        # A damaged frame's dialect is a reader's guess from bytes that may be the damaged ones.
        if t["check"] == "ok" and f["dialect"] != t["dialect"]:
            bad.add(f"frame {i}: dialect {f['dialect']} != truth {t['dialect']}")
        if timed and not same_number(f["ts"], t["ts"]):
            bad.add(f"frame {i}: ts {f['ts']} != {t['ts']}")
        if timed and "latency_ms" in f and not abs(f["latency_ms"] - t["latency_ms"]) < 0.002:
            bad.add(f"frame {i}: latency {f['latency_ms']} != {t['latency_ms']}")
        compare_values(i, f, t, bad)
        # The echo of 0x05 0x06 0x08 0x15 0x16 is their normal reply: nothing to note.
        if t["role"] == "response" and t["dialect"] in ("gsl", "modbus") \
                and t["function"] in (0x05, 0x06, 0x08, 0x15, 0x16) \
                and any(x.startswith("echo of") for x in f["issues"]):
            bad.add(f"frame {i}: the normal echo noted: {f['issues']}")
        # A read broadcast to address 0 is a finding (and, in the truth, no timeout).
        if t.get("fault") == "broadcast_read" and not any(
                x.startswith("broadcast to address 0") for x in f["issues"]):
            bad.add(f"frame {i}: a broadcast read without its finding: {f['issues']}")
        # A write whose byte count disagrees with its quantity is a finding.
        if t.get("fault") == "write_count_mismatch" and not any(
                x.startswith("byte count") and "quantity written" in x for x in f["issues"]):
            bad.add(f"frame {i}: a write count mismatch without its finding: {f['issues']}")
        # A write whose byte count says fewer bytes than it carries: a malformed frame.
        if t.get("fault") == "byte_count_lies" and not any(
                x.startswith("malformed") for x in f["issues"]):
            bad.add(f"frame {i}: a byte count that lies, not malformed: {f['issues']}")
        # A user-defined code's frame is a frame of it, not noise and not malformed.
        if t.get("fault") == "user_defined_function" and f["issues"]:
            bad.add(f"frame {i}: a user-defined function's frame with {f['issues']}")
        # A reply one label: late, not also without a request.
        if t.get("fault") == "late_reply" and (
                len(f["issues"]) != 1 or not f["issues"][0].startswith("late reply")):
            bad.add(f"frame {i}: a late reply labelled {f['issues']}")


def compare_values(i, found, truth, bad):
    if truth["role"] != "response" or truth["check"] != "ok":
        return
    if truth.get("fault") == "duplicate":
        return  # answers no request, so its words have no known start address
    values = {v["register"]: v.get("value") for v in found.get("values", [])}
    if truth["dialect"] == "modbus":
        compare_float_words(i, values, truth, bad)
        return
    for v in truth.get("values", []):
        if "value" not in v:
            continue  # bits, enums, text: their raw words are checked with the frame bytes
        got = values.get(v["register"])
        if not isinstance(got, (int, float)) or not same_number(got, v["value"]):
            bad.add(f"frame {i}: register {v['register']} ({v['key']}) = {got}, "
                    f"truth {v['value']}")


def compare_float_words(i, values, truth, bad):
    """A plain Modbus device's truth names the IEEE-754 singles it sent (raw: the 32 bits, high
    word first); audit, given no map for the device, reports each register's word."""
    for v in truth.get("values", []):
        address = int(v["register"], 16)
        high, low = (values.get(f"0x{a:04X}") for a in (address, address + 1))
        if not isinstance(high, int) or not isinstance(low, int) or high << 16 | low != v["raw"]:
            bad.add(f"frame {i}: float at {v['register']} ({v['key']}) words {high}, {low}, "
                    f"truth 0x{v['raw']:08x}")


# Requests whose start and count are poll block fields: reads, and the block writes of plain
# Modbus. A one-register or one-coil write names a start only; other requests neither.
READ_FUNCTIONS = {"gsl": (0x03, 0x04), "hybrid": (0x11, 0x12, 0x16, 0x17, 0x1F), "ascii": (0x52,),
                  "modbus": (0x01, 0x02, 0x03, 0x04, 0x0F, 0x10, 0x17)}
MODBUS_START_ONLY = (0x05, 0x06)
MODBUS_NO_BLOCK = (0x08, 0x11, 0x2B) + tuple(range(0x41, 0x49)) + tuple(range(0x64, 0x6F))


def request_block(frame):
    """(station, dialect, function, start, count) of a poll request, from its bytes."""
    raw = bytes.fromhex(frame["hex"])
    start = count = None
    if frame["dialect"] == "ascii":  # ENQ station(2) R start(4) count(2) checksum(4) EOT
        text = raw[1:-1].decode("ascii")
        start, count = int(text[3:7], 16), int(text[7:9], 16)
    elif frame["function"] in READ_FUNCTIONS[frame["dialect"]]:  # station, function, start, count
        start, count = int.from_bytes(raw[2:4], "big"), int.from_bytes(raw[4:6], "big")
    elif frame["function"] in MODBUS_START_ONLY:
        start = int.from_bytes(raw[2:4], "big")
    return (frame["station"], frame["dialect"], frame["function"], start, count)


def has_block_rule(frame):
    if frame["function"] in READ_FUNCTIONS[frame["dialect"]]:
        return True
    return frame["dialect"] == "modbus" and frame["function"] in MODBUS_START_ONLY + MODBUS_NO_BLOCK


def interval_figures(times):
    """period, jitter (population standard deviation) and max deviation of the intervals, ms"""
    intervals = [(b - a) * 1e3 for a, b in zip(times, times[1:])]
    if not intervals:
        return 0, None, None, None
    mean = sum(intervals) / len(intervals)
    jitter = (sum((i - mean) ** 2 for i in intervals) / len(intervals)) ** 0.5
    return len(intervals), mean, jitter, max(abs(i - mean) for i in intervals)


def compare_polls(summary, truth_frames, timed, bad):
    """One poll period per block the truth's good requests ask for (a damaged request is in
    none); the figures themselves only where the capture keeps the bus timing."""
    times = {}
    for t in truth_frames:
        if t["role"] != "request" or t["check"] != "ok":
            continue
        if not has_block_rule(t):
            bad.add(f"polls: no block rule for {t['dialect']} function {t['function']}")
            return
        times.setdefault(request_block(t), []).append(t["ts"])
    found = {}
    for bus in summary.get("buses", []):
        for p in bus["polls"]:
            key = (p["station"], p["dialect"], p["function"], p["start"], p["count"])
            found[key] = (p["intervals"], p["period_ms"], p["jitter_ms"], p["max_deviation_ms"])
    if sorted(found, key=str) != sorted(times, key=str):
        bad.add(f"poll blocks: audit {sorted(found, key=str)}, truth {sorted(times, key=str)}")
        return
    for key, ts in times.items():
        want = interval_figures(ts)
        if found[key][0] != want[0]:
            bad.add(f"poll block {key}: {found[key][0]} intervals, truth {want[0]}")
        elif timed and want[0] and any(abs(g - w) > 0.01 for g, w in zip(found[key][1:], want[1:])):
            bad.add(f"poll block {key}: period, jitter, max deviation {found[key][1:]} ms, "
                    f"truth {want[1:]}")


def compare_masters(summary, truth, bad):
    """As many masters on the bus as the truth has (a sample without a "masters" list has one),
    so a single logger's bus raises no "two masters" finding."""
    want = len(truth.get("masters", [])) or 1
    for bus in summary.get("buses", []):
        found = len(bus.get("masters", []))
        if found != want:
            periods = [m.get("period_ms") for m in bus.get("masters", [])]
            bad.add(f"masters on bus {bus['bus']}: audit {found} (cycles {periods} ms), "
                    f"truth {want}")


def compare_conflicts(summary, truth, bad):
    """Address conflicts only where the truth has a second device (none in the library): a
    station that repeats a reply is not two devices."""
    want = {c["station"]: c["second_replies"] for c in truth.get("address_conflicts", [])}
    found = {int(k): s.get("address_conflicts") for k, s in summary.get("stations", {}).items()
             if s.get("address_conflicts") != 0}
    if found != want:
        bad.add(f"address conflicts by station: audit {found}, truth {want}")
    collisions = len(truth.get("collisions", []))
    if summary.get("collisions") != collisions or (collisions == 0 and
                                                   summary.get("lost_in_collision") != 0):
        bad.add(f"collisions: audit {summary.get('collisions')}, truth {collisions}")


def compare_stations(summary, truth, bad):
    """The stations are the simulated inverters and plain Modbus devices: a damaged frame's
    station byte names none. The bad checks are each counted once, under a station or the
    unknown station."""
    stations = set(range(truth["first_station"], truth["first_station"] + truth["inverters"]))
    stations |= {d["station"] for d in truth.get("devices", [])}
    # A reply with a good check names its station even when no device has it (a late reply
    # that a peer put on the line for a station nobody has).
    stations |= {e["station"] for e in truth["events"]
                 if e["type"] == "frame" and e["role"] == "response" and e["check"] == "ok"}
    # A broadcast's good request is counted under address 0, as the audit counts it.
    stations |= {0 for e in truth["events"] if e["type"] == "frame" and e["station"] == 0
                 and e["check"] == "ok"}
    stations = sorted(stations)
    found = sorted(int(key) for key in summary.get("stations", {}))
    if found != stations:
        bad.add(f"stations: audit {found}, truth {stations}")
    for d in truth.get("devices", []):
        name = summary.get("stations", {}).get(str(d["station"]), {}).get("device", {}).get("name")
        if "name" in d and name != d["name"]:
            bad.add(f"station {d['station']}: device name {name!r}, truth {d['name']!r}")
    unknown = summary.get("unknown_station", {})
    counted = sum(s["bad_checks"] for s in summary.get("stations", {}).values())
    counted += unknown.get("damaged_frames", 0)
    if counted != summary.get("bad_checks"):
        bad.add(f"bad checks by station {counted} (unknown {unknown}), "
                f"summary {summary.get('bad_checks')}")
    claimed = sum(unknown.get("claimed", {}).values())
    if claimed != unknown.get("damaged_frames", 0):
        bad.add(f"unknown station: claimed {unknown.get('claimed')} != its damaged frames")


def main():
    pvtap, capture, truth_path = sys.argv[1:4]
    with open(truth_path, encoding="utf-8") as f:
        truth = json.load(f)
    events = audit(pvtap, capture)
    timed = capture.endswith(".pdu.pcap")
    bad = Mismatches()
    compare_frames([e for e in events if e["type"] == "frame"],
                   [e for e in truth["events"] if e["type"] == "frame"], timed, bad)
    noise_found = sum(e["bytes"] for e in events if e["type"] == "noise")
    noise_truth = sum(e["bytes"] for e in truth["events"] if e["type"] == "noise")
    if noise_found != noise_truth:
        bad.add(f"noise bytes: audit {noise_found}, truth {noise_truth}")
    # The audit says a timeout when it is decided (a later request to the station can decide
    # it before an earlier request's timer runs out); the truth lists them by request.
    timed_out = sorted((e for e in events if e["type"] == "timeout"), key=lambda e: e["request_ts"])
    timeouts = [(e["station"], e["function"]) for e in timed_out]
    if timeouts != [(t["station"], t["function"]) for t in truth["timeouts"]]:
        bad.add(f"timeouts: audit {timeouts}, truth {truth['timeouts']}")
    ignored = [(e["station"], e["function"]) for e in events
               if e["type"] == "unanswered" and e.get("reason") == "damaged_request"]
    if ignored != [(t["station"], t["function"]) for t in truth["unanswered_damaged_requests"]]:
        bad.add(f"unanswered damaged requests: audit {ignored}, "
                f"truth {truth['unanswered_damaged_requests']}")
    summary = events[-1] if events and events[-1]["type"] == "summary" else {}
    if summary.get("unanswered_at_end") != len(truth["unanswered_at_end"]):
        bad.add(f"unanswered at end: audit {summary.get('unanswered_at_end')}, "
                f"truth {len(truth['unanswered_at_end'])}")
    compare_polls(summary, [e for e in truth["events"] if e["type"] == "frame"], timed, bad)
    compare_stations(summary, truth, bad)
    compare_masters(summary, truth, bad)
    compare_conflicts(summary, truth, bad)
    compare_example_lists(pvtap, capture, bad)
    for key in SUMMARY_KEYS:
        if summary.get(key) != truth["summary"][key]:
            bad.add(f"summary {key}: audit {summary.get(key)}, truth {truth['summary'][key]}")
    return bad.report(capture)


if __name__ == "__main__":
    sys.exit(main())
