"""Service Response Time tables: tshark -q -z invrtu,srt and -z invascii,srt."""

import re
import unittest

from bus_frames import (ascii_reply, ascii_request, gsl_exception, gsl_read_reply,
                        gsl_write_single, hybrid_reply, rtu_read_request)
from pcap_writer import Pcap, TcpFlow
from tshark_runner import PluginTestCase


def build_capture():
    pcap = Pcap()
    gsl = TcpFlow(pcap, server=("10.0.0.2", 4001))
    for latency in (0.020, 0.040, 0.060):
        gsl.request(rtu_read_request(1, 0x03, 1050, 2))
        gsl.reply(gsl_read_reply(1, [1, 2]), after=latency)
    gsl.request(rtu_read_request(1, 0x03, 9000, 1))
    gsl.reply(gsl_exception(1, 0x03, 2), after=0.030)
    gsl.request(gsl_write_single(1, 2010, 0xAAAA))
    gsl.reply(gsl_write_single(1, 2010, 0xAAAA), after=0.050)
    gsl.request(rtu_read_request(2, 0x03, 1050, 2))  # never answered
    hybrid = TcpFlow(pcap, client=("10.0.0.1", 50001), server=("10.0.0.3", 8899), time=3.0)
    hybrid.request(rtu_read_request(6, 0x12, 0x1000, 2))
    hybrid.reply(hybrid_reply(6, 0x12, 0x31, 103, [1, 2]), after=0.100)
    ascii = TcpFlow(pcap, client=("10.0.0.1", 50002), server=("10.0.0.4", 20108), time=6.0)
    for latency in (0.200, 0.400):
        ascii.request(ascii_request(1, 0x0020, 2))
        ascii.reply(ascii_reply(1, 0x0020, [266, 57]), after=latency)
    return pcap


def srt_rows(output):
    """{index: (calls, min, max)} from tshark's SRT table."""
    rows = {}
    for line in output.splitlines():
        m = re.match(r"\s*(\d+)\s+0x[0-9A-F]{2} .*?\s(\d+)\s+([\d.]+)\s+([\d.]+)\s+[\d.]+\s+[\d.]+$",
                     line)
        if m:
            rows[int(m.group(1))] = (int(m.group(2)), float(m.group(3)), float(m.group(4)))
    return rows


class ResponseTimeTables(PluginTestCase, unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        super().setUpClass()
        cls.capture = cls.tshark.write("srt.pcap", build_capture())

    def table(self, name):
        out = self.tshark.run(["-r", self.capture, "-2", "-q", "-z", name + ",srt"]).stdout
        self.assertIn("SRT Statistics", out)
        return srt_rows(out)

    def test_rtu_table_has_a_row_per_function(self):
        rows = self.table("invrtu")
        self.assertEqual(set(rows), {0x03, 0x06, 0x12})
        calls, low, high = rows[0x03]
        self.assertEqual(calls, 4)  # three reads and one exception; the unanswered one is out
        self.assertAlmostEqual(low, 0.020, places=6)
        self.assertAlmostEqual(high, 0.060, places=6)
        self.assertEqual(rows[0x06][0], 1)
        self.assertAlmostEqual(rows[0x12][1], 0.100, places=6)

    def test_ascii_table(self):
        rows = self.table("invascii")
        self.assertEqual(rows, {0x52: (2, 0.200, 0.400)})


if __name__ == "__main__":
    unittest.main()
