#!/usr/bin/env python3
"""Inputs are told by their content, not their name (issue 38, item 5): a sigrok session
named otherwise is read as a session, a pcap named .sr as a capture, and a file that is
neither says what its first bytes look like, in one line, exit 2. Errors name the cause
(item 6): a record claiming 2,147,483,647 bytes is corrupt, not truncated; a file cut inside a
record ends there; an unreadable recording or map is "Permission denied" (run as an
unprivileged user, as root reads every file).

Usage: check_input_content.py PVTAP SAMPLES_DIR WORK_DIR
"""
import json
import os
import shutil
import struct
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


def one_line(checks, what, result, words):
    lines = result.stderr.strip().splitlines()
    checks.equal(f"{what}: exit status", result.returncode, 2)
    checks.true(f"{what}: one line naming {words} ({lines})",
                len(lines) == 1 and all(w in lines[0] for w in words))


def check_damage(pvtap, samples, work, checks):
    with open(os.path.join(samples, "demo.user0.pcap"), "rb") as f:
        data = f.read()
    first = 24 + 16 + struct.unpack("<I", data[32:36])[0]
    corrupt = os.path.join(work, "corrupt.pcap")
    with open(corrupt, "wb") as f:
        f.write(data[:first] + struct.pack("<IIII", 1782036000, 5, 2147483647, 2147483647) +
                b"\x01\x02")
    one_line(checks, "a record claiming 2147483647 bytes", audit(pvtap, corrupt),
             ["corrupt at byte", "2147483647"])
    cut = os.path.join(work, "cut.pcap")
    with open(cut, "wb") as f:
        f.write(data[:first + 20])
    one_line(checks, "a file cut inside a record", audit(pvtap, cut),
             ["truncated", "ends inside a record"])


def check_permissions(pvtap, samples, work, checks):
    if os.geteuid() != 0 or shutil.which("setpriv") is None:
        return  # an unprivileged run cannot make a file unreadable to itself otherwise
    os.chmod(work, 0o755)
    for name in ("locked.sr", "locked.toml"):
        path = os.path.join(work, name)
        shutil.copy(os.path.join(samples, "logic-bus.sr"), path)
        os.chmod(path, 0)
    nobody = ["setpriv", "--reuid=65534", "--regid=65534", "--clear-groups", pvtap, "audit"]
    run = lambda args: subprocess.run(nobody + args, capture_output=True, text=True,  # noqa
                                      timeout=RUN_GUARD_S)
    one_line(checks, "an unreadable recording", run([os.path.join(work, "locked.sr")]),
             ["locked.sr", "Permission denied"])
    result = run(["--map", os.path.join(work, "locked.toml"),
                  os.path.join(samples, "demo.user0.pcap")])
    one_line(checks, "an unreadable map", result, ["locked.toml", "Permission denied"])
    checks.true(f"an unreadable map is no 'bad register map' ({result.stderr.strip()})",
                "bad register map" not in result.stderr)


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
    check_damage(pvtap, samples, work, checks)
    check_permissions(pvtap, samples, work, checks)
    return checks.finish()


if __name__ == "__main__":
    sys.exit(main())
