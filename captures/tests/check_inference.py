#!/usr/bin/env python3
"""pvtap's inference of unmapped registers scored against the simulator's truth: a meter of
float32 values in each word order and a battery of u16, s16, u32, s32, flags, fill and text,
none of them in a map. Every register the truth lays out must be inferred with its type, width
and word order (a counter as a counter), in at least 90 % of them, and every float's word order
right.

    check_inference.py PVTAP_SIM PVTAP WORK_DIR
"""
import json
import os
import subprocess
import sys


def run(args):
    result = subprocess.run(args, capture_output=True, text=True, timeout=120)
    if result.returncode not in (0, 1):
        sys.exit("FAIL: %s exited %d: %s" % (" ".join(args), result.returncode, result.stderr))
    return result.stdout


def inferred(pvtap, capture):
    """{(station, function, register): inferred value} from the audit's jsonl summary."""
    summary = json.loads(run([pvtap, "audit", "--summary-only", "--format", "jsonl",
                              capture]).splitlines()[-1])
    out = {}
    for station, s in summary["stations"].items():
        for block in s.get("inferred", []):
            for v in block["values"]:
                out[(int(station), block["function"], int(v["register"], 16))] = v
    return out


def matches(truth, got):
    if got is None or got["type"] != truth["type"] or got["words"] != truth["words"]:
        return False
    if truth["words"] == 2 and got["word_order"] != truth["word_order"]:
        return False
    return got["counter"] == truth.get("counter", False)


def main():
    sim, pvtap, work = sys.argv[1:4]
    os.makedirs(work, exist_ok=True)
    failures, scored, right = [], 0, 0
    for order in ("high_first", "low_first"):
        capture = os.path.join(work, "unmapped-%s.pcap" % order)
        truth_path = os.path.join(work, "unmapped-%s.truth.json" % order)
        run([sim, "--inverters", "0", "--meter", "11", "--meter-word-order", order,
             "--battery", "5", "--duration", "600", "--seed", "36", "--pdu", capture,
             "--truth", truth_path])
        with open(truth_path, encoding="utf-8") as f:
            truth = json.load(f)
        got = inferred(pvtap, capture)
        for device in truth["devices"]:
            for t in device.get("layout", []):
                v = got.get((device["station"], t["function"], t["register"]))
                scored += 1
                if matches(t, v):
                    right += 1
                    continue
                failures.append("%s meter: station %d %s (0x%04X, fc %d) is %s%s, inferred %s"
                                % (order, device["station"], t["key"], t["register"],
                                   t["function"], t["type"],
                                   " " + t.get("word_order", "") if t["words"] == 2 else "",
                                   None if v is None else "%s %s (%s)" % (
                                       v["type"], v["word_order"], v["evidence"])))
                if t["type"] == "float32" and v is not None and v["type"] == "float32":
                    failures[-1] += " [a float's word order is never allowed wrong]"
    share = right / scored if scored else 0.0
    print("%d of %d registers inferred right (%.0f %%)" % (right, scored, 100 * share))
    for f in failures:
        print("  " + f)
    bad_order = [f for f in failures if "never allowed" in f]
    if scored < 50 or share < 0.9 or bad_order:
        print("FAIL")
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
