"""Link type 252 records for the dissector named "pvtap", as the analyzer writes them."""

import unittest

from bus_frames import (ascii_reply, ascii_request, gsl_read_reply, gsl_write_single,
                        hybrid_reply, rtu_read_request)
from pcap_writer import (LINKTYPE_WIRESHARK_UPPER_PDU, P2P_DIR_RECV, P2P_DIR_SENT, Pcap,
                         exported_pdu_record)
from tshark_runner import PluginTestCase

RECORDS = [
    # (name, bytes, direction tag or None)
    ("broadcast", bytes.fromhex("FF 11 10 60 00 02 6D 08"), P2P_DIR_SENT),
    ("info_bad", bytes.fromhex("06 11 08 31 00 00 67 31 00 00 67 93 3A"), P2P_DIR_RECV),
    ("info_good", bytes.fromhex("09 11 08 22 00 00 6B 22 00 00 6B F2 77"), P2P_DIR_RECV),
    ("gsl_req", rtu_read_request(1, 0x03, 1056, 1), P2P_DIR_SENT),
    ("gsl_rep", gsl_read_reply(1, [5002]), P2P_DIR_RECV),
    ("ascii_req", ascii_request(1, 0x0020, 2), P2P_DIR_SENT),
    ("ascii_rep", ascii_reply(1, 0x0020, [266, 57]), P2P_DIR_RECV),
    ("hybrid_req", rtu_read_request(6, 0x12, 0x1000, 0x24), None),
    ("hybrid_rep", hybrid_reply(6, 0x12, 0x31, 103, list(range(2200, 2236))), None),
    ("noise", b"\x00\x00\x13", None),
    ("gsl_write", gsl_write_single(1, 2010, 0x5555), P2P_DIR_SENT),
    ("write_unknown_side", gsl_write_single(2, 1250, 500), None),
    ("echo_unknown_side", gsl_write_single(2, 1250, 500), None),
    ("unpadded_name", rtu_read_request(3, 0x03, 1056, 1), P2P_DIR_SENT),
]


def records_capture():
    pcap = Pcap(LINKTYPE_WIRESHARK_UPPER_PDU)
    at = {}
    time = 100.0
    for name, payload, direction in RECORDS:
        time += 0.05
        pad = name != "unpadded_name"
        pcap.add(time, exported_pdu_record(payload, direction, pad=pad))
        at[name] = len(pcap.records)
    return pcap, at


class ExportedPduRecords(PluginTestCase, unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        super().setUpClass()
        pcap, cls.at = records_capture()
        cls.capture = cls.tshark.write("records.pcap", pcap)
        cls.names = ["frame.number", "frame.protocols", "invrtu.role", "invascii.role",
                     "invrtu.crc.status", "invrtu.request_in", "invascii.request_in",
                     "invrtu.gsl.grid_frequency", "invascii.pv_voltage",
                     "invrtu.hybrid.battery_voltage", "invrtu.noise", "invrtu.response_in"]
        cls.rows = {int(r[0][0]): r for r in cls.tshark.fields(cls.capture, cls.names)}

    def cell(self, name, field):
        return self.rows[self.at[name]][self.names.index(field)]

    def test_every_record_opens_dissected(self):
        self.assertEqual(len(self.rows), len(RECORDS))
        for name, _, _ in RECORDS:
            protocols = self.cell(name, "frame.protocols")[0]
            expected = "invascii" if name.startswith("ascii") else "invrtu"
            self.assertTrue(protocols.endswith(expected), (name, protocols))

    def test_direction_tag_gives_the_role(self):
        self.assertEqual(self.cell("gsl_req", "invrtu.role"), ["0"])
        self.assertEqual(self.cell("gsl_rep", "invrtu.role"), ["1"])
        self.assertEqual(self.cell("ascii_rep", "invascii.role"), ["1"])
        # The GSL write carries the request direction, so it is no echo.
        self.assertEqual(self.cell("gsl_write", "invrtu.role"), ["0"])

    def test_records_without_direction_are_read_by_their_structure(self):
        self.assertEqual(self.cell("hybrid_req", "invrtu.role"), ["0"])
        self.assertEqual(self.cell("hybrid_rep", "invrtu.role"), ["1"])
        self.assertEqual(self.cell("hybrid_rep", "invrtu.hybrid.battery_voltage"), ["220.6"])

    def test_matching_and_values_across_records(self):
        self.assertEqual(self.cell("gsl_rep", "invrtu.request_in"), [str(self.at["gsl_req"])])
        self.assertEqual(self.cell("gsl_rep", "invrtu.gsl.grid_frequency"), ["50.02"])
        self.assertEqual(self.cell("ascii_rep", "invascii.request_in"),
                         [str(self.at["ascii_req"])])
        self.assertEqual(self.cell("ascii_rep", "invascii.pv_voltage"), ["266"])
        self.assertEqual(self.cell("info_good", "invrtu.request_in"), [str(self.at["broadcast"])])
        self.assertEqual(self.cell("hybrid_req", "invrtu.response_in"),
                         [str(self.at["hybrid_rep"])])

    def test_crc_verdicts_of_the_reference_vectors(self):
        self.assertEqual(self.cell("info_bad", "invrtu.crc.status"), ["0"])
        self.assertEqual(self.cell("info_good", "invrtu.crc.status"), ["1"])

    def test_write_echo_without_direction_is_recognized_by_the_matcher(self):
        self.assertEqual(self.cell("write_unknown_side", "invrtu.role"), ["0"])
        self.assertEqual(self.cell("echo_unknown_side", "invrtu.role"), ["1"])
        self.assertEqual(self.cell("echo_unknown_side", "invrtu.request_in"),
                         [str(self.at["write_unknown_side"])])

    def test_dissector_name_without_padding(self):
        self.assertEqual(self.cell("unpadded_name", "invrtu.role"), ["0"])

    def test_noise_record(self):
        self.assertEqual(self.cell("noise", "invrtu.noise"), ["000013"])


if __name__ == "__main__":
    unittest.main()
