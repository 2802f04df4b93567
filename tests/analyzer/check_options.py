#!/usr/bin/env python3
"""Options say when they cannot do anything: an option that needs another is refused, a value
out of range names the range, and every parse error is one line that starts with `pvtap:`.
One baud range for audit and sniff: 1200 (which `sniff --baud auto` tries) to 115200.

Usage: check_options.py PVTAP CAPTURE
"""
import subprocess
import sys
import os

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "support"))
from checks import Checks  # noqa: E402

RUN_GUARD_S = 60


def run(pvtap, args):
    return subprocess.run([pvtap, *args], capture_output=True, text=True, timeout=RUN_GUARD_S)


def refused(checks, pvtap, args, words):
    result = run(pvtap, args)
    lines = result.stderr.strip().splitlines()
    what = " ".join(args)
    checks.equal(f"exit status of pvtap {what}", result.returncode, 2)
    checks.true(f"pvtap {what}: one line on stderr ({result.stderr.strip()!r})", len(lines) == 1)
    checks.true(f"pvtap {what}: the line starts with 'pvtap:'",
                bool(lines) and lines[0].startswith("pvtap: "))
    for word in words:
        checks.true(f"pvtap {what}: the line names {word!r} ({result.stderr.strip()!r})",
                    word in result.stderr)
    checks.equal(f"pvtap {what}: nothing on stdout", result.stdout, "")


def main():
    pvtap, capture = sys.argv[1], sys.argv[2]
    checks = Checks()
    needs = (("--values-format", "jsonl", "--values"), ("--plot", "pv_power", "--html"),
             ("--mqtt-password-file", "pw", "--mqtt"), ("--mqtt-topic", "site", "--mqtt"),
             ("--mqtt-discovery", None, "--mqtt"))
    for command in ("audit", "sniff"):
        for option, value, needed in needs:
            args = [command, option] + ([value] if value else []) + [capture]
            refused(checks, pvtap, args, [option, needed])
        # CLI11 words the range "1 to 65535" (Debian 12) or "[1 - 65535]" (Debian 13).
        refused(checks, pvtap, [command, "--port", "99999", capture], ["--port", "range", "65535"])
        refused(checks, pvtap, [command, "--baud", "600", capture], ["--baud", "1200", "115200"])
        refused(checks, pvtap, [command, "--format", "xml", capture], ["--format", "xml"])
    for option, value in (("--parity", "even"), ("--stop-bits", "2")):
        refused(checks, pvtap, ["sniff", "--device", "/dev/null", "--baud", "auto", option, value],
                ["--baud auto", option])
    for rate in ("1200", "115200"):
        result = run(pvtap, ["audit", "--summary-only", "--baud", rate, capture])
        checks.equal(f"audit --baud {rate}: exit status", result.returncode, 0)
    refused(checks, pvtap, ["audit", "--timeout", "-1", capture], ["--timeout"])
    check_duplex(checks, pvtap, capture)
    return checks.finish()


def check_duplex(checks, pvtap, capture):
    """--duplex: two serial captures, one per pair; a pair that cannot be read is named and
    the other is read all the same."""
    refused(checks, pvtap, ["audit", "--duplex", capture], ["--duplex", "two"])
    pdu = os.path.join(os.path.dirname(capture), "demo.pdu.pcap")
    refused(checks, pvtap, ["audit", "--duplex", capture, pdu], ["--duplex", "serial", pdu])
    refused(checks, pvtap, ["audit", "--duplex", "--raw", capture], ["--duplex"])
    missing = capture + ".missing"
    result = run(pvtap, ["audit", "--summary-only", "--duplex", capture, missing])
    checks.equal("audit --duplex with a pair missing: exit status", result.returncode, 2)
    checks.true(f"audit --duplex with a pair missing names it ({result.stderr!r})",
                missing in result.stderr and "not read" in result.stderr)
    checks.true("audit --duplex with a pair missing reports the other pair",
                "frames" in result.stdout)


if __name__ == "__main__":
    sys.exit(main())
