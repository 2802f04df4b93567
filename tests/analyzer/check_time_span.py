#!/usr/bin/env python3
"""The report's time span runs from the first byte of bus traffic to the last: no frame of the
capture starts before the span's first instant or after its last (issue 38, item 7), on
every sample capture.

Usage: check_time_span.py PVTAP SAMPLES_DIR
"""
import datetime
import glob
import json
import os
import re
import subprocess
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "support"))
from checks import Checks  # noqa: E402

RUN_GUARD_S = 120
SPAN = re.compile(r"^time: (\S+ \S+) \.\. (\S+ \S+) UTC", re.M)


def epoch(text):
    when = datetime.datetime.strptime(text, "%Y-%m-%d %H:%M:%S.%f")
    return when.replace(tzinfo=datetime.timezone.utc).timestamp()


def main():
    pvtap, samples = sys.argv[1], sys.argv[2]
    checks = Checks()
    captures = sorted(glob.glob(os.path.join(samples, "*.pcap")))
    checks.true("sample captures found", len(captures) > 10)
    for capture in captures:
        name = os.path.basename(capture)
        text = subprocess.run([pvtap, "audit", "--summary-only", capture], capture_output=True,
                              text=True, timeout=RUN_GUARD_S).stdout
        lines = subprocess.run([pvtap, "audit", "--format", "jsonl", capture],
                               capture_output=True, text=True, timeout=RUN_GUARD_S).stdout
        span = SPAN.search(text)
        checks.true(f"{name}: the report gives its time span", span is not None)
        starts = [json.loads(l)["ts"] for l in lines.splitlines()
                  if l.strip() and json.loads(l)["type"] == "frame"]
        if span is None or not starts:
            continue
        first, last = epoch(span.group(1)), epoch(span.group(2))
        # The span is printed to the microsecond.
        checks.true(f"{name}: the span begins at or before the first frame "
                    f"({span.group(1)} vs {min(starts):.6f})", first <= min(starts) + 1e-6)
        checks.true(f"{name}: the span ends at or after the last frame's start",
                    last + 1e-6 >= max(starts))
    return checks.finish()


if __name__ == "__main__":
    sys.exit(main())
