#!/usr/bin/env python3
"""pvtap's inference of unmapped registers scored against the simulator's truth: a meter of
float32 values in each word order and a battery of u16, s16, u32, s32, flags, fill and text,
none of them in a map. Every register the truth lays out must be inferred with its type, width
and word order (a counter as a counter), in at least 90 % of them, and every float's word order
right. The draft maps --draft-map writes load back with --map and name those values.

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


def kind_name(t):
    """The truth's kind of a value, as the scoring table lists it."""
    name = t["type"]
    if t["words"] == 2:
        name += " " + t["word_order"].replace("_", " ")
    return name + (" counter" if t.get("counter") else "")


def check_draft_maps(pvtap, capture, work, got, failures):
    """--draft-map DIR writes station-N.toml, which --map loads back: every inferred value is
    then a named value of the summary, floats read as inferred. A folder that cannot be written
    is one pvtap: line per file, and the audit goes on."""
    folder = os.path.join(work, "drafts")
    if os.path.isdir(folder):
        for name in os.listdir(folder):
            os.remove(os.path.join(folder, name))
    run([pvtap, "audit", "--summary-only", "--draft-map", folder, capture])
    names = sorted(os.listdir(folder)) if os.path.isdir(folder) else []
    if names != ["station-11.toml", "station-5.toml"]:
        failures.append("draft maps written: %s" % names)
        return
    args = [pvtap, "audit", "--summary-only", "--format", "jsonl"]
    for name in names:
        station = name[len("station-"):-len(".toml")]
        args += ["--map", "%s=%s" % (station, os.path.join(folder, name))]
    summary = json.loads(run(args + [capture]).splitlines()[-1])
    # A map does not tell holding and input registers apart: an address both read is left out.
    tables = {}
    for (station, function, register) in got:
        tables[(station, register)] = tables.get((station, register), 0) + 1
    for (station, function, register), v in got.items():
        if v["type"] == "unused" or tables[(station, register)] > 1:
            continue
        values = {x["register"]: x for x in summary["stations"][str(station)]["values"]}
        named = values.get(v["register"])
        if named is None or named["name"] is None or v["type"] not in named["name"]:
            failures.append("draft map of station %d: %s is %s, not the inferred %s"
                            % (station, v["register"], named, v["type"]))
        elif v["type"] == "float32" and abs(named["value"] - v["last"]) > 1e-3 * abs(v["last"]):
            failures.append("draft map of station %d: %s reads %s, inferred %s last"
                            % (station, v["register"], named["value"], v["last"]))
        if "inferred" in summary["stations"][str(station)]:
            failures.append("station %d still has unmapped blocks with its draft map" % station)
    blocker = os.path.join(work, "not-a-folder")
    open(blocker, "w").close()
    result = subprocess.run([pvtap, "audit", "--summary-only", "--draft-map",
                             os.path.join(blocker, "drafts"), capture],
                            capture_output=True, text=True, timeout=120)
    lines = result.stderr.splitlines()
    if result.returncode != 0 or len(lines) != 2 or \
            not all(l.startswith("pvtap: cannot write the draft map ") for l in lines) or \
            "unmapped registers" not in result.stdout:
        failures.append("an unwritable --draft-map folder: exit %d, stderr %r"
                        % (result.returncode, result.stderr))


def main():
    sim, pvtap, work = sys.argv[1:4]
    os.makedirs(work, exist_ok=True)
    failures, scored, right = [], 0, 0
    kinds = {}  # the truth's kind: [right, wrong, not inferred]
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
                tally = kinds.setdefault(kind_name(t), [0, 0, 0])
                tally[0 if matches(t, v) else 2 if v is None else 1] += 1
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
        if order == "low_first":
            check_draft_maps(pvtap, capture, work, got, failures)
    share = right / scored if scored else 0.0
    print("%d of %d registers inferred right (%.0f %%)" % (right, scored, 100 * share))
    print("  %-22s %5s %5s %12s" % ("kind", "right", "wrong", "not inferred"))
    for name, (r, w, n) in sorted(kinds.items()):
        print("  %-22s %5d %5d %12d" % (name, r, w, n))
    for f in failures:
        print("  " + f)
    bad_order = [f for f in failures if "never allowed" in f]
    other = [f for f in failures if "draft map" in f]
    if scored < 50 or share < 0.9 or bad_order or other:
        print("FAIL")
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
