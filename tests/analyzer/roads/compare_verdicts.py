#!/usr/bin/env python3
"""Compares the verdicts of two `pvtap audit --format jsonl` (or `pvtap sniff --format jsonl`)
outputs of the same bus traffic that reached pvtap by different roads.

usage: compare_verdicts.py [options] A.jsonl B.jsonl

Exit status 0 when the verdicts are the same, 1 with one line per difference, 2 when a file
cannot be read. Compared: every frame in order (dialect, role, station, function, check, bytes,
latency to the microsecond, findings, decoded values, bus), every timeout or unanswered request (station,
function, reason), every noise run (bytes, offset in the bus's stream), every gap, and the
summary's counts (frames, bad checks, damaged replies, timeouts, noise runs and bytes,
duplicates, ...), stations with their latest values and latency p50/max. Times are compared (to the microsecond) only
with --times: a road may stamp its records otherwise and still give the same verdicts.

As a module: `differences(a_lines, b_lines, Options())` returns the lines of differences.
"""
import argparse
import dataclasses
import difflib
import json
import sys

# The summary's counts that are verdicts (not sizes of a carrier).
SUMMARY_COUNTS = ("bytes", "frames", "requests", "responses", "bad_checks", "timeouts",
                  "damaged_replies", "unanswered_damaged_requests", "noise_bytes",
                  "noise_runs", "exceptions", "frame_bytes", "lost_bytes", "gaps",
                  "malformed_frames", "unsolicited", "late_replies", "duplicates",
                  "byte_count_mismatches", "quantity_problems", "dialect_changes",
                  "gateway_timeouts", "unanswered_at_end", "unanswered_after_loss")
STATION_COUNTS = ("requests", "responses", "bad_checks", "timeouts", "damaged_replies",
                  "exceptions", "unsolicited", "duplicates", "dialect_changes")
LATENCY_FIGURES = ("count", "p50", "max")
# What --ignore can leave out.
IGNORABLE = ("bus", "latency", "issues", "offset", "gaps", "stations", "unknown_station",
             "bytes", "frame_bytes", "lost_bytes", "exception_codes", "values")


@dataclasses.dataclass
class Options:
    times: bool = False            # compare every event's time, to the microsecond
    latency_tolerance_ms: float = 0.0
    ignore: frozenset = frozenset()
    max_lines: int = 20            # differences listed per kind of event


def read_jsonl(path):
    with open(path, encoding="utf-8") as f:
        return [json.loads(line) for line in f if line.strip()]


def micros(seconds):
    return None if seconds is None else round(seconds * 1e6)


def frame_key(e, o):
    key = [e.get("bus") if "bus" not in o.ignore else None, e.get("dialect"), e.get("role"),
           e.get("station"), e.get("function"), e.get("check"), e.get("raw")]
    if "latency" not in o.ignore:
        latency = e.get("latency_ms")
        if o.latency_tolerance_ms > 0 and latency is not None:
            latency = round(latency / o.latency_tolerance_ms)
        key.append(latency)
    if "issues" not in o.ignore:
        key.append(tuple(e.get("issues", ())))
    if "values" not in o.ignore:
        key.append(values_key(e.get("values")))
    if o.times:
        key.append(micros(e.get("ts")))
    return tuple(key)


def values_key(values):
    """A frame's or a station's decoded values, as one comparable text: register, name, number
    or text, unit and marks alike, or the roads decoded the bytes differently."""
    return json.dumps(values or [], sort_keys=True)


def timeout_key(e, o):
    key = [e.get("bus") if "bus" not in o.ignore else None, e["type"], e.get("dialect"),
           e.get("station"), e.get("function"), e.get("reason")]
    if o.times:
        key += [micros(e.get("ts")), micros(e.get("request_ts"))]
    return tuple(key)


def noise_key(e, o):
    key = [e.get("bus") if "bus" not in o.ignore else None, e.get("bytes"), e.get("raw")]
    if "offset" not in o.ignore:
        key.append(e.get("offset"))
    if o.times:
        key.append(micros(e.get("ts")))
    return tuple(key)


def gap_key(e, o):
    key = [e.get("bus") if "bus" not in o.ignore else None, e.get("bytes"), e.get("direction")]
    if o.times:
        key.append(micros(e.get("ts")))
    return tuple(key)


KINDS = (("frame", ("frame",), frame_key), ("timeout", ("timeout", "unanswered"), timeout_key),
         ("noise", ("noise",), noise_key), ("gap", ("gap",), gap_key))


def show(key):
    return " ".join("-" if v is None else str(v) for v in key)


def sequence_differences(kind, a, b, o):
    """Lines saying where two sequences of event keys part, as a diff of their runs."""
    out = []
    if len(a) != len(b):
        out.append(f"{kind}s: {len(a)} in A, {len(b)} in B")
    matcher = difflib.SequenceMatcher(a=a, b=b, autojunk=False)
    listed = 0
    for tag, a0, a1, b0, b1 in matcher.get_opcodes():
        if tag == "equal":
            continue
        for i in range(a0, a1):
            if listed < o.max_lines:
                out.append(f"{kind} A#{i}: {show(a[i])}")
            listed += 1
        for j in range(b0, b1):
            if listed < o.max_lines:
                out.append(f"{kind} B#{j}: {show(b[j])}")
            listed += 1
    if listed > o.max_lines:
        out.append(f"{kind}s: {listed - o.max_lines} more differing lines")
    return out


def latency_figures(d):
    return {k: (d or {}).get(k) for k in LATENCY_FIGURES}


def compare_value(out, name, a, b):
    if a != b:
        out.append(f"{name}: A {json.dumps(a)}, B {json.dumps(b)}")


def summary_differences(a, b, o):
    out = []
    if a is None or b is None:
        if (a is None) != (b is None):
            out.append(f"summary: {'missing in A' if a is None else 'missing in B'}")
        return out
    for key in SUMMARY_COUNTS:
        if key not in o.ignore:
            compare_value(out, f"summary {key}", a.get(key), b.get(key))
    if "latency" not in o.ignore:
        compare_value(out, "summary latency_ms", latency_figures(a.get("latency_ms")),
                      latency_figures(b.get("latency_ms")))
    if "exception_codes" not in o.ignore:
        compare_value(out, "summary exception_codes", a.get("exception_codes"),
                      b.get("exception_codes"))
    if "unknown_station" not in o.ignore:
        compare_value(out, "summary unknown_station", a.get("unknown_station"),
                      b.get("unknown_station"))
    if "stations" not in o.ignore:
        out += station_differences(a.get("stations") or {}, b.get("stations") or {}, o)
    return out


def station_differences(a, b, o):
    out = []
    for name in sorted(set(a) | set(b)):
        if name not in a or name not in b:
            out.append(f"station {name}: only in {'A' if name in a else 'B'}")
            continue
        for key in STATION_COUNTS:
            compare_value(out, f"station {name} {key}", a[name].get(key), b[name].get(key))
        if "latency" not in o.ignore:
            compare_value(out, f"station {name} latency_ms",
                          latency_figures(a[name].get("latency_ms")),
                          latency_figures(b[name].get("latency_ms")))
        compare_value(out, f"station {name} device", (a[name].get("device") or {}).get("name"),
                      (b[name].get("device") or {}).get("name"))
        if "values" not in o.ignore and values_key(a[name].get("values")) != \
                values_key(b[name].get("values")):
            out.append(f"station {name} values: A {len(a[name].get('values') or [])}, "
                       f"B {len(b[name].get('values') or [])}, not the same")
    return out


def differences(a_lines, b_lines, o=None):
    o = o or Options()
    out = []
    for kind, types, key in KINDS:
        if kind == "gap" and "gaps" in o.ignore:
            continue
        a = [key(e, o) for e in a_lines if e.get("type") in types]
        b = [key(e, o) for e in b_lines if e.get("type") in types]
        out += sequence_differences(kind, a, b, o)
    summary_a = next((e for e in reversed(a_lines) if e.get("type") == "summary"), None)
    summary_b = next((e for e in reversed(b_lines) if e.get("type") == "summary"), None)
    return out + summary_differences(summary_a, summary_b, o)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("a", metavar="A.jsonl")
    parser.add_argument("b", metavar="B.jsonl")
    parser.add_argument("--times", action="store_true",
                        help="compare every event's time too, to the microsecond")
    parser.add_argument("--latency-tolerance-ms", type=float, default=0.0,
                        help="latencies equal when they round alike to this step (default: "
                             "equal to the microsecond)")
    parser.add_argument("--ignore", action="append", default=[], choices=IGNORABLE,
                        help="leave a field out of the comparison (repeatable)")
    parser.add_argument("--max-lines", type=int, default=20,
                        help="differences listed per kind of event (default 20)")
    args = parser.parse_args(argv)
    try:
        a, b = read_jsonl(args.a), read_jsonl(args.b)
    except (OSError, ValueError) as error:
        print(f"compare_verdicts: {error}", file=sys.stderr)
        return 2
    options = Options(args.times, args.latency_tolerance_ms, frozenset(args.ignore),
                      args.max_lines)
    lines = differences(a, b, options)
    for line in lines:
        print(line)
    return 1 if lines else 0


if __name__ == "__main__":
    sys.exit(main())
