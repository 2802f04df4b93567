"""invascii over TCP with no setup: the seed's example replies through a gateway."""

import unittest

from bus_frames import ascii_reply, ascii_request, with_bad_checksum, with_crc
from pcap_writer import Pcap, TcpFlow
from tshark_runner import PluginTestCase

# The seed's data words (PROTOCOLS.md section 5).
FAULTS = [0x0008, 0x40A2, 0x0021, 0x0000]
PV = [266, 57]
LINE = [217, 0, 0, 65, 0, 0, 601]
POWER = [2724, 57, 230, 2518, 2980, 998, 11340, 0]
SYSTEM = [0x1030, 0x0510, 0x0001]


def ascii_flow(pcap):
    at = {}
    flow = TcpFlow(pcap, server=("10.0.0.4", 20108))

    def mark(name):
        at[name] = len(pcap.records)

    flow.request(ascii_request(1, 0x0020, 2)); mark("pv_req")
    flow.reply(ascii_reply(1, 0x0020, PV)); mark("pv")
    flow.request(ascii_request(1, 0x0050, 7)); mark("line_req")
    line = ascii_reply(1, 0x0050, LINE)
    flow.reply(line[:1]); mark("line_piece_1")
    flow.reply(line[1:17]); mark("line_piece_2")
    flow.reply(line[17:]); mark("line")
    flow.request(ascii_request(1, 0x0060, 8) + ascii_request(2, 0x0060, 8)); mark("power_reqs")
    flow.reply(ascii_reply(1, 0x0060, POWER)); mark("power")
    flow.request(ascii_request(1, 0x0004, 4)); mark("faults_req")
    flow.reply(b"\x00\xff" + with_bad_checksum(ascii_reply(1, 0x0004, FAULTS)) + b"\x7e"); mark("faults")
    flow.request(ascii_request(1, 0x01E0, 2)); mark("system_req")
    flow.reply(ascii_reply(1, 0x01E0, SYSTEM)); mark("system")
    # Noise that happens to be an RTU frame with a good CRC is still just noise here. Bytes
    # that may start a frame at a segment's end wait for that direction's next segment, so
    # the noise shows with the reply after it.
    flow.reply(with_crc(bytes.fromhex("11 01 00 13 00 25"))); mark("rtu_shaped_noise")
    flow.request(ascii_request(1, 0x0004, 4)); mark("faults_req_again")
    flow.reply(ascii_reply(1, 0x0004, FAULTS)); mark("faults_again")
    # Past station 2's reply timeout: the first packet after it announces the timeout.
    flow.request(ascii_request(1, 0x0020, 2), after=1.5); mark("late_req")
    flow.reply(ascii_reply(1, 0x0020, PV)); mark("late")
    return at


class AsciiOverTcp(PluginTestCase, unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        super().setUpClass()
        pcap = Pcap()
        cls.at = ascii_flow(pcap)
        cls.capture = cls.tshark.write("ascii.pcap", pcap)
        cls.names = ["frame.number", "invascii.station", "invascii.role",
                     "invascii.checksum.status", "invascii.checksum.expected",
                     "invascii.request_in", "invascii.response_in", "invascii.pv_voltage",
                     "invascii.pv_current", "invascii.cumulative_energy",
                     "invascii.line_frequency", "invascii.inverter_status.inverter_running",
                     "invascii.noise", "invascii.manufacture_date", "invascii.expected_count"]
        cls.rows = {int(r[0][0]): r for r in cls.tshark.fields(cls.capture, cls.names)}
        cls.text = cls.tshark.verbose(cls.capture)

    def cell(self, packet, field):
        return self.rows[packet][self.names.index(field)]

    def matching(self, display_filter):
        return [int(r[0][0]) for r in self.tshark.fields(self.capture, ["frame.number"],
                                                          display_filter)]

    def test_seed_values_as_fields(self):
        a = self.at
        self.assertEqual(self.cell(a["pv"], "invascii.pv_voltage"), ["266"])
        self.assertEqual(self.cell(a["pv"], "invascii.pv_current"), ["5.7"])
        self.assertEqual(self.cell(a["power"], "invascii.cumulative_energy"), ["570.23"])
        self.assertEqual(self.cell(a["line"], "invascii.line_frequency"), ["60.1"])
        self.assertEqual(self.cell(a["system"], "invascii.manufacture_date"), ["2005-10"])

    def test_seed_values_with_units_in_the_tree(self):
        self.assertIn("PV voltage (0x0020): 266 V", self.text)
        self.assertIn("cumulative energy (0x0062): 570.230 kWh", self.text)
        self.assertIn("line frequency (0x005C): 60.1 Hz", self.text)
        self.assertIn("phase and capacity (0x01E0): single phase, 3.0 kW", self.text)

    def test_bit_table_as_bitfields(self):
        self.assertEqual(
            self.cell(self.at["faults_again"], "invascii.inverter_status.inverter_running"), ["1"])
        # Never from a frame with a bad check (as in pvtap audit).
        self.assertEqual(self.cell(self.at["faults"], "invascii.inverter_status.inverter_running"),
                         [])
        self.assertIn("= inverter running: True", self.text)

    def test_reply_split_after_its_first_byte_is_reassembled(self):
        a = self.at
        for piece in ("line_piece_1", "line_piece_2"):
            self.assertEqual(self.cell(a[piece], "invascii.station"), [])
        self.assertEqual(self.cell(a["line"], "invascii.request_in"), [str(a["line_req"])])

    def test_two_requests_in_one_segment_and_one_never_answered(self):
        a = self.at
        self.assertEqual(self.cell(a["power_reqs"], "invascii.station"), ["1", "2"])
        # The verdict is on the packet where the timeout became known; the request links to it.
        self.assertEqual(self.matching("invascii.timeout_in"), [a["power_reqs"]])
        announced = self.matching("invascii.unanswered")
        self.assertEqual(announced, [a["late_req"]])
        self.assertEqual(self.matching("invascii.unanswered_request == %d" % a["power_reqs"]),
                         announced)
        self.assertEqual(self.cell(a["power_reqs"], "invascii.response_in"), [str(a["power"])])

    def test_bad_checksum_between_noise(self):
        a = self.at
        self.assertEqual(self.cell(a["faults"], "invascii.checksum.status"), ["0"])
        good = ascii_reply(1, 0x0004, FAULTS)
        self.assertEqual(self.cell(a["faults"], "invascii.checksum.expected"),
                         ["0x" + good[-5:-1].decode()])
        self.assertEqual(self.cell(a["faults"], "invascii.noise"), ["00ff"])
        # The last byte may start a frame: it waits for the slave's next segment.
        self.assertEqual(self.cell(a["system"], "invascii.noise"), ["7e"])
        self.assertEqual(self.cell(a["faults"], "invascii.request_in"), [str(a["faults_req"])])
        self.assertIn(a["faults"], self.matching("invascii.checksum.bad"))
        self.assertEqual(self.cell(a["pv"], "invascii.checksum.status"), ["1"])

    def test_rtu_shaped_noise_is_plain_noise(self):
        noise = with_crc(bytes.fromhex("11 01 00 13 00 25")).hex()
        self.assertEqual(self.cell(self.at["faults_again"], "invascii.noise"), [noise])

    def test_no_dissector_bug_or_malformed_frame(self):
        self.assertNotIn("Dissector bug", self.text)
        self.assertNotIn("Malformed", self.text)

    def test_word_count_that_disagrees_with_the_request(self):
        a = self.at
        self.assertEqual(self.cell(a["system"], "invascii.expected_count"), ["2"])
        self.assertEqual(self.matching("invascii.count_mismatch"), [a["system"]])


if __name__ == "__main__":
    unittest.main()
