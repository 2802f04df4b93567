#!/usr/bin/env python3
"""End-to-end checks of `pvtap audit` on generated captures (see tests/analyzer/forge/).

Each mode runs the built pvtap and compares its output with what the capture generator knows
the capture holds. Usage: check_audit.py --pvtap PVTAP --dir CAPTURE_DIR MODE [NAME] [options]
Exit status 0 when every check holds, 1 with the failures listed, 77 when a needed tool is
missing (CTest reports the test as skipped).
"""

import argparse
import csv
import io
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "support"))
from checks import Checks  # noqa: E402

# The longest one program this test runs may take: a guard, not a timing check. On expiry
# subprocess raises TimeoutExpired, which names the command that was waited for.
RUN_GUARD_S = 120

SKIP = 77
SUMMARY_COUNTS = ("bytes", "frames", "requests", "responses", "bad_checks", "timeouts",
                  "noise_bytes", "exceptions", "lost_bytes", "gaps", "unsolicited",
                  "unanswered_after_loss")


def run(pvtap, args, expect_status=None, checks=None):
    result = subprocess.run([pvtap, "audit", *args], capture_output=True, text=True, timeout=110)
    if checks is not None and expect_status is not None:
        checks.equal(f"exit status of pvtap audit {' '.join(args)}", result.returncode,
                     expect_status)
        checks.true(f"no crash report for {args}", "Sanitizer" not in result.stderr)
    return result


def parse_jsonl(text, checks):
    lines = []
    for number, line in enumerate(text.splitlines(), 1):
        try:
            lines.append(json.loads(line))
        except json.JSONDecodeError as error:
            checks.failures.append(f"line {number} is not JSON ({error}): {line[:120]}")
    return lines


def capture_path(directory, name):
    stem = name.split(".")[0]
    for extension in (".pcap", ".pcapng", ".bin"):
        path = os.path.join(directory, stem + extension)
        if os.path.exists(path):
            return path
    raise SystemExit(f"no capture for {name} in {directory}")


def load_expectation(directory, name):
    with open(os.path.join(directory, name + ".expect.json"), encoding="utf-8") as f:
        expected = json.load(f)
    expected["args"] = [a.replace("{dir}", directory) for a in expected["args"]]
    return expected


def input_args(directory, name, expected):
    """The capture as pvtap's arguments: a FILE, or --raw FILE for plain dumps."""
    args = list(expected["args"])
    path = capture_path(directory, name)
    if "--raw" in args:
        args.remove("--raw")
        return args + ["--raw", path]
    return args + [path]


def check_invariants(lines, checks):
    """Every byte read is in a frame or reported as noise; the lines add up to the summary."""
    summary = lines[-1]
    frames = [l for l in lines if l["type"] == "frame"]
    noise = [l for l in lines if l["type"] == "noise"]
    gaps = [l for l in lines if l["type"] == "gap"]
    timeouts = [l for l in lines if l["type"] == "timeout"]
    checks.equal("byte invariant: bytes = frame bytes + noise bytes", summary["bytes"],
                 summary["frame_bytes"] + summary["noise_bytes"])
    checks.equal("frame lines add up to frame_bytes", sum(f["length"] for f in frames),
                 summary["frame_bytes"])
    checks.equal("noise lines add up to noise_bytes", sum(n["bytes"] for n in noise),
                 summary["noise_bytes"])
    checks.equal("gap lines add up to lost_bytes",
                 sum(g["bytes"] for g in gaps if g["bytes"] is not None), summary["lost_bytes"])
    checks.equal("gap lines", len(gaps), summary["gaps"])
    checks.equal("frame lines", len(frames), summary["frames"])
    checks.equal("timeout lines", len(timeouts), summary["timeouts"])
    checks.equal("bad frame lines", sum(1 for f in frames if f["check"] == "bad"),
                 summary["bad_checks"])
    for f in frames:
        checks.equal("frame length is its raw length", f["length"], len(f["raw"]) // 2)
        checks.true(f"bad frame {f['raw']} says what it should have been",
                    (f["check"] == "bad") == ("check_expected" in f))
        checks.true(f"frame {f['raw']} has values and issues lists",
                    isinstance(f["values"], list) and isinstance(f["issues"], list))


def check_values(summary, expected, checks):
    for v in expected["values"]:
        station = summary["stations"].get(v["station"])
        if station is None:
            checks.failures.append(f"station {v['station']} missing from the summary")
            continue
        found = [x for x in station["values"] if x["register"] == v["register"]]
        if not found:
            checks.failures.append(f"station {v['station']} has no value for {v['register']}")
            continue
        checks.true(f"station {v['station']} register {v['register']}: got {found[0]['value']},"
                    f" expected {v['value']}", abs(found[0]["value"] - v["value"]) < 1e-6)


def audit_jsonl(options, args, checks, status=0):
    result = run(options.pvtap, ["--format", "jsonl", *args], status, checks)
    lines = parse_jsonl(result.stdout, checks)
    if not lines or lines[-1].get("type") != "summary":
        checks.failures.append("the last jsonl line is not the summary")
        return None
    return lines


def mode_expect(options, checks):
    expected = load_expectation(options.dir, options.name)
    args = input_args(options.dir, options.name, expected)
    lines = audit_jsonl(options, args, checks)
    if lines is None:
        return
    summary = lines[-1]
    for key, value in expected["counts"].items():
        checks.equal(f"summary {key}", summary.get(key), value)
    frames = [[l["raw"], l["role"], l["check"]] for l in lines if l["type"] == "frame"]
    if expected["ordered"]:
        checks.equal("frames (raw, role, check) in order", frames, expected["frames"])
    else:
        checks.equal("frames (raw, role, check)", sorted(frames), sorted(expected["frames"]))
    check_invariants(lines, checks)
    check_values(summary, expected, checks)
    text = run(options.pvtap, ["--summary-only", *args], 0, checks)
    checks.true("text report is printed", "== pvtap audit report ==" in text.stdout)


def mode_roundtrip(options, checks):
    expected = load_expectation(options.dir, options.name)
    args = input_args(options.dir, options.name, expected)
    with tempfile.TemporaryDirectory() as tmp:
        written = os.path.join(tmp, "frames.pcap")
        first = audit_jsonl(options, ["--write", written, *args], checks)
        again = audit_jsonl(options, [written], checks)
        if first is None or again is None:
            return
        before = [[l["raw"], l["role"], l["check"]] for l in first if l["type"] == "frame"]
        after = [[l["raw"], l["role"], l["check"]] for l in again if l["type"] == "frame"]
        checks.equal("frames read back from the written capture", after, before)
        checks.equal("noise read back", again[-1]["noise_bytes"], first[-1]["noise_bytes"])
        checks.equal("bytes read back", again[-1]["bytes"], first[-1]["bytes"])
        # The written file holds the capture data lost too: a request whose reply was in it
        # reads back as unanswered after the loss, not as a timeout.
        for key in ("timeouts", "unanswered_after_loss", "gaps", "lost_bytes"):
            checks.equal(f"{key} read back", again[-1][key], first[-1][key])
        checks.equal("bad checks read back", again[-1]["bad_checks"], first[-1]["bad_checks"])


def mode_fail_on(options, checks):
    findings = capture_path(options.dir, "user0")
    clean = capture_path(options.dir, "eth_clean")
    run(options.pvtap, ["--summary-only", findings], 0, checks)
    run(options.pvtap, ["--summary-only", "--fail-on", "errors", findings], 1, checks)
    run(options.pvtap, ["--format", "jsonl", "--fail-on", "errors", findings], 1, checks)
    run(options.pvtap, ["--summary-only", "--fail-on", "errors", clean], 0, checks)


def expect_one_line_error(options, args, phrases, checks, stdout_empty=True):
    result = run(options.pvtap, args, 2, checks)
    lines = result.stderr.strip().splitlines()
    checks.equal(f"stderr lines for {args}", len(lines), 1)
    for phrase in phrases:
        checks.true(f"error for {args} mentions {phrase!r}: {result.stderr.strip()}",
                    phrase in result.stderr)
    if stdout_empty:
        checks.equal(f"stdout for {args}", result.stdout, "")
    return result


def mode_bad_inputs(options, checks):
    d = options.dir
    expect_one_line_error(options, [os.path.join(d, "missing.pcap")],
                          ["missing.pcap", "No such file"], checks)
    expect_one_line_error(options, [os.path.join(d, "not_a_capture.txt")],
                          ["not a pcap or pcapng capture"], checks)
    expect_one_line_error(options, [os.path.join(d, "empty.pcap")], ["empty"], checks)
    expect_one_line_error(options, [os.path.join(d, "unsupported.pcap")],
                          ["unsupported link type", "IEEE802_11", "supported:", "USER0"], checks)
    expect_one_line_error(options, [d], ["is a directory"], checks)
    expect_one_line_error(options, ["--raw", os.path.join(d, "missing.bin")],
                          ["No such file"], checks)
    expect_one_line_error(options, ["--write", "/nonexistent-dir/out.pcap",
                                    capture_path(d, "user0")], ["cannot write"], checks)
    # A missing file after a good one: the good one is reported, the missing one named.
    result = expect_one_line_error(options, [capture_path(d, "user0"),
                                             os.path.join(d, "missing.pcap")],
                                   ["missing.pcap", "No such file", "not read"], checks,
                                   stdout_empty=False)
    checks.true("the good file beside a missing one is reported",
                "input: " + capture_path(d, "user0") in result.stdout)
    result = run(options.pvtap, ["--map", os.path.join(d, "bad_map.toml"),
                                 capture_path(d, "user0")], 2, checks)
    checks.true("a bad map names the file and line", "bad_map.toml:" in result.stderr)
    # Truncated: results up to the cut are printed, then one error line, exit 2.
    full = audit_jsonl(options, [capture_path(d, "user0")], checks)
    result = expect_one_line_error(options, ["--format", "jsonl",
                                             os.path.join(d, "truncated.pcap")],
                                   ["truncated", "records"], checks, stdout_empty=False)
    partial = parse_jsonl(result.stdout, checks)
    if full and partial:
        checks.equal("truncated capture still ends with a summary", partial[-1]["type"],
                     "summary")
        checks.true("truncated capture gives part of the frames",
                    0 < partial[-1]["frames"] < full[-1]["frames"])
        check_invariants(partial, checks)


def mode_usage(options, checks):
    capture = capture_path(options.dir, "user0")
    for args in (["--format", "xml", capture], ["--fail-on", "warnings", capture],
                 ["--baud", "0", capture], ["--no-such-option", capture], [],
                 ["--raw", capture, capture], ["--port", "http", capture]):
        run(options.pvtap, args, 2, checks)
    top = subprocess.run([options.pvtap], capture_output=True, text=True, timeout=RUN_GUARD_S)
    checks.equal("pvtap without a subcommand", top.returncode, 2)
    helped = run(options.pvtap, ["--help"], 0, checks)
    for phrase in ("--format", "--fail-on", "Exit status", "USER0", "--raw"):
        checks.true(f"--help explains {phrase}", phrase in helped.stdout)


def gsl_map(name):
    """A GSL map that renames register 1050 (grid line voltage AB in the built-in map)."""
    return ('dialect = "gsl"\nmode = "extend"\n\n[[register]]\naddress = 1050\n'
            'key = "line_ab"\nname = "%s"\nscale = 0.1\nunit = "V"\n' % name)


def register_names(options, args, env, checks):
    result = subprocess.run([options.pvtap, "audit", "--format", "jsonl", *args],
                            capture_output=True, text=True, timeout=110, env=env)
    checks.equal(f"exit status with {args} ({result.stderr.strip()[:200]})", result.returncode, 0)
    return {value["name"] for line in parse_jsonl(result.stdout, checks)
            for value in line.get("values", [])}


def mode_user_maps(options, checks):
    """~/.config/pvtap/maps/*.toml (or $XDG_CONFIG_HOME/pvtap/maps) before --map files."""
    capture = capture_path(options.dir, "user0")
    home = tempfile.mkdtemp(prefix="pvtap-user-maps-")
    try:
        folder = os.path.join(home, ".config", "pvtap", "maps")
        os.makedirs(folder)
        with open(os.path.join(folder, "site.toml"), "w") as f:
            f.write(gsl_map("site line AB"))
        env = {k: v for k, v in os.environ.items() if k != "XDG_CONFIG_HOME"}
        env["HOME"] = home
        names = register_names(options, [capture], env, checks)
        checks.true("the user's map renames register 1050", "site line AB" in names)
        checks.true("the built-in name is gone", "grid line voltage AB" not in names)
        override = os.path.join(home, "override.toml")
        with open(override, "w") as f:
            f.write(gsl_map("override line AB"))
        names = register_names(options, ["--map", override, capture], env, checks)
        checks.true("a --map file is laid over the user's map", "override line AB" in names)
        xdg = dict(env, XDG_CONFIG_HOME=os.path.join(home, "xdg"))
        names = register_names(options, [capture], xdg, checks)
        checks.true("XDG_CONFIG_HOME replaces ~/.config", "grid line voltage AB" in names)
        with open(os.path.join(folder, "zz-broken.toml"), "w") as f:
            f.write('dialect = "gsl"\n[[register]]\naddress = 1050\nscael = 0.1\n')
        result = subprocess.run([options.pvtap, "audit", capture], capture_output=True,
                                text=True, timeout=110, env=env)
        checks.equal("a bad user map is a usage error", result.returncode, 2)
        checks.true("the error names the user's map", "zz-broken.toml" in result.stderr)
    finally:
        shutil.rmtree(home, ignore_errors=True)


def station_values(options, args, station, checks, full=False):
    """{register: (name, value)} of one station in the summary of an audit (full: the whole
    value objects)."""
    lines = audit_jsonl(options, args, checks)
    if not lines:
        return {}
    values = lines[-1]["stations"].get(station, {}).get("values", [])
    return {v["register"]: v if full else (v["name"], v["value"]) for v in values}


def mode_station_maps(options, checks):
    """--map STATION=FILE: the example SDM630 map given to the meter (station 10) beside a GSL
    inverter; several stations with one map; usage errors in audit and sniff."""
    d = options.dir
    capture = capture_path(d, "station_map")
    meter = f"10={options.example_map}"
    plain = station_values(options, [capture], "10", checks, full=True)
    checks.true("without a map the meter's words are values of the summary", len(plain) > 0)
    checks.equal("without a map the summary names no value of the meter",
                 [v for v in plain.values() if v["name"] is not None], [])
    # The meter's floats are input registers: raw words of function 0x04, keyed as a draft map
    # would name them.
    checks.equal("unmapped words are input registers read by 0x04",
                 {(v["function"], v["table"]) for v in plain.values()}, {(4, "input")})
    checks.equal("unmapped keys name table and address",
                 [v for v in plain.values()
                  if v["key"] != "input_reg_0x%s" % v["register"][2:].lower()], [])
    named = station_values(options, ["--map", meter, capture], "10", checks)
    checks.equal("phase 1 voltage from the example map", named.get("0x0000"),
                 ("phase 1 line to neutral voltage", 230.1))
    checks.equal("phase 3 voltage", named.get("0x0004"), ("phase 3 line to neutral voltage", 229.8))
    checks.equal("frequency", named.get("0x0046"), ("supply frequency", 49.98))
    inverter = station_values(options, ["--map", meter, capture], "1", checks)
    checks.equal("the inverter keeps the GSL map", inverter.get("1050", (None,))[0],
                 "grid line voltage AB")
    # One map for two stations: the inverter now speaks the map's dialect and its words are
    # read by the meter's map, where 1050 (0x041A) has no name.
    frames = [f for f in audit_jsonl(options, ["--map", f"1,10={options.example_map}", capture],
                                     checks) if f.get("type") == "frame" and f["station"] == 1]
    checks.true("station 1 has frames", len(frames) == 2)
    checks.true(f"a station list gives the map to each: {frames}",
                all(f["dialect"] == "modbus" for f in frames) and
                any(v["register"] == "0x041A" and v["name"] is None
                    for f in frames for v in f["values"]))
    errors = {"0=m.toml": "0 is the broadcast address", "248=m.toml": "station 248 is outside",
              "x=m.toml": "'x' is not a station address", "10,=m.toml": "'' is not a station",
              "10=": "no map FILE", f"10={d}/missing.toml": "cannot open the file",
              f"10={d}/bad_map.toml": "bad_map.toml:2:1:",
              f"10={d}/site_map.toml": "must be a gsl or modbus map, not hybrid"}
    for value, phrase in errors.items():
        result = run(options.pvtap, ["--map", value, capture], 2, checks)
        checks.true(f"--map {value} says {phrase!r}: {result.stderr.strip()}",
                    phrase in result.stderr)
        checks.equal(f"nothing printed for --map {value}", result.stdout, "")
    sniff = subprocess.run([options.pvtap, "sniff", "--device", "/dev/null", "--map", "0=m.toml"],
                           capture_output=True, text=True, timeout=RUN_GUARD_S)
    checks.equal("sniff: exit status for a bad station", sniff.returncode, 2)
    checks.true(f"sniff names the bad station: {sniff.stderr.strip()}",
                "station 0 is outside" in sniff.stderr)
    for command in ("audit", "sniff"):
        helped = subprocess.run([options.pvtap, command, "--help"], capture_output=True, text=True,
                                timeout=RUN_GUARD_S)
        checks.true(f"{command} --help explains STATION=FILE", "STATION=FILE" in helped.stdout)


PLUGIN_LINE = re.compile(r"Wireshark plugin for Wireshark (\d+\.\d+): (?:(installed|installed for "
                         r"this user|built, not installed), (/\S+/pvtap\.so)|(not built) \(.+\))")


def version_in(pvtap, hidden, home):
    """pvtap --version with the plugin files in `hidden` covered by /dev/null (a mount
    namespace of its own, so no other test's tshark sees it) and HOME at `home`."""
    binds = "".join('mount --bind /dev/null "%s" || exit 77; ' % path for path in hidden)
    command = ["sh", "-c", binds + '"$0" --version', pvtap]
    run = lambda propagation: subprocess.run(
        ["unshare", "--mount"] + propagation + command, capture_output=True, text=True,
        timeout=RUN_GUARD_S, env=dict(os.environ, HOME=home))
    result = run([])
    # In a chroot whose root is no mount point (the release check's Debian roots) unshare
    # cannot make the new namespace private; those roots run in a private namespace already.
    if result.returncode != 0 and "propagation" in result.stderr:
        result = run(["--propagation", "unchanged"])
    return result


def mode_version(options, checks):
    """--version names the plugin file that exists, in the order Wireshark would load it (the
    system's, the user's, the build's), and says 'not built' when none does: each file named
    is hidden in turn until none is left."""
    result = subprocess.run([options.pvtap, "--version"], capture_output=True, text=True,
                            timeout=RUN_GUARD_S)
    checks.equal("exit status of pvtap --version", result.returncode, 0)
    lines = result.stdout.splitlines()
    checks.true(f"pvtap --version gives the version: {result.stdout!r}",
                re.fullmatch(r"pvtap \d+\.\d+\.\d+", lines[0] if lines else "") is not None)
    if len(lines) == 2 and lines[1].startswith("Wireshark plugin: not built (Wireshark's"):
        print("SKIP: configured without Wireshark's development files, no plugin to name")
        return
    if os.geteuid() != 0 or shutil.which("unshare") is None or shutil.which("mount") is None:
        print("SKIP: hiding plugin files needs root, unshare and mount")
        return
    home = tempfile.mkdtemp(prefix="pvtap-version-")
    try:
        hidden, said = [], []
        for _ in range(4):
            result = version_in(options.pvtap, hidden, home)
            line = result.stdout.splitlines()[1:2]
            match = PLUGIN_LINE.fullmatch(line[0]) if line else None
            checks.true(f"the plugin line reads as one: {result.stdout!r} {result.stderr!r}",
                        match is not None)
            if match is None:
                return
            if match.group(4):
                break
            path = match.group(3)
            checks.true(f"{path} (said {match.group(2)}) is a file", os.path.isfile(path))
            said.append(match.group(2))
            if match.group(2) == "built, not installed" and not hidden:
                # A copy in the user's personal plugin folder comes before the build's.
                personal = os.path.join(home, ".local/lib/wireshark/plugins", match.group(1),
                                        "epan", "pvtap.so")
                os.makedirs(os.path.dirname(personal))
                shutil.copyfile(path, personal)
                again = version_in(options.pvtap, hidden, home).stdout
                checks.true(f"a personal copy is named: {again!r}",
                            f"installed for this user, {personal}" in again)
                os.remove(personal)
            hidden.append(path)
        checks.true(f"with every plugin file hidden ({said}) it says 'not built'",
                    match is not None and match.group(4) == "not built")
        checks.true("the build's plugin was among those named", "built, not installed" in said)
    finally:
        shutil.rmtree(home, ignore_errors=True)


def mode_threads(options, checks):
    """--threads 2 (a second thread reads ahead, the default) prints what --threads 1 prints,
    byte for byte: on every test capture, on one of many read-ahead batches, on that capture
    cut inside a record, and on several files read as one capture."""
    work = tempfile.mkdtemp(prefix="pvtap-threads-")
    try:
        big = os.path.join(work, "big.pcap")
        generated = subprocess.run([options.gen, "bench", big, "2"], capture_output=True,
                                   text=True, timeout=110)
        checks.equal(f"generating a 2 MB capture ({generated.stderr.strip()})",
                     generated.returncode, 0)
        cut = os.path.join(work, "cut.pcap")
        with open(big, "rb") as f:
            data = f.read()
        with open(cut, "wb") as f:
            f.write(data[:len(data) * 3 // 5])  # a cut this deep falls inside a record
        # big.pcap and eth_tcp.pcap begin with the same handshake: refused as repeats, alike.
        inputs = [[big], [cut], [big, capture_path(options.dir, "eth_tcp")],
                  [big, capture_path(options.dir, "user0")]]
        inputs += [[os.path.join(options.dir, name)] for name in sorted(os.listdir(options.dir))
                   if name.endswith((".pcap", ".pcapng"))]
        for files in inputs:
            for output in (["--format", "jsonl"], ["--summary-only"]):
                one = run(options.pvtap, ["--threads", "1", *output, *files])
                two = run(options.pvtap, ["--threads", "2", *output, *files])
                what = " ".join([*output, *(os.path.basename(f) for f in files)])
                checks.equal(f"exit status, {what}", two.returncode, one.returncode)
                checks.true(f"stdout is the same, {what}", two.stdout == one.stdout)
                checks.equal(f"stderr, {what}", two.stderr, one.stderr)
                if files == [cut]:
                    checks.true(f"the cut capture is reported truncated, {what}",
                                "truncated" in one.stderr and "ends inside a record" in one.stderr
                                and one.returncode == 2)
                    checks.true(f"the cut capture still gives frames, {what}",
                                len(one.stdout) > 1000)
    finally:
        shutil.rmtree(work, ignore_errors=True)


def mode_formats(options, checks):
    expected = load_expectation(options.dir, options.name)
    args = input_args(options.dir, options.name, expected)
    lines = audit_jsonl(options, args, checks)
    if lines is None:
        return
    result = run(options.pvtap, ["--format", "csv", *args], 0, checks)
    rows = list(csv.reader(io.StringIO(result.stdout)))
    checks.equal("csv header", rows[0],
                 ["type", "ts", "bus", "dialect", "role", "station", "function", "length",
                  "check", "check_expected", "latency_ms", "raw", "values", "issues"])
    checks.true("every csv row has 14 fields", all(len(r) == 14 for r in rows))
    events = [l for l in lines if l["type"] != "summary"]
    checks.equal("csv rows (one per event)", len(rows) - 1, len(events))
    csv_frames = [r[11] for r in rows[1:] if r[0] == "frame"]
    checks.equal("csv frames", csv_frames, [l["raw"] for l in lines if l["type"] == "frame"])
    text = run(options.pvtap, args, 0, checks)
    for phrase in ("== pvtap audit report ==", "latest values", "poll period", "bus timing",
                   "BAD CRC", "TIMEOUT", "GAP", "latency"):
        checks.true(f"text output shows {phrase!r}", phrase in text.stdout)
    summary_only = run(options.pvtap, ["--format", "jsonl", "--summary-only", *args], 0, checks)
    only = parse_jsonl(summary_only.stdout, checks)
    checks.equal("--summary-only jsonl is one line", len(only), 1)
    if only:
        checks.equal("--summary-only gives the same summary", only[0], lines[-1])


NOBODY = 65534


def run_tshark(home, args):
    """tshark with the plugin in a temporary personal folder; as root (which makes tshark
    ignore personal plugins) it runs as the unprivileged user 65534."""
    command = ["env", "-i", "HOME=" + home, "PATH=/usr/sbin:/usr/bin:/sbin:/bin",
               "LC_ALL=C.UTF-8", "tshark", *args]
    if os.geteuid() == 0:
        command = ["setpriv", f"--reuid={NOBODY}", f"--regid={NOBODY}", "--clear-groups",
                   *command]
    return subprocess.run(command, capture_output=True, text=True, timeout=110)


def mode_tshark(options, checks):
    if not options.plugin or not os.path.exists(options.plugin) or shutil.which("tshark") is None:
        print("skipped: needs tshark and the built Wireshark plugin")
        return SKIP
    sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "dissector"))
    import tshark_runner  # noqa: E402  (tests/dissector: the check for a system-wide pvtap.so)
    tshark_runner.refuse_system_plugin()
    expected = load_expectation(options.dir, options.name)
    args = input_args(options.dir, options.name, expected)
    home = tempfile.mkdtemp(prefix="pvtap-audit-tshark-")
    try:
        written = os.path.join(home, "frames.pcap")
        lines = audit_jsonl(options, ["--write", written, *args], checks)
        plugins = os.path.join(home, tshark_runner.plugin_subdir())
        os.makedirs(plugins)
        shutil.copy(options.plugin, os.path.join(plugins, "pvtap.so"))
        if os.geteuid() == 0:
            for root, dirs, files in os.walk(home):
                for name in [root] + [os.path.join(root, n) for n in dirs + files]:
                    os.chown(name, NOBODY, NOBODY)
        plugins = run_tshark(home, ["-G", "plugins"])
        checks.true("tshark loads pvtap.so", "pvtap.so" in plugins.stdout)
        result = run_tshark(home, ["-r", written, "-T", "fields", "-e", "frame.number",
                                   "-Y", "invrtu.role || invascii.role"])
        checks.equal(f"tshark exit status ({result.stderr.strip()[:200]})", result.returncode, 0)
        if lines is not None:
            checks.equal("frames tshark shows with the plugin", len(result.stdout.splitlines()),
                         lines[-1]["frames"])
    finally:
        shutil.rmtree(home, ignore_errors=True)
    return None


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--pvtap", required=True)
    parser.add_argument("--dir", required=True)
    parser.add_argument("--plugin", default="")
    parser.add_argument("--gen", default="", help="pvtap-capture-gen, for mode threads")
    parser.add_argument("--example-map", default="", help="a map of examples/maps, for mode "
                        "station-maps")
    parser.add_argument("mode")
    parser.add_argument("name", nargs="?")
    options = parser.parse_args()
    checks = Checks()
    modes = {"expect": mode_expect, "roundtrip": mode_roundtrip, "fail-on": mode_fail_on,
             "bad-inputs": mode_bad_inputs, "usage": mode_usage, "formats": mode_formats,
             "tshark": mode_tshark, "user-maps": mode_user_maps, "version": mode_version, "threads": mode_threads,
             "station-maps": mode_station_maps}
    if modes[options.mode](options, checks) == SKIP:
        return SKIP
    return checks.finish()


if __name__ == "__main__":
    sys.exit(main())
