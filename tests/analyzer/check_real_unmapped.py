#!/usr/bin/env python3
"""Devices without a map on a real bus: the plain dump of a Huawei inverter polling its battery
(station 5) and a DTSU666 meter (station 11), ../shared/real/raw, audited with no map. The
meter's block at 0x0836 (80 registers) is inferred as float32 high word first; its phase
voltage (0x083C) and frequency (0x084C) are in the jsonl summary, the text report and the HTML
report; --draft-map writes station-5.toml and station-11.toml, and the audit with them gives
every inferred value again, now named.

Usage: check_real_unmapped.py PVTAP REAL_DIR WORK_DIR
"""
import json
import os
import subprocess
import sys

RUN_GUARD_S = 300
SKIP = 77
DUMP = os.path.join("raw", "huawei_sun2000_luna_dtsu_9600_8N1.bin")


def audit(pvtap, dump, *extra):
    run = subprocess.run([pvtap, "audit", *extra, "--raw", dump], capture_output=True,
                         text=True, timeout=RUN_GUARD_S)
    if run.returncode not in (0, 1):
        raise RuntimeError(f"pvtap audit {' '.join(extra)} exited {run.returncode}: "
                           f"{run.stderr.strip()}")
    return run.stdout


def summary(pvtap, dump, *extra):
    return json.loads(audit(pvtap, dump, "--summary-only", "--format", "jsonl",
                            *extra).splitlines()[-1])


def meter_block(s):
    for block in s["stations"].get("11", {}).get("inferred", []):
        if block["function"] == 3 and block["values"][0]["register"] == "0x0836":
            return block
    return None


def check_meter(block, bad):
    if block is None:
        bad.append("no inferred block of station 11 at 0x0836")
        return {}
    values = {v["register"]: v for v in block["values"]}
    floats = [v for v in block["values"] if v["type"] == "float32"]
    if len(floats) != 40 or any(v["word_order"] != "high_first" for v in floats):
        bad.append(f"0x0836: {len(floats)} float32 values of 40, word orders "
                   f"{sorted({v['word_order'] for v in floats})}")
    for register, low, high, what in (("0x083C", 200, 260, "a phase voltage"),
                                      ("0x084C", 49, 51, "the frequency")):
        v = values.get(register)
        if v is None or not low <= v["last"] <= high:
            bad.append(f"{register} ({what}) reads {v and v['last']}, not {low}..{high}")
    return values


def check_reports(pvtap, dump, work, values, bad):
    text = audit(pvtap, dump)
    volts = values.get("0x083C", {}).get("last")
    if volts is not None and f"{volts:.1f}" not in text:
        bad.append(f"the text report does not show 0x083C's {volts:.1f}")
    html = os.path.join(work, "real-unmapped.html")
    audit(pvtap, dump, "--summary-only", "--html", html)
    with open(html, encoding="utf-8") as f:
        page = f.read()
    for register in ("0x083C", "0x084C"):
        if register not in page:
            bad.append(f"the HTML report does not name {register}")


def check_draft_maps(pvtap, dump, work, first, bad):
    folder = os.path.join(work, "drafts")
    os.makedirs(folder, exist_ok=True)
    for name in os.listdir(folder):
        os.remove(os.path.join(folder, name))
    audit(pvtap, dump, "--summary-only", "--draft-map", folder)
    names = sorted(os.listdir(folder))
    if names != ["station-11.toml", "station-5.toml"]:
        bad.append(f"draft maps written: {names}")
        return
    maps = []
    for name in names:
        maps += ["--map", f"{name[len('station-'):-len('.toml')]}={os.path.join(folder, name)}"]
    again = summary(pvtap, dump, *maps)
    compared = 0
    for station in ("5", "11"):
        named = {v["register"]: v for v in again["stations"][station]["values"]}
        for block in first["stations"][station].get("inferred", []):
            for v in block["values"]:
                got = named.get(v["register"])
                if v["type"] in ("unused", "text", "bits") or got is None and \
                        block["function"] != 3:
                    continue  # fill, words shown as words, and input registers a map shares
                compared += 1
                if got is None or not got.get("name") or not isinstance(got.get("value"),
                                                                        (int, float)):
                    bad.append(f"station {station} {v['register']} with its draft map: {got}")
                elif abs(got["value"] - v["last"]) > 1e-3 * max(1.0, abs(v["last"])):
                    bad.append(f"station {station} {v['register']}: {got['value']} with the "
                               f"draft map, {v['last']} inferred")
    if compared < 50:
        bad.append(f"only {compared} inferred values compared with their draft map's")
    print(f"{compared} inferred values read the same with the draft maps")


def main():
    pvtap, real, work = sys.argv[1:4]
    dump = os.path.join(real, DUMP)
    if not os.path.isfile(dump):
        print(f"{dump} is missing")
        return SKIP
    os.makedirs(work, exist_ok=True)
    bad = []
    first = summary(pvtap, dump)
    values = check_meter(meter_block(first), bad)
    check_reports(pvtap, dump, work, values, bad)
    check_draft_maps(pvtap, dump, work, first, bad)
    for line in bad:
        print("FAIL:", line)
    print(f"{len(bad)} failures")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
