#!/usr/bin/env python3
"""Runs `pvtap audit --format jsonl` on one sample capture and compares what it finds with
the simulator's ground truth: frames (bytes, roles, check verdicts), timeouts, noise, register
values and the summary's totals. Timestamps and latencies are compared only on the link type
252 carrier, whose records keep the bus timing; the other carriers re-time the bytes.

usage: check_sample_audit.py PVTAP CAPTURE TRUTH
"""
import json
import subprocess
import sys

SUMMARY_KEYS = ("bytes", "frames", "requests", "responses", "bad_checks", "timeouts",
                "noise_bytes", "exceptions")


def audit(pvtap, capture):
    run = subprocess.run([pvtap, "audit", "--format", "jsonl", capture],
                         capture_output=True, text=True, check=False)
    if run.returncode != 0:
        sys.exit(f"pvtap audit exited {run.returncode}: {run.stderr.strip()}")
    return [json.loads(line) for line in run.stdout.splitlines() if line.strip()]


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
        if timed and not same_number(f["ts"], t["ts"]):
            bad.add(f"frame {i}: ts {f['ts']} != {t['ts']}")
        if timed and "latency_ms" in f and not abs(f["latency_ms"] - t["latency_ms"]) < 0.002:
            bad.add(f"frame {i}: latency {f['latency_ms']} != {t['latency_ms']}")
        compare_values(i, f, t, bad)


def compare_values(i, found, truth, bad):
    if truth["role"] != "response" or truth["check"] != "ok":
        return
    if truth.get("fault") == "duplicate":
        return  # answers no request, so its words have no known start address
    values = {v["register"]: v.get("value") for v in found.get("values", [])}
    for v in truth.get("values", []):
        if "value" not in v:
            continue  # bits, enums, text: their raw words are checked with the frame bytes
        got = values.get(v["register"])
        if not isinstance(got, (int, float)) or not same_number(got, v["value"]):
            bad.add(f"frame {i}: register {v['register']} ({v['key']}) = {got}, "
                    f"truth {v['value']}")


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
    timeouts = [(e["station"], e["function"]) for e in events if e["type"] == "timeout"]
    if timeouts != [(t["station"], t["function"]) for t in truth["timeouts"]]:
        bad.add(f"timeouts: audit {timeouts}, truth {truth['timeouts']}")
    summary = events[-1] if events and events[-1]["type"] == "summary" else {}
    if summary.get("unanswered_at_end") != len(truth["unanswered_at_end"]):
        bad.add(f"unanswered at end: audit {summary.get('unanswered_at_end')}, "
                f"truth {len(truth['unanswered_at_end'])}")
    for key in SUMMARY_KEYS:
        if summary.get(key) != truth["summary"][key]:
            bad.add(f"summary {key}: audit {summary.get(key)}, truth {truth['summary'][key]}")
    return bad.report(capture)


if __name__ == "__main__":
    sys.exit(main())
