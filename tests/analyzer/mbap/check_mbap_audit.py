#!/usr/bin/env python3
"""pvtap audit on Modbus/TCP captures built here: every ADU a frame, the MBAP headers carrier
bytes and never noise, pairing by transaction id, exceptions and the gateway's 0x0B, a length
that lies; on port 502, on another port (recognized by structure) and with --port.

    check_mbap_audit.py --pvtap PVTAP --scratch DIR --samples captures/samples
"""
import argparse
import glob
import json
import os
import struct
import subprocess
import sys
import unittest

# The capture is built by the helper the plugin's tests share.
sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "..", "dissector"))
import mbap_capture  # noqa: E402

ARGS = None


def audit(capture, *extra):
    out = subprocess.run([ARGS.pvtap, "audit", "--format", "jsonl", *extra, capture],
                         check=True, capture_output=True, text=True, timeout=60).stdout
    lines = [json.loads(line) for line in out.splitlines()]
    return lines[:-1], lines[-1]


class SimulatedGateways(unittest.TestCase):
    """The library's Modbus/TCP samples against the simulator's ground truth."""

    def test_every_adu_a_frame_and_the_truths_timeouts_and_exceptions(self):
        samples = sorted(glob.glob(os.path.join(ARGS.samples, "*.mbap.pcap")))
        self.assertTrue(samples, "no Modbus/TCP samples in " + ARGS.samples)
        for path in samples:
            with self.subTest(sample=os.path.basename(path)):
                truth_path = path[:-len(".mbap.pcap")] + ".truth.json"
                with open(truth_path) as f:
                    truth = json.load(f)
                summary = audit(path)[1]
                mbap = summary["network"]["mbap"]
                self.assertEqual(mbap["adus"], truth["mbap"]["adus"])
                self.assertEqual(mbap["carrier_bytes"], truth["mbap"]["carrier_bytes"])
                self.assertEqual(summary["frames"], truth["mbap"]["adus"])
                # The truth's PDU bytes count the unit id, as the bus's frame bytes do.
                self.assertEqual(summary["bytes"], truth["mbap"]["pdu_bytes"])
                self.assertEqual(summary["gateway_timeouts"], truth["mbap"]["gateway_exceptions"])
                for key in ("requests", "timeouts", "exceptions", "bad_checks", "noise_bytes"):
                    self.assertEqual(summary[key], truth["summary"][key], key)


class MbapAudit(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        os.makedirs(ARGS.scratch, exist_ok=True)
        cls.on_502 = os.path.join(ARGS.scratch, "mbap_502.pcap")
        cls.on_1502 = os.path.join(ARGS.scratch, "mbap_1502.pcap")
        mbap_capture.build(cls.on_502)
        mbap_capture.build(cls.on_1502, port=1502)
        cls.events, cls.summary = audit(cls.on_502)

    def check_counts(self, summary):
        e = mbap_capture.EXPECTED
        mbap = summary["network"]["mbap"]
        self.assertEqual(summary["network"]["flows_analyzed"], 1)
        self.assertEqual(summary["network"]["flows_ignored"], 0)
        self.assertEqual(mbap["flows"], 1)
        self.assertEqual(mbap["adus"], e["adus"])
        self.assertEqual(mbap["carrier_bytes"], e["carrier_bytes"])
        self.assertEqual(mbap["findings"], e["findings"])
        self.assertEqual(mbap["skipped_bytes"], e["skipped_bytes"])
        self.assertEqual(summary["frames"], e["adus"])
        self.assertEqual(summary["requests"], e["requests"])
        self.assertEqual(summary["responses"], e["responses"])
        self.assertEqual(summary["exceptions"], e["exceptions"])
        self.assertEqual(summary["gateway_timeouts"], e["gateway_timeouts"])
        self.assertEqual(summary["timeouts"], e["timeouts"])
        self.assertEqual(summary["bad_checks"], 0)
        self.assertEqual(summary["noise_bytes"], 0)
        self.assertEqual(summary["exception_codes"], {"modbus 0x02": 1})

    def test_counts_on_port_502(self):
        self.check_counts(self.summary)

    def test_recognized_by_structure_on_another_port(self):
        self.check_counts(audit(self.on_1502)[1])

    def test_port_option_reads_it_as_modbus_tcp(self):
        self.check_counts(audit(self.on_1502, "--port", "1502")[1])

    def test_every_byte_is_a_frame_a_header_or_skipped(self):
        mbap = self.summary["network"]["mbap"]
        frame_bytes = sum(ev["length"] for ev in self.events if ev["type"] == "frame")
        self.assertEqual(frame_bytes, self.summary["frame_bytes"])
        self.assertEqual(self.summary["bytes"], frame_bytes)
        payload = frame_bytes + mbap["carrier_bytes"] + mbap["skipped_bytes"]
        self.assertEqual(payload, self.tcp_payload_bytes())

    def tcp_payload_bytes(self):
        """The TCP payload of the capture, counted again from the file."""
        total = 0
        with open(self.on_502, "rb") as f:
            f.read(24)
            while True:
                head = f.read(16)
                if len(head) < 16:
                    return total
                length = struct.unpack("<IIII", head)[2]
                packet = f.read(length)
                ip = packet[14:]
                ip_len = (ip[0] & 0x0F) * 4
                tcp = ip[ip_len:]
                total += len(tcp) - (tcp[12] >> 4) * 4

    def test_write_leaves_out_frames_that_have_no_crc(self):
        written = os.path.join(ARGS.scratch, "written.pcap")
        subprocess.run([ARGS.pvtap, "audit", "--summary-only", "--write", written, self.on_502],
                       check=True, capture_output=True, timeout=60)
        with open(written, "rb") as f:
            self.assertEqual(len(f.read()), 24)  # the file header alone: no record

    def test_checks_are_said_to_be_tcps(self):
        checks = {ev["check"] for ev in self.events if ev["type"] == "frame"}
        self.assertEqual(checks, {"tcp"})

    def test_pipelined_replies_pair_by_transaction_id(self):
        frames = [ev for ev in self.events if ev["type"] == "frame"]
        replies = [ev for ev in frames if ev["role"] == "response"]
        # The first three replies answer requests 2, 1 and 3 (sent 10 ms apart at 100.01 s):
        # each latency is its own request's, not the previous frame's.
        self.assertEqual([round(r["latency_ms"], 3) for r in replies[:3]], [40.0, 55.0, 40.0])

    def test_the_gateways_0x0b_is_said_to_be_a_timeout_behind_it(self):
        issues = [i for ev in self.events if ev["type"] == "frame" for i in ev["issues"]]
        self.assertIn("exception 0x0B: gateway target device failed to respond (a timeout on "
                      "the serial bus behind the gateway)", issues)

    def test_text_report_names_the_bus_and_the_lying_length(self):
        text = subprocess.run([ARGS.pvtap, "audit", "--summary-only", self.on_502], check=True,
                              capture_output=True, text=True, timeout=60).stdout
        self.assertIn("-- bus 10.0.0.9:502 --", text)
        self.assertIn("Modbus/TCP: 1 flows, 21 ADUs, 126 carrier bytes (MBAP headers); 1 "
                      "headers that lied (12 bytes skipped)", text)
        self.assertIn("10.0.0.9:502: MBAP length overruns what was sent (the next segment is "
                      "whole ADUs) (protocol id 0, length 30): 12 bytes skipped", text)
        self.assertIn("timeouts: 2 good requests their station did not answer within "
                      "--timeout: 1 met silence until the timeout ran out, 1 answered by the "
                      "gateway's exception 0x0B (the device behind the gateway did not answer: "
                      "a timeout on its serial bus)", text)
        self.assertIn("noise: 0 bytes in 0 runs", text)


if __name__ == "__main__":
    parser = argparse.ArgumentParser()
    parser.add_argument("--pvtap", required=True)
    parser.add_argument("--scratch", required=True)
    parser.add_argument("--samples", required=True, help="the sample library (captures/samples)")
    ARGS, rest = parser.parse_known_args()
    unittest.main(argv=[sys.argv[0]] + rest, verbosity=2)
