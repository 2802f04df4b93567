#!/usr/bin/env python3
"""pvtap audit --values on a sample capture: the rows are the values the jsonl frames carry.

  check_sample_values.py PVTAP CAPTURE

The expected rows come from `pvtap audit --format jsonl`: every value of every reply with a
good check. --values (csv), --values-format jsonl and --values-format influx must give exactly
those rows, in the same order, with the same numbers; the influx lines must pass a strict
line-protocol parser (measurement pvtap, tags bus/station/dialect/key, one float field
`value`, a nanosecond timestamp that is the frame's).
"""

import csv
import io
import json
import re
import subprocess
import sys

# Line protocol as InfluxDB reads it: measurement, tags (",", "=" and " " escaped; a backslash
# keeps the character after it in the name, and only those three lose it), one space, fields,
# one space, an integer timestamp.
ESCAPED = r"(?:[^,= \\]|\\.)+"
LINE = re.compile(r"^(?P<measurement>(?:[^, \\]|\\.)+)"
                  r"(?P<tags>(?:,%s=%s)*)"
                  r" (?P<fields>%s=[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?"
                  r"(?:,%s=[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?)*)"
                  r"(?: (?P<time>-?\d{1,19}))?$" % (ESCAPED, ESCAPED, ESCAPED, ESCAPED))


def unescape(text):
    return re.sub(r"\\([,= ])", r"\1", text)


def parse_line(line):
    m = LINE.match(line)
    if not m:
        raise ValueError("not line protocol: %r" % line)
    tags = {}
    for part in re.findall(r",(%s=%s)" % (ESCAPED, ESCAPED), m.group("tags")):
        key, value = re.match(r"(%s)=(%s)$" % (ESCAPED, ESCAPED), part).groups()
        if unescape(key) in tags:
            raise ValueError("tag %s twice: %r" % (key, line))
        tags[unescape(key)] = unescape(value)
    fields = dict(f.split("=", 1) for f in m.group("fields").split(","))
    return m.group("measurement"), tags, fields, m.group("time")


def pvtap_output(args):
    result = subprocess.run(args, capture_output=True, text=True)
    if result.returncode != 0:
        sys.exit("FAIL: %s exited %d: %s" % (" ".join(args), result.returncode, result.stderr))
    return result.stdout


def expected_rows(pvtap, capture):
    rows = []
    for line in pvtap_output([pvtap, "audit", "--format", "jsonl", capture]).splitlines():
        f = json.loads(line)
        if f["type"] != "frame" or f["role"] != "response" or f["check"] != "ok":
            continue
        for v in f["values"]:
            rows.append({"ts": f["ts"], "bus": f.get("bus"), "station": f["station"],
                         "dialect": f["dialect"], "register": v["register"], "name": v["name"],
                         "value": v["value"], "unit": v.get("unit"),
                         "unmapped_key": None if v["name"] is not None else
                         unmapped_key(f["dialect"], f["function"], v["register"])})
    return rows


def unmapped_key(dialect, function, register):
    """The key of a word no map names: its table and address ("input_reg_0x0002")."""
    address = int(register, 16) if register.startswith("0x") else int(register)
    table = "input_reg" if dialect in ("gsl", "modbus") and function == 4 else "reg"
    return "%s_0x%04x" % (table, address)


def read_values(pvtap, capture, fmt, path):
    pvtap_output([pvtap, "audit", "--summary-only", "--values", path, "--values-format", fmt,
                  capture])
    with open(path, encoding="utf-8") as f:
        return f.read()


def same_value(expected, got):
    if isinstance(expected, str):
        return expected == got
    return expected is None and got in (None, "") or float(expected) == float(got)


def check_csv(rows, text, failures):
    got = list(csv.DictReader(io.StringIO(text)))
    if len(got) != len(rows):
        failures.append("csv: %d rows, the jsonl frames carry %d values" % (len(got), len(rows)))
        return
    for e, g in zip(rows, got):
        plain = [str(e["ts"]) if e["ts"] is not None else "", e["bus"] or "", str(e["station"]),
                 e["dialect"], e["register"], e["name"] or "", e["unit"] or ""]
        have = [g["ts"], g["bus"], g["station"], g["dialect"], g["register"], g["name"], g["unit"]]
        if [p.rstrip("0") for p in plain] != [h.rstrip("0") for h in have] or \
                not same_value(e["value"], g["value"]):
            failures.append("csv row %s differs from the frame's value %s" % (g, e))
            return


def check_jsonl(rows, text, failures):
    got = [json.loads(line) for line in text.splitlines()]
    if len(got) != len(rows):
        failures.append("jsonl: %d rows, the jsonl frames carry %d values" % (len(got), len(rows)))
        return
    for e, g in zip(rows, got):
        for field in ("ts", "bus", "station", "dialect", "register", "name", "value", "unit"):
            if g[field] != e[field]:
                failures.append("jsonl row %s: %s is %r, the frame says %r"
                                % (g, field, g[field], e[field]))
                return
        if g["key"] is None or (e["name"] is None and g["key"] != e["unmapped_key"]):
            failures.append("jsonl row %s: the map's key, or for a word no map names %s"
                            % (g, e["unmapped_key"]))
            return


def check_influx(rows, text, failures):
    numeric = [r for r in rows if
               isinstance(r["value"], (int, float)) and not isinstance(r["value"], bool)]
    lines = text.splitlines()
    if len(lines) != len(numeric):
        failures.append("influx: %d lines, %d numeric values with a key" % (len(lines), len(numeric)))
        return
    for e, line in zip(numeric, lines):
        try:
            measurement, tags, fields, stamp = parse_line(line)
        except ValueError as error:
            failures.append(str(error))
            return
        want_tags = {"station": str(e["station"]), "dialect": e["dialect"]}
        if e["bus"]:
            want_tags["bus"] = e["bus"]
        problems = []
        if measurement != "pvtap":
            problems.append("measurement %s" % measurement)
        if {k: tags.get(k) for k in want_tags} != want_tags or set(tags) - {"bus", "station",
                                                                              "dialect", "key"}:
            problems.append("tags %s" % tags)
        if "key" not in tags or list(fields) != ["value"] or float(fields["value"]) != e["value"] \
                or (e["unmapped_key"] is not None and tags["key"] != e["unmapped_key"]):
            problems.append("fields %s" % fields)
        if stamp is None or stamp != str(int(("%.6f" % e["ts"]).replace(".", "")) * 1000):
            problems.append("timestamp %s for ts %s" % (stamp, e["ts"]))
        if problems:
            failures.append("influx line %r: %s" % (line, "; ".join(problems)))
            return


def main():
    pvtap, capture, work = sys.argv[1], sys.argv[2], sys.argv[3]
    rows = expected_rows(pvtap, capture)
    failures = []
    if not rows:
        failures.append("the capture has no values to check")
    check_csv(rows, read_values(pvtap, capture, "csv", work + ".csv"), failures)
    check_jsonl(rows, read_values(pvtap, capture, "jsonl", work + ".jsonl"), failures)
    check_influx(rows, read_values(pvtap, capture, "influx", work + ".lp"), failures)
    for f in failures:
        print("FAIL: " + f)
    print("%s: %d values checked in csv, jsonl and influx" % (capture, len(rows)))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
