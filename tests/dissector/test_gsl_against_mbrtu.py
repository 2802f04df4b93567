"""The same GSL capture through invrtu and through Wireshark's own Modbus RTU dissector:
register values and CRC verdicts must agree."""

import os
import tomllib
import unittest

from bus_frames import gsl_read_reply, rtu_read_request, with_bad_crc, words_be
from pcap_writer import Pcap, TcpFlow
from tshark_runner import PluginTestCase

PORT = 4001
MAP_FILE = os.path.join(os.path.dirname(__file__), "..", "..", "protocols", "maps", "gsl.toml")
# Reads (start ID, count) covering numbers, pairs, bits, raw and signed registers.
READS = [(1050, 23), (1030, 4), (1073, 12), (1085, 11), (1050, 7), (1086, 4), (1250, 3),
         (1030, 4), (1060, 13)]
BAD_CRC_READS = {1, 4}  # indexes of READS whose reply is damaged on the line


def words_for(start, count):
    """Deterministic, varied register words; some above 0x8000 for the signed register."""
    return [(start * 7919 + i * 40503) & 0xFFFF for i in range(count)]


def build_capture():
    pcap = Pcap()
    flow = TcpFlow(pcap, server=("10.0.0.2", PORT))
    replies = []
    for index, (start, count) in enumerate(READS):
        flow.request(rtu_read_request(1, 0x03, start, count))
        words = words_for(start, count)
        if index in BAD_CRC_READS:
            data = words_be(words)
            flow.reply(with_bad_crc(bytes([1, 0x03, len(data)]) + data))
        else:
            flow.reply(gsl_read_reply(1, words))
        replies.append(len(pcap.records))
    return pcap, replies


def load_map():
    with open(MAP_FILE, "rb") as f:
        registers = tomllib.load(f)["register"]
    return {entry["address"]: entry for entry in registers}


def expected_value(entry, raw_words):
    """What invrtu must show for an entry, from the raw words Modbus RTU reports."""
    kind = entry.get("kind", "enum" if "values" in entry else "number")
    if kind in ("raw", "bits"):
        return ("int", raw_words[0])
    if kind != "number":
        return None
    raw = raw_words[0]
    if entry.get("words", 1) == 2:
        raw = raw_words[0] * 65536 + raw_words[1]
    elif entry.get("signed") and raw >= 0x8000:
        raw -= 0x10000
    return ("float", raw * entry.get("scale", 1.0))


class GslAgainstModbusRtu(PluginTestCase, unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        super().setUpClass()
        pcap, cls.replies = build_capture()
        cls.capture = cls.tshark.write("gsl.pcap", pcap)
        cls.registers = load_map()
        keys = ["invrtu.gsl." + e["key"] for e in cls.registers.values()]
        cls.ours = {int(r[0][0]): dict(zip(["crc"] + keys, r[1:]))
                    for r in cls.tshark.fields(cls.capture,
                                               ["frame.number", "invrtu.crc.status"] + keys,
                                               "invrtu")}
        mbrtu = ["-d", "tcp.port==%d,mbrtu" % PORT, "-o", "mbrtu.crc_verification:TRUE"]
        cls.theirs = {int(r[0][0]): r[1:] for r in cls.tshark.fields(
            cls.capture, ["frame.number", "mbrtu.crc16.status", "modbus.regnum16",
                          "modbus.regval_uint16"], "mbrtu", options=mbrtu)}

    def test_both_dissect_every_frame(self):
        self.assertEqual(len(self.ours), 2 * len(READS))
        self.assertEqual(sorted(self.ours), sorted(self.theirs))

    def test_crc_verdicts_agree(self):
        for packet, row in self.theirs.items():
            self.assertEqual(self.ours[packet]["crc"], row[0], "packet %d" % packet)
        bad = [p for p, row in self.theirs.items() if row[0] == ["0"]]
        self.assertEqual(bad, [self.replies[i] for i in sorted(BAD_CRC_READS)])

    def test_register_values_agree(self):
        compared = 0
        for index, packet in enumerate(self.replies):
            if index in BAD_CRC_READS:
                # Values are never decoded from a frame with a bad check (as in pvtap audit).
                shown = [v for key, v in self.ours[packet].items() if key != "crc" and v]
                self.assertEqual(shown, [], (packet, "values of a bad-CRC reply"))
                continue
            numbers, values = self.theirs[packet][1], self.theirs[packet][2]
            raw = dict(zip(map(int, numbers), map(int, values)))
            for address, entry in self.registers.items():
                width = entry.get("words", 1)
                if any(address + k not in raw for k in range(width)):
                    continue
                expected = expected_value(entry, [raw[address + k] for k in range(width)])
                if expected is None:
                    continue
                shown = self.ours[packet]["invrtu.gsl." + entry["key"]]
                self.assertEqual(len(shown), 1, (packet, entry["key"], shown))
                if expected[0] == "int":
                    self.assertEqual(int(shown[0], 0), expected[1], (packet, entry["key"]))
                else:
                    self.assertAlmostEqual(float(shown[0]), expected[1], places=6,
                                           msg=(packet, entry["key"]))
                compared += 1
        self.assertGreater(compared, 50)


if __name__ == "__main__":
    unittest.main()
