#!/usr/bin/env python3
"""The LAN samples (Solarman V5 through a logger stick, Modbus/TCP through a gateway) hold what
their ground truth says, read without pvtap:

- TCP: real tshark finds no analysis problem (lost segments, bad acknowledgements, ...).
- V5: a reader here takes each direction's stream apart into V5 frames: every length holds,
  every checksum is right except where the truth says bad, the frames are the truth's (control
  code, sequence, length, TCP segments), replies echo their request's sequence byte, the RTU
  frames inside are the truth's frames in order (quirk bytes, two zeros after a reply's CRC,
  where the truth says), requests without a reply are the truth's timeouts, and the carrier's
  counts are the truth's.
- MBAP: tshark's own mbtcp dissector reads every ADU with the truth's transaction id, unit,
  function and length; each request has one reply of its transaction; the gateway's exception
  0x0B answers exactly the truth's timeouts; the PDUs are the truth's frames without their CRC;
  the counts (pipelined requests included) are the truth's.
- The simulator: a lying MBAP length is where the truth says, by what it says; carrier options
  that the bus cannot honour are refused.

usage: check_lan_samples.py SAMPLES_DIR PVTAP_SIM SCRATCH
"""
import glob
import json
import os
import subprocess
import sys

TSHARK = ["tshark", "-n", "-o", "tcp.desegment_tcp_streams:TRUE"]
CONTROL = {"request": 0x4510, "response": 0x1510, "heartbeat": 0x4710, "data_report": 0x4210,
           "heartbeat_answer": 0x1710, "data_answer": 0x1210}


class Problems(list):
    def check(self, ok, text):
        if not ok:
            self.append(text)


def crc16_modbus(data):
    crc = 0xFFFF
    for b in data:
        crc ^= b
        for _ in range(8):
            crc = (crc >> 1) ^ 0xA001 if crc & 1 else crc >> 1
    return crc


def crc_ok(frame):
    return len(frame) >= 4 and crc16_modbus(frame[:-2]) == int.from_bytes(frame[-2:], "little")


def tshark_fields(path, fields, display_filter=None):
    cmd = TSHARK + ["-r", path, "-T", "fields", "-E", "occurrence=a", "-E", "aggregator=|"]
    if display_filter:
        cmd += ["-Y", display_filter]
    for f in fields:
        cmd += ["-e", f]
    run = subprocess.run(cmd, capture_output=True, text=True, check=True)
    return [line.split("\t") for line in run.stdout.splitlines()]


def tcp_problems(path, problems):
    flagged = tshark_fields(path, ["frame.number"], "tcp.analysis.flags")
    problems.check(not flagged, f"{path}: tshark flags TCP problems in frames "
                   f"{[r[0] for r in flagged][:5]}")


def streams(path, device_port):
    """Each direction's payload bytes, and the segments: (start offset, end offset, time)."""
    out = {}
    rows = tshark_fields(path, ["frame.time_epoch", "tcp.srcport", "tcp.seq", "tcp.len",
                                "tcp.payload"], "tcp.len > 0")
    for time, port, seq, length, payload in rows:
        side = "device" if int(port) == device_port else "client"
        data, segments = out.setdefault(side, (bytearray(), []))
        start = int(seq) - 1  # relative sequence numbers: the SYN took 0
        if start != len(data):
            raise SystemExit(f"{path}: {side} segment at {start}, stream at {len(data)}")
        data += bytes.fromhex(payload.replace(":", ""))
        segments.append((start, len(data), float(time)))
    return out


def v5_frames(data, segments, side):
    """The V5 frames of one direction with what a reader sees of them."""
    frames, at = [], 0
    while at < len(data):
        if data[at] != 0xA5 or at + 13 > len(data):
            raise SystemExit(f"{side}: no V5 frame at offset {at}")
        length = int.from_bytes(data[at + 1:at + 3], "little")
        end = at + 13 + length
        frame = bytes(data[at:end])
        spanned = [s for s in segments if s[0] < end and s[1] > at]
        frames.append({
            "bytes": frame, "from": side, "ts": spanned[-1][2], "length": length,
            "ends_right": len(frame) == 13 + length and frame[-1] == 0x15,
            "control": int.from_bytes(frame[3:5], "little"), "sequence": frame[5:7].hex(),
            "checksum": "ok" if sum(frame[1:-2]) % 256 == frame[-2] else "bad",
            "segments": len(spanned),
            "shared": any(s[0] < at or s[1] > end for s in spanned) and len(spanned) == 1,
        })
        at = end
    return frames


def rtu_of(frame, truth_quirk):
    """The RTU frame a V5 request or reply carries, and the quirk bytes after it."""
    payload = frame["bytes"][11:-2]
    if frame["control"] == CONTROL["request"]:
        return payload[15:], 0
    rtu = payload[14:]
    # A reply with two zeros after a good CRC: the known quirk, told by the CRC itself; a
    # damaged reply's end is taken from the truth, its zeros still checked.
    if not crc_ok(rtu) and rtu[-2:] == b"\0\0" and crc_ok(rtu[:-2]):
        return rtu[:-2], 2
    if truth_quirk and rtu[-2:] == b"\0\0":
        return rtu[:-truth_quirk], truth_quirk
    return rtu, 0


def check_v5(path, truth, problems):
    tcp_problems(path, problems)
    s = streams(path, truth["v5"]["port"])
    frames = sorted(v5_frames(*s["client"], "client") + v5_frames(*s["device"], "stick"),
                    key=lambda f: f["ts"])
    expected = truth["v5_frames"]
    problems.check(len(frames) == len(expected),
                   f"{path}: {len(frames)} V5 frames, truth {len(expected)}")
    events = truth["events"]
    # Requests in the order sent, each with the reply that echoes its sequence byte; a reply
    # to a request older than the last one sent is late.
    exchanges, waiting, counts = [], {}, dict.fromkeys(truth["v5"], 0)
    for f, t in zip(frames, expected):
        where = f"{path}: V5 frame at {f['ts']:.6f}"
        problems.check(f["ends_right"], f"{where}: its length does not hold")
        problems.check(
            (f["from"], hex(f["control"]), f["sequence"], f["length"], f["checksum"],
             f["segments"], f["shared"]) ==
            (t["from"], t["control"], t["sequence"], t["length"], t["checksum"],
             t.get("segments", 1), t.get("shared_segment", False)), f"{where}: {f} vs {t}")
        counts["frames"] += 1
        counts["bad_checksums"] += f["checksum"] == "bad"
        counts["split_frames"] += f["segments"] > 1
        counts["shared_segments"] += f["shared"] and f["from"] == "stick" and \
            f["control"] == CONTROL["response"]
        rtu, quirk = b"", 0
        if f["control"] == CONTROL["request"]:
            rtu, quirk = rtu_of(f, 0)
            counts["requests"] += 1
            exchange = {"request": ("request", rtu.hex()), "ts": f["ts"], "reply": None,
                        "refused": t.get("refused", False)}
            exchanges.append(exchange)
            waiting[f["sequence"][:2]] = exchange
        elif f["control"] == CONTROL["response"]:
            newest = exchanges[-1] if exchanges else None
            asked = waiting.pop(f["sequence"][:2], None)
            problems.check(asked is not None,
                           f"{where}: reply sequence {f['sequence']} echoes no request waiting")
            if "stick_code" in t:
                check_stick_code(f, t, asked, truth, counts, problems, where)
            else:
                counts["responses"] += 1
                rtu, quirk = rtu_of(f, t.get("quirk_bytes", 0))
                late = asked is not None and asked is not newest
                problems.check(late == t.get("late", False),
                               f"{where}: late {late}, truth {t.get('late', False)}")
                if asked:
                    asked["reply"] = ("response", rtu.hex())
                if late:
                    counts["replies_after_next_request"] += 1
                    latency = (f["ts"] - asked["ts"]) * 1e3
                    problems.check(abs(latency - t["latency_ms"]) < 0.002,
                                   f"{where}: latency {latency} ms, truth {t['latency_ms']}")
            problems.check(quirk == t.get("quirk_bytes", 0), f"{where}: {quirk} quirk bytes")
        if "event" in t:
            ev = events[t["event"]]
            problems.check(ev["hex"] == rtu.hex(),
                           f"{where}: carries {rtu.hex()}, truth event {t['event']} {ev['hex']}")
        counts["heartbeats"] += f["control"] == CONTROL["heartbeat"]
        counts["data_reports"] += f["control"] == CONTROL["data_report"]
        counts["client_answers"] += f["control"] in (CONTROL["heartbeat_answer"],
                                                     CONTROL["data_answer"])
        counts["rtu_bytes"] += len(rtu)
        counts["quirk_bytes"] += quirk
        counts["carrier_bytes"] += len(f["bytes"]) - len(rtu) - quirk
    carried = []
    for x in exchanges:
        if not x["refused"]:
            carried += [x["request"]] + ([x["reply"]] if x["reply"] else [])
    problems.check([(e["role"], e["hex"]) for e in events] == carried,
                   f"{path}: the RTU frames inside the V5 frames are not the truth's frames")
    counts["stick_frames"] = counts["heartbeats"] + counts["data_reports"]
    for key in ("logger_serial", "port", "dropped_replies"):
        counts[key] = truth["v5"][key]
    for f, t in zip(frames, expected):
        serial = int.from_bytes(f["bytes"][7:11], "little")
        problems.check((serial == counts["logger_serial"]) != t.get("refused", False),
                       f"{path}: frame at {f['ts']:.6f} addresses logger {serial}")
    problems.check(counts == truth["v5"], f"{path}: counts {counts}, truth {truth['v5']}")
    check_unanswered(path, truth, exchanges, problems)


def check_stick_code(f, t, asked, truth, counts, problems, where):
    """A response whose payload carries the stick's two-byte code in place of an RTU frame:
    05 answers a request the bus left unanswered (a truth timeout with the stick's reason), 06
    refuses a request addressed to another serial (a request the truth says was refused)."""
    code = f["bytes"][11 + 14:-2]
    problems.check(len(code) == 2 and code[1] == 0 and code[:1].hex() == t["stick_code"],
                   f"{where}: stick code {code.hex()}, truth {t['stick_code']}")
    counts["stick_codes"] += 1
    if asked is None:
        return
    if t["stick_code"] == "05":
        counts["stick_timeouts"] += 1
        problems.check(any(abs(x["request_ts"] - asked["ts"]) < 0.01 and
                           x.get("reason") == "the stick answered code 05"
                           for x in truth["timeouts"]),
                       f"{where}: code 05 to a request that is no truth timeout with its reason")
    elif t["stick_code"] == "06":
        counts["refused_requests"] += 1
        problems.check(asked["refused"], f"{where}: code 06 to a request the truth did not refuse")


def check_unanswered(path, truth, exchanges, problems):
    """Requests that got no RTU reply and were not refused: the truth's timeouts and the
    requests still waiting at the end, and nothing else."""
    unanswered = [x for x in exchanges if not x["reply"] and not x["refused"]]
    waiting = len(truth["timeouts"]) + len(truth["unanswered_at_end"])
    problems.check(len(unanswered) == waiting,
                   f"{path}: {len(unanswered)} requests unanswered, truth {waiting}")
    drops = sum(f["kind"] == "stick_drop" for f in truth["faults"])
    problems.check(drops == truth["v5"]["dropped_replies"],
                   f"{path}: {drops} stick_drop faults, {truth['v5']['dropped_replies']} drops")


def mbap_adus(path):
    rows = tshark_fields(path, ["frame.time_epoch", "tcp.srcport", "mbtcp.trans_id",
                                "mbtcp.prot_id", "mbtcp.len", "mbtcp.unit_id",
                                "modbus.func_code", "modbus.exception_code", "tcp.payload"],
                         "mbtcp")
    adus = []
    for time, port, tids, prots, lens, units, funcs, exceptions, payload in rows:
        # One ADU per segment here (the gateway and client send each alone).
        problems_free = "|" not in tids
        adus.append({"ts": float(time), "from": "gateway" if port == "502" else "client",
                     "transaction": int(tids.split("|")[0]), "protocol": int(prots.split("|")[0]),
                     "length_field": int(lens.split("|")[0]), "unit": int(units.split("|")[0]),
                     "function": int(funcs.split("|")[0]) if funcs else None,
                     "exception": int(exceptions) if exceptions else None,
                     "unit_pdu": bytes.fromhex(payload.replace(":", ""))[6:],
                     "alone": problems_free})
    return adus


def check_mbap(path, truth, problems):
    tcp_problems(path, problems)
    adus, expected, events = mbap_adus(path), truth["mbap_frames"], truth["events"]
    problems.check(len(adus) == len(expected),
                   f"{path}: tshark reads {len(adus)} MBAP ADUs, truth {len(expected)}")
    counts = dict.fromkeys(truth["mbap"], 0)
    counts["port"] = 502
    outstanding, exceptions = {}, []
    for a, t in zip(adus, expected):
        where = f"{path}: ADU at {a['ts']:.6f}"
        # mbtcp names an exception reply by its function without the 0x80 bit.
        function = t["function"] & 0x7F
        problems.check((a["from"], a["transaction"], a["protocol"], a["unit"], a["function"],
                        a["length_field"], a["alone"]) ==
                       (t["from"], t["transaction"], 0, t["unit"], function,
                        t["length_field"], True), f"{where}: {a} vs {t}")
        problems.check(len(a["unit_pdu"]) == a["length_field"], f"{where}: length field lies")
        counts["adus"] += 1
        counts["carrier_bytes"] += 6
        counts["pdu_bytes"] += len(a["unit_pdu"])
        if a["from"] == "client":
            counts["requests"] += 1
            counts["pipelined_requests"] += bool(outstanding)
            outstanding[a["transaction"]] = a
        else:
            counts["responses"] += 1
            problems.check(a["transaction"] in outstanding,
                           f"{where}: reply to transaction {a['transaction']}, never asked")
            outstanding.pop(a["transaction"], None)
        if "event" in t:
            problems.check(a["unit_pdu"].hex() == events[t["event"]]["hex"][:-4],
                           f"{where}: PDU {a['unit_pdu'].hex()} is not event {t['event']}")
        if a["exception"] == 0x0B:
            counts["gateway_exceptions"] += 1
            exceptions.append(a)
    problems.check(len(outstanding) == len(truth["unanswered_at_end"]),
                   f"{path}: {len(outstanding)} transactions unanswered at the end")
    problems.check(len(exceptions) == len(truth["timeouts"]) and
                   all(e["unit"] == t["station"] for e, t in zip(exceptions, truth["timeouts"])),
                   f"{path}: {len(exceptions)} gateway exceptions 0x0B, "
                   f"{len(truth['timeouts'])} timeouts on the bus")
    problems.check(counts == truth["mbap"], f"{path}: counts {counts}, truth {truth['mbap']}")


def check_simulator(sim, scratch, problems):
    os.makedirs(scratch, exist_ok=True)
    capture, truth_path = os.path.join(scratch, "lying.mbap.pcap"), os.path.join(scratch, "t.json")
    subprocess.run([sim, "--seed", "9", "--duration", "60", "--faults", "missing=10",
                    "--mbap", capture, "--mbap-faults", "lying_length=20", "--truth",
                    truth_path], check=True)
    with open(truth_path, encoding="utf-8") as f:
        truth = json.load(f)
    rows = tshark_fields(capture, ["tcp.payload"], "tcp.len > 0")
    segments = [bytes.fromhex(r[0].replace(":", "")) for r in rows]
    said = [(int.from_bytes(s[4:6], "big"), len(s) - 6) for s in segments]
    told = [(t["length_field"], t["length"]) for t in truth["mbap_frames"]]
    problems.check(said == told, "lying lengths: the ADUs' length fields are not the truth's")
    lies = sum(field != length for field, length in said)
    problems.check(lies == truth["mbap"]["lying_lengths"] and lies > 0,
                   f"lying lengths: {lies} in the capture, truth {truth['mbap']['lying_lengths']}")
    check_stick(sim, scratch, problems)
    for bad in (["--v5", "x", "--faults", "noise=5"], ["--mbap", "x", "--faults", "corrupt=5"],
                ["--v5", "x", "--pdu", "y"], ["--v5", "x", "--mbap", "y"],
                ["--v5", "x", "--dialect", "ascii"], ["--v5", "x", "--v5-faults", "lost=5"]):
        run = subprocess.run([sim] + bad, cwd=scratch, capture_output=True, text=True)
        problems.check(run.returncode == 2, f"pvtap-sim {' '.join(bad)}: exit {run.returncode}")


# Real sticks' ways (issue 35): codes 05 and 06 in place of RTU frames, a client with a wrong
# serial, heartbeats where a reply was due and replies after the client's next request; with
# the carrier faults of the samples besides.
STICK_FAULTS = "stick_code=50,wrong_serial=8,late=10,beat_first=10,quirk=20,drop=3," \
               "bad_checksum=2,split=10,merge=3"


def check_stick(sim, scratch, problems):
    """A stick with every behaviour of STICK_FAULTS: the capture holds what its truth says,
    and each behaviour happened."""
    capture, truth_path = (os.path.join(scratch, "stick.v5.pcap"),
                           os.path.join(scratch, "stick.truth.json"))
    subprocess.run([sim, "--seed", "35", "--dialect", "gsl,hybrid", "--inverters", "4",
                    "--duration", "120", "--period", "5", "--faults", "missing=10,corrupt=3",
                    "--v5", capture, "--v5-faults", STICK_FAULTS, "--truth", truth_path],
                   check=True)
    with open(truth_path, encoding="utf-8") as f:
        truth = json.load(f)
    check_v5(capture, truth, problems)
    for key in ("stick_timeouts", "refused_requests", "replies_after_next_request",
                "dropped_replies"):
        problems.check(truth["v5"][key] > 0, f"{capture}: no {key} in the truth")
    # No --heartbeat: each heartbeat (but one merged with a reply) is where a reply was due,
    # and the reply comes late, after the client's next request.
    frames = [f for f in truth["v5_frames"] if not f.get("shared_segment")]
    beats = [i for i, f in enumerate(frames) if f["control"] == "0x4710"]
    problems.check(beats, f"{capture}: no heartbeat where a reply was due")
    for i in beats:
        after = [(f["from"], f["control"], f.get("late", False)) for f in frames[i + 1:i + 4]]
        problems.check(after == [("client", "0x1710", False), ("client", "0x4510", False),
                                 ("stick", "0x1510", True)],
                       f"{capture}: heartbeat at {frames[i]['ts']} followed by {after}")


def main():
    samples, sim, scratch = sys.argv[1:4]
    sim = os.path.abspath(sim)
    problems = Problems()
    v5 = sorted(glob.glob(os.path.join(samples, "*.v5.pcap")))
    mbap = sorted(glob.glob(os.path.join(samples, "*.mbap.pcap")))
    problems.check(v5 and mbap, f"no V5 or MBAP samples in {samples}")
    for path in v5 + mbap:
        with open(path.rsplit(".", 2)[0] + ".truth.json", encoding="utf-8") as f:
            truth = json.load(f)
        (check_v5 if path in v5 else check_mbap)(path, truth, problems)
    check_simulator(sim, scratch, problems)
    for p in problems:
        print(p)
    print(f"{len(v5)} V5 and {len(mbap)} MBAP samples: {len(problems)} problems")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
