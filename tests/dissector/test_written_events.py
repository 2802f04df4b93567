"""Records of pvtap's own capture that mark a moment rather than carry bus bytes (capture data
lost, the end of a run) show what they mark: no record of a `--write` file is blank in
Wireshark, and none is read as bytes of the bus."""

import os
import subprocess
import unittest

from bus_frames import gsl_read_reply, rtu_read_request
from pcap_writer import Pcap, TcpFlow
from tshark_runner import PluginTestCase

RUN_GUARD_S = 120


def gateway_with_a_hole(pcap):
    """Three polls through a gateway; 10 bytes of the second request's segment never
    captured (the sequence number jumps)."""
    flow = TcpFlow(pcap)
    for i in range(3):
        if i == 1:
            flow.seq[False] += 10
        flow.request(rtu_read_request(1, 0x03, 1056, 1), after=1.0)
        flow.reply(gsl_read_reply(1, [5000 + i]), after=0.05)


class WrittenEvents(PluginTestCase, unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        super().setUpClass()
        pcap = Pcap()
        gateway_with_a_hole(pcap)
        source = cls.tshark.write("gateway.pcap", pcap)
        cls.written = cls.tshark.path("written.pcap")
        audit = subprocess.run([os.environ["PVTAP_BINARY"], "audit", "--summary-only",
                                "--write", cls.written, source], capture_output=True,
                               text=True, timeout=RUN_GUARD_S)
        if audit.returncode != 0:
            raise AssertionError("pvtap audit --write failed: " + audit.stderr)
        cls.tshark._hand_over()
        cls.rows = cls.tshark.fields(cls.written, ["frame.protocols", "pvtap.event",
                                                   "_ws.col.Protocol", "_ws.col.Info"])

    def test_no_record_is_blank(self):
        self.assertGreater(len(self.rows), 6)
        for row in self.rows:
            self.assertTrue(row[2] and row[2][0], f"a record without a protocol: {row}")
            self.assertTrue(row[3] and row[3][0], f"a record without an Info: {row}")

    def test_the_loss_is_said(self):
        events = [row[1][0] for row in self.rows if row[1]]
        lost = [e for e in events if e.startswith("capture data lost")]
        self.assertEqual(len(lost), 1, events)
        self.assertIn("10 bytes", lost[0])

    def test_event_records_are_not_bus_bytes(self):
        for row in self.rows:
            if row[1]:
                self.assertNotIn("invrtu", row[0][0])
                self.assertEqual(row[2][0], "pvtap")


if __name__ == "__main__":
    unittest.main()
