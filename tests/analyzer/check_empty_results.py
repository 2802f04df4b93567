#!/usr/bin/env python3
"""An audit that finds nothing says so (issue 38, item 3): a statistic over nothing reads
"none measured", never 0.0; an audit without a frame says why it might be and what to try
(--dialect auto, --port, the tap's line settings); --fail-on empty, and errors, exit 1 then.

Usage: check_empty_results.py PVTAP SAMPLES_DIR
"""
import os
import subprocess
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "support"))
from checks import Checks  # noqa: E402

RUN_GUARD_S = 120


def audit(pvtap, *args):
    return subprocess.run([pvtap, "audit", "--summary-only", *args], capture_output=True,
                          text=True, timeout=RUN_GUARD_S)


def main():
    pvtap, samples = sys.argv[1], sys.argv[2]
    serial = os.path.join(samples, "gsl-clean.user0.pcap")
    gateway = os.path.join(samples, "demo.gateway.pcap")
    checks = Checks()
    text = audit(pvtap, "--dialect", "ascii", serial).stdout
    checks.true("no latency: 'none measured'", "n=0  none measured" in text)
    checks.true("no latency: no mean of 0.0", "mean 0.0" not in text)
    checks.true(f"no frame: the hint names --dialect auto ({text[:600]})",
                "no frame in" in text and "--dialect auto" in text)
    text = audit(pvtap, "--port", "80", gateway).stdout
    checks.true("no bus bytes through a gateway: the hint names --port", "--port" in text and
                "flows ignored" in text)
    for fail_on, capture, extra, status in (
            ("empty", gateway, ["--port", "80"], 1), ("errors", gateway, ["--port", "80"], 1),
            (None, gateway, ["--port", "80"], 0), ("empty", serial, [], 0),
            ("empty", serial, ["--dialect", "ascii"], 1)):
        args = (["--fail-on", fail_on] if fail_on else []) + extra + [capture]
        checks.equal(f"exit status of audit {' '.join(args)}", audit(pvtap, *args).returncode,
                     status)
    text = audit(pvtap, serial).stdout
    checks.true("frames found: no hint", "no frame" not in text)
    return checks.finish()


if __name__ == "__main__":
    sys.exit(main())
