#!/usr/bin/env python3
"""The simulator's SunSpec inverter, with no map given: both programs learn its model chain from
the logger's scan and decode its models' points with their scale factors. pvtap audit's newest
value of every point the truth lays out equals the truth's last; the plugin's values (one pass
and two) equal pvtap's; --draft-map records the chain, and a capture that starts after the scan
decodes the same with it (in pvtap and in the plugin's station map table) and not without it.

    check_sunspec.py PVTAP_SIM PVTAP PLUGIN WORK_DIR
"""
import json
import os
import subprocess
import sys

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")
sys.dont_write_bytecode = True
sys.path.insert(0, os.path.join(ROOT, "tests", "dissector"))
STATION = 3


def run(args):
    result = subprocess.run(args, capture_output=True, text=True, timeout=300)
    if result.returncode not in (0, 1):
        sys.exit("FAIL: %s exited %d: %s" % (" ".join(args), result.returncode, result.stderr))
    return result.stdout


def truth_last(truth):
    """{register: last value} of the points the truth's replies carried."""
    last = {}
    for event in truth["events"]:
        for v in event.get("values", []):
            last[v["register"]] = (v["key"], v["value"])
    return last


def audited(pvtap, capture, maps=()):
    args = [pvtap, "audit", "--summary-only", "--format", "jsonl"]
    for m in maps:
        args += ["--map", m]
    summary = json.loads(run(args + [capture]).splitlines()[-1])
    return {v["register"]: v for v in summary["stations"][str(STATION)]["values"]}


def plugin_last(plugin, capture, two_pass, station_map=None):
    """{key: last number} of the station map values Wireshark shows (PDML: each value's key
    and number are its children); with `station_map`, that map file given to STATION in the
    plugin's "Station register maps" table."""
    import xml.etree.ElementTree as ET
    os.environ["PVTAP_PLUGIN"] = plugin
    from tshark_runner import TsharkHome
    home = TsharkHome()
    try:
        name = os.path.basename(capture)
        with open(capture, "rb") as src, open(home.path(name), "wb") as dst:
            dst.write(src.read())
        args = (["-2"] if two_pass else []) + ["-r", home.path(name), "-T", "pdml"]
        if station_map:
            with open(station_map, encoding="utf-8") as f:
                copied = home.write_text(os.path.basename(station_map), f.read())
            args += ["-o", 'uat:pvtap_station_maps:"%d","%s"' % (STATION, copied)]
        home._hand_over()
        last = {}
        for value in ET.fromstring(home.run(args).stdout).iter("field"):
            if value.get("name") != "invrtu.map_value":
                continue
            children = {c.get("name"): c.get("show") for c in value.findall("field")}
            if "invrtu.map_number" in children:
                last[children["invrtu.map_key"]] = float(children["invrtu.map_number"])
        return last
    finally:
        home.close()


def main():
    sim, pvtap, plugin, work = sys.argv[1:5]
    os.makedirs(work, exist_ok=True)
    capture = os.path.join(work, "sunspec.pcap")
    truth_path = os.path.join(work, "sunspec.truth.json")
    run([sim, "--inverters", "0", "--sunspec", str(STATION), "--duration", "120", "--seed", "41",
         "--pdu", capture, "--truth", truth_path])
    with open(truth_path, encoding="utf-8") as f:
        truth = truth_last(json.load(f))
    failures = []
    got = audited(pvtap, capture)
    for register, (key, value) in sorted(truth.items()):
        v = got.get(register)
        if v is None or not isinstance(v.get("value"), (int, float)) or \
                abs(v["value"] - value) > 1e-6 * max(1.0, abs(value)):
            failures.append("audit: %s (%s) is %s, the truth %s" % (key, register, v, value))
        elif not v.get("name") or ":" not in v["name"]:
            failures.append("audit: %s has no model's name: %s" % (key, v))
    if len(truth) < 20:
        failures.append("the truth lays out only %d points" % len(truth))

    # The chain, recorded: a capture cut after the scan decodes with it as the whole one did.
    drafts = os.path.join(work, "drafts")
    os.makedirs(drafts, exist_ok=True)
    run([pvtap, "audit", "--summary-only", "--draft-map", drafts, capture])
    draft = os.path.join(drafts, "station-%d.toml" % STATION)
    text = open(draft, encoding="utf-8").read() if os.path.isfile(draft) else ""
    if "[sunspec]" not in text or "[103, 50]" not in text:
        failures.append("the draft map records no chain:\n" + text[:400])
    cut = os.path.join(work, "after-scan.pcap")
    run(["editcap", "-r", capture, cut, "17-1000000"])
    without = audited(pvtap, cut)
    with_map = audited(pvtap, cut, ["%d=%s" % (STATION, draft)])
    for register, (key, value) in sorted(truth.items()):
        named = with_map.get(register)
        if named is None or abs(named["value"] - value) > 1e-6 * max(1.0, abs(value)):
            failures.append("after the scan, with the draft map: %s is %s" % (key, named))
        if without.get(register, {}).get("name"):
            failures.append("after the scan, without a map, %s is named: %s"
                            % (key, without[register]))

    if os.path.isfile(plugin):
        runs = [(capture, two_pass, None, "one pass" if not two_pass else "two passes")
                for two_pass in (False, True)]
        runs.append((cut, False, draft, "after the scan, with the draft map"))
        for path, two_pass, station_map, what in runs:
            shown = plugin_last(plugin, path, two_pass, station_map)
            for register, (key, value) in sorted(truth.items()):
                if key not in shown or abs(shown[key] - value) > 1e-6 * max(1.0, abs(value)):
                    failures.append("plugin (%s): %s is %s, the truth %s"
                                    % (what, key, shown.get(key), value))
    else:
        print("plugin not built: its part skipped")
    print("%d SunSpec points checked against the truth" % len(truth))
    for f in failures:
        print("  " + f)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
