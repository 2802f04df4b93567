"""The reference's options as preferences: GSL register IDs and the 32-bit pair rule."""

import unittest

from bus_frames import gsl_read_reply, rtu_read_request
from pcap_writer import Pcap, TcpFlow
from tshark_runner import PluginTestCase


class ReferenceOptions(PluginTestCase, unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        super().setUpClass()
        pcap = Pcap()
        flow = TcpFlow(pcap, server=("10.0.0.2", 4001))
        flow.request(rtu_read_request(1, 0x03, 0x1056, 1))  # ID 1056 read as hex digits
        flow.reply(gsl_read_reply(1, [5001]))
        flow.request(rtu_read_request(1, 0x03, 1086, 2))  # total energy, high and low word
        flow.reply(gsl_read_reply(1, [1, 2]))
        cls.capture = cls.tshark.write("options.pcap", pcap)

    def replies(self, options=()):
        return self.tshark.fields(self.capture, ["invrtu.gsl.grid_frequency",
                                                 "invrtu.gsl.total_energy", "invrtu.word"],
                                  "invrtu.role == 1", options)

    def test_defaults_are_decimal_ids_and_binary_pairs(self):
        self.assertEqual(self.replies(), [[[], [], ["0x1389"]], [[], ["6553.8"], []]])

    def test_hex_ids(self):
        rows = self.replies(["-o", "invrtu.gsl_ids:hex"])
        self.assertEqual(rows[0], [["50.01"], [], []])

    def test_decimal_pairs(self):
        rows = self.replies(["-o", "invrtu.pair_rule:decimal"])
        self.assertEqual(rows[1], [[], ["1000.2"], []])


if __name__ == "__main__":
    unittest.main()
