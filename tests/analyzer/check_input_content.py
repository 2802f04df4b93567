#!/usr/bin/env python3
"""Inputs are told by their content, not their name (issue 38, item 5): a sigrok session
named otherwise is read as a session, a pcap named .sr as a capture, and a file that is
neither says what its first bytes look like, in one line, exit 2.

Usage: check_input_content.py PVTAP SAMPLES_DIR WORK_DIR
"""
import json
import os
import shutil
import subprocess
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "support"))
from checks import Checks  # noqa: E402

RUN_GUARD_S = 120


def audit(pvtap, path):
    return subprocess.run([pvtap, "audit", "--summary-only", "--format", "jsonl", path],
                          capture_output=True, text=True, timeout=RUN_GUARD_S)


def frames(result):
    lines = [l for l in result.stdout.splitlines() if l.strip()]
    return json.loads(lines[-1])["frames"] if lines else None


def main():
    pvtap, samples, work = sys.argv[1:4]
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    checks = Checks()
    for original, renamed in (("logic-bus.sr", "logic-bus.bin"),
                              ("demo.user0.pcap", "demo.sr"), ("demo.pdu.pcap", "demo.vcd")):
        copy = os.path.join(work, renamed)
        shutil.copy(os.path.join(samples, original), copy)
        expected = frames(audit(pvtap, os.path.join(samples, original)))
        result = audit(pvtap, copy)
        checks.equal(f"{original} named {renamed}: exit status", result.returncode, 0)
        checks.equal(f"{original} named {renamed}: frames", frames(result), expected)
        checks.true(f"{original} has frames", bool(expected))
    page = os.path.join(work, "page.pcap")
    with open(page, "w") as f:
        f.write("<html>not a capture</html>\n")
    result = subprocess.run([pvtap, "audit", page], capture_output=True, text=True,
                            timeout=RUN_GUARD_S)
    checks.equal("a text file named .pcap: exit status", result.returncode, 2)
    lines = result.stderr.strip().splitlines()
    checks.true(f"a text file named .pcap: one line with its first bytes ({lines})",
                len(lines) == 1 and "3c 68 74 6d 6c" in lines[0] and "<html>" in lines[0])
    return checks.finish()


if __name__ == "__main__":
    sys.exit(main())
