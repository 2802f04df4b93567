"""Register maps from the pvtap/ folder of the personal configuration folder."""

import unittest

from bus_frames import hybrid_reply, rtu_read_request
from pcap_writer import Pcap, TcpFlow
from tshark_runner import PluginTestCase

SITE_MAP = """
dialect = "hybrid"
mode = "extend"

[[register]]
address = 0x1006
key = "battery_voltage"
name = "battery voltage"
scale = 0.01
unit = "V"

[[register]]
address = 0x1050
key = "export_limit"
name = "export limit"
unit = "W"
"""

BROKEN_MAP = """
dialect = "gsl"
[[register]]
address = 1050
key = "grid voltage"
name = "grid voltage"
scael = 0.1
"""


class UserRegisterMaps(PluginTestCase, unittest.TestCase):
    user_maps = {"site.toml": SITE_MAP, "zz-broken.toml": BROKEN_MAP}

    @classmethod
    def setUpClass(cls):
        super().setUpClass()
        pcap = Pcap()
        flow = TcpFlow(pcap, server=("10.0.0.3", 8899))
        flow.request(rtu_read_request(6, 0x12, 0x1000, 8))
        flow.reply(hybrid_reply(6, 0x12, 0x31, 103, list(range(2200, 2208))))
        flow.request(rtu_read_request(6, 0x17, 0x104B, 6))
        flow.reply(hybrid_reply(6, 0x17, 0x31, 103, [11, 12, 13, 14, 15, 4600]))
        cls.capture = cls.tshark.write("site.pcap", pcap)

    def test_extended_register_has_its_own_field(self):
        rows = self.tshark.fields(self.capture, ["invrtu.hybrid.export_limit",
                                                 "invrtu.hybrid.battery_voltage"], "invrtu.role == 1")
        self.assertEqual(rows, [[[], ["22.06"]], [["4600"], []]])

    def test_built_in_registers_stay(self):
        rows = self.tshark.fields(self.capture, ["invrtu.hybrid.load_voltage"], "invrtu.role == 1")
        self.assertEqual(rows[0], [["220.2"]])

    def test_broken_file_is_reported_not_fatal(self):
        result = self.tshark.run(["-r", self.capture, "-2"])
        self.assertIn("zz-broken.toml was not loaded", result.stderr)
        self.assertIn("unknown register field 'scael'", result.stderr)
        self.assertEqual(result.stdout.count("invRTU"), 4)


if __name__ == "__main__":
    unittest.main()
