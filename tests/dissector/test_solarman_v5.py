"""invv5 in the real tshark: logger-stick flows recognised by structure, V5 header fields and
verdicts, the RTU frames handed to invrtu, the same verdicts as pvtap audit in one pass and
two, frames across and within segments, and Modbus/TCP left to mbtcp."""

import json
import os
import subprocess
import unittest

from bus_frames import gsl_read_reply, rtu_read_request
from pcap_writer import Pcap, TcpFlow
from test_sample_library import PROTOCOLS, Verdicts, add_pdu, audit_verdicts, pvtap_binary
from tshark_runner import PluginTestCase
from v5_frames import (REQUEST, RESPONSE, SERIAL, broken_stick, request_payload,
                       response_payload, stick_reads, threads_stick, v5_frame)

# What pvtap audit's summary says of the sticks, and the invv5 field or expert that says the
# same in the plugin: each is counted once per occurrence.
V5_COUNTS = {"frames": "invv5.control", "bad_checksums": "invv5.checksum.bad",
             "quirk_frames": "invv5.quirk", "truncated_frames": "invv5.truncated",
             "length_mismatches": "invv5.length_mismatch"}


# A stick as real ones behave (issue 35), from pvtap-sim with its truth: codes 05 (no reply on
# the bus) and 06 (a client that addressed another serial), heartbeats where a reply was due
# and replies after the client's next request, besides the carrier faults of the samples.
STICK_FAULTS = ("stick_code=50,wrong_serial=8,late=10,beat_first=10,quirk=20,drop=3,"
                "bad_checksum=2,split=10,merge=3")
# pvtap audit's summary key of the stick's codes, and the invv5 field or expert that says each.
STICK_COUNTS = {"stick_codes": "invv5.stick_code", "stick_timeouts": "invv5.stick_no_reply",
                "refused_requests": "invv5.stick_refused",
                "other_stick_codes": "invv5.stick_code_other"}


def simulated_stick(directory):
    """The capture and its ground truth."""
    sim = os.environ.get("PVTAP_SIM")
    if not sim or not os.access(sim, os.X_OK):
        raise RuntimeError("PVTAP_SIM must name the built pvtap-sim (got %r)" % sim)
    capture, truth = os.path.join(directory, "stick.v5.pcap"), os.path.join(directory, "t.json")
    subprocess.run([sim, "--seed", "35", "--dialect", "gsl,hybrid", "--inverters", "4",
                    "--duration", "120", "--period", "5", "--faults", "missing=10,corrupt=3",
                    "--v5", capture, "--v5-faults", STICK_FAULTS, "--truth", truth],
                   check=True, timeout=120)
    with open(truth) as f:
        return capture, json.load(f)


def audit_v5(capture):
    out = subprocess.run([pvtap_binary(), "audit", "--format", "jsonl", "--summary-only",
                          capture], capture_output=True, text=True, timeout=120, check=True)
    summary = json.loads(out.stdout.splitlines()[-1])
    v5 = summary["network"]["solarman_v5"]
    return {key: v5[key] for key in V5_COUNTS}


def field_counts(node, counts):
    """How often each field or expert name occurs in a tshark JSON tree."""
    if isinstance(node, list):
        for item in node:
            field_counts(item, counts)
    elif isinstance(node, dict):
        for key, value in node.items():
            if isinstance(value, list) and not key.endswith("_tree"):
                counts[key] = counts.get(key, 0) + len(value)
                field_counts(value, counts)
            else:
                if not key.endswith("_tree"):
                    counts[key] = counts.get(key, 0) + 1
                field_counts(value, counts)
    return counts


def split_and_joined(pcap):
    """A request cut across two segments, a reply and a heartbeat in one, a request whose
    first byte is its segment's last."""
    flow = TcpFlow(pcap, client=("10.0.0.1", 50600), server=("10.0.0.11", 8899), time=400.0)
    first = v5_frame(REQUEST, 1, request_payload(rtu_read_request(1, 0x03, 1050, 2)))
    flow.request(first[:9])
    flow.request(first[9:])
    reply = v5_frame(RESPONSE, 1, response_payload(gsl_read_reply(1, [2301, 2302])))
    beat = v5_frame(0x4710, 2, b"\0")
    flow.reply(reply + beat)
    second = v5_frame(REQUEST, 3, request_payload(rtu_read_request(1, 0x03, 1056, 1)))
    flow.request(first + second[:1])
    flow.request(second[1:])
    flow.reply(v5_frame(RESPONSE, 1, response_payload(gsl_read_reply(1, [2303, 2304]))))
    flow.reply(v5_frame(RESPONSE, 3, response_payload(gsl_read_reply(1, [5000]), True)))


def modbus_tcp(pcap, port, time):
    """Modbus/TCP whose transaction id starts with 0xA5 (V5's start byte)."""
    flow = TcpFlow(pcap, client=("10.0.0.1", 50700), server=("10.0.0.12", port), time=time)
    flow.request(bytes.fromhex("A5 10 00 00 00 06 01 03 00 00 00 0A"))
    flow.reply(bytes.fromhex("A5 10 00 00 00 07 01 03 04 00 01 00 02"))


class SolarmanV5(PluginTestCase, unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        super().setUpClass()
        pcap = Pcap()
        cls.script = stick_reads(pcap)
        cls.reads = cls.tshark.write("stick.pcap", pcap)
        pcap = Pcap()
        broken_stick(pcap)
        cls.broken = cls.tshark.write("broken.pcap", pcap)
        pcap = Pcap()
        split_and_joined(pcap)
        cls.split = cls.tshark.write("split.pcap", pcap)

    def plugin(self, capture, passes):
        """invrtu's verdicts and the counts of invv5's fields, from tshark's JSON."""
        v, counts = Verdicts(), {}
        out = self.tshark.run(["-r", capture] + (["-2"] if passes == 2 else []) +
                              ["-Y", "invv5", "-T", "json", "--no-duplicate-keys"]).stdout
        for packet in json.loads(out):
            layers = packet["_source"]["layers"]
            for name in PROTOCOLS:
                pdus = layers.get(name, [])
                for pdu in pdus if isinstance(pdus, list) else [pdus]:
                    add_pdu(v, name, pdu)
            field_counts(layers.get("invv5", []), counts)
        return v, {key: counts.get(field, 0) for key, field in V5_COUNTS.items()}

    def assert_agrees_with_audit(self, capture, cut_at_end=0):
        """`cut_at_end`: frames the capture's end cuts short. pvtap audit knows the input
        ended and reports them truncated; no packet comes after them for the plugin to say
        so in (as for invrtu's bytes pending at the end), so it shows them in neither pass."""
        audit, audit_counts = audit_verdicts(capture), audit_v5(capture)
        audit_counts["truncated_frames"] -= cut_at_end
        self.assertGreater(sum(audit.frames.values()), 0)
        for passes in (1, 2):
            with self.subTest(passes=passes):
                verdicts, v5 = self.plugin(capture, passes)
                self.assertEqual(verdicts.as_dict(), audit.as_dict())
                self.assertEqual(v5, audit_counts)

    def test_a_stick_gets_the_verdicts_of_pvtap_audit(self):
        self.assert_agrees_with_audit(self.reads)
        _, v5 = self.plugin(self.reads, 2)
        self.assertEqual(v5, {"frames": 61, "bad_checksums": 1, "quirk_frames": 6,
                              "truncated_frames": 0, "length_mismatches": 0})

    def test_broken_frames_get_the_verdicts_of_pvtap_audit(self):
        self.assert_agrees_with_audit(self.broken, cut_at_end=1)
        self.assertEqual(audit_v5(self.broken)["truncated_frames"], 1)
        _, v5 = self.plugin(self.broken, 2)
        self.assertEqual(v5["length_mismatches"], 1)
        lying = self.tshark.fields(self.broken, ["invv5.claimed_size"], "invv5.length_mismatch")
        self.assertEqual(lying, [[["64"]]])  # 13 + the payload's 21 + the 30 it lies about

    def test_frames_across_and_within_segments_are_each_shown_once(self):
        self.assert_agrees_with_audit(self.split)
        rows = self.tshark.fields(self.split, ["frame.number", "invv5.control", "invv5.sequence"],
                                  "invv5")
        shown = [(r[1], r[2]) for r in rows]
        self.assertEqual(shown, [
            (["0x4510"], ["0x0001"]),                      # completed by its second segment
            (["0x1510", "0x4710"], ["0x0001", "0x0002"]),  # two frames in one segment
            (["0x4510"], ["0x0001"]),                      # the next one's first byte waits
            (["0x4510"], ["0x0003"]),
            (["0x1510"], ["0x0001"]),
            (["0x1510"], ["0x0003"]),
        ])

    def test_a_simulated_stick_gets_the_verdicts_of_pvtap_audit_and_its_truth(self):
        capture, truth = simulated_stick(self.tshark.home)
        self.tshark._hand_over()
        self.assert_agrees_with_audit(capture)
        want = {"stick_codes": truth["v5"]["stick_codes"],
                "stick_timeouts": truth["v5"]["stick_timeouts"],
                "refused_requests": truth["v5"]["refused_requests"], "other_stick_codes": 0}
        self.assertGreater(want["stick_timeouts"], 0)
        self.assertGreater(want["refused_requests"], 0)
        for passes in (1, 2):
            out = self.tshark.run(["-r", capture] + (["-2"] if passes == 2 else []) +
                                  ["-Y", "invv5.stick_code", "-T", "json",
                                   "--no-duplicate-keys"]).stdout
            counts = {}
            for packet in json.loads(out):
                field_counts(packet["_source"]["layers"].get("invv5", []), counts)
            with self.subTest(passes=passes):
                self.assertEqual({k: counts.get(f, 0) for k, f in STICK_COUNTS.items()}, want)
        refusals = self.tshark.fields(capture, ["_ws.expert.message"], "invv5.stick_refused")
        self.assertEqual(len(refusals), want["refused_requests"])
        for row in refusals:
            self.assertIn("The stick refused it: the client addressed logger 2111130827; the "
                          "stick is 2712345678", row[0])
        # The bus is the stick's: no second bus named after the serial the client addressed.
        self.assertEqual(self.tshark.fields(capture, ["invv5.serial"],
                                            "invv5.serial == 2111130827 && invrtu"), [])

    def test_the_issue_threads_stick_gets_the_verdicts_of_pvtap_audit(self):
        """Paired by sequence byte (latencies 200, 600 and 600 ms less the replies' time on
        the wire), code 05 a timeout, 06 a refusal, text before a V5 frame apart."""
        pcap = Pcap()
        threads_stick(pcap)
        capture = self.tshark.write("threads.pcap", pcap)
        self.assert_agrees_with_audit(capture)
        latencies = self.tshark.fields(capture, ["invrtu.response_time"],
                                       "invrtu.role == 1 && invrtu.response_time")
        self.assertEqual([round(float(r[0][0]), 3) for r in latencies],
                         [0.193, 0.593, 0.593])
        coded = self.tshark.fields(capture, ["invv5.stick_code"], "invv5.stick_no_reply")
        self.assertEqual(coded, [[["0x05"]]])
        refused = self.tshark.fields(capture, ["invv5.stick_code"], "invv5.stick_refused")
        self.assertEqual(refused, [[["0x06"]]])

    def test_a_lost_segment_gets_the_verdicts_of_pvtap_audit(self):
        """A reply's segment the capture lost: the request it answered waited during a loss."""
        pcap = Pcap()
        flow = TcpFlow(pcap, client=("10.0.0.1", 50900), server=("10.0.0.14", 8899), time=800.0)
        for i in range(4):
            flow.request(v5_frame(REQUEST, i, request_payload(rtu_read_request(1, 0x03, 1050,
                                                                               1))), after=0.5)
            flow.reply(v5_frame(RESPONSE, i, response_payload(gsl_read_reply(1, [2300 + i]))),
                       after=0.05)
            if i == 1:
                pcap.records.pop()  # lost
        self.assert_agrees_with_audit(self.tshark.write("lost.pcap", pcap))

    def test_header_fields_are_filterable(self):
        serials = self.tshark.fields(self.reads, ["invv5.serial"], "invv5.control == 0x4710")
        self.assertEqual(serials, [[[str(SERIAL)]]])
        quirks = self.tshark.fields(self.reads, ["frame.number"], "invv5.quirk == 00:00")
        self.assertEqual([int(r[0][0]) for r in quirks],
                         sorted(self.script.packets["reply_%d" % i] for i in (4, 9, 14, 19, 24, 29)))
        bad = self.tshark.fields(self.reads, ["frame.number", "invrtu.station"],
                                 "invv5.checksum.status == 0")
        self.assertEqual(bad, [[[str(self.script.packets["reply_23"])], ["1"]]])

    def test_modbus_tcp_is_left_to_mbtcp(self):
        pcap = Pcap()
        modbus_tcp(pcap, 502, 500.0)
        modbus_tcp(pcap, 1502, 600.0)  # off its port: mbtcp is not called, nor is invv5
        capture = self.tshark.write("mbtcp.pcap", pcap)
        rows = self.tshark.fields(capture, ["tcp.port", "mbtcp.trans_id", "invv5.control"],
                                  "tcp.len > 0")
        self.assertEqual(len(rows), 4)
        for row in rows:
            if "502" in row[0]:
                self.assertEqual(row[1], ["42256"])  # 0xA510: mbtcp read it
            self.assertEqual(row[2], [])


if __name__ == "__main__":
    unittest.main()
