"""invrtu over TCP with no setup: GSL and Hybrid gateways found by the heuristics."""

import unittest

from bus_frames import (gsl_exception, gsl_read_reply, gsl_write_single, hybrid_reply,
                        rtu_read_request, with_bad_crc, with_crc)
from pcap_writer import Pcap, TcpFlow
from tshark_runner import PluginTestCase

GSL_WORDS = [2300, 2310, 2290, 100, 101, 102, 6001]  # IDs 1050..1056: 230.0 V ... 60.01 Hz
HYBRID_RUNNING = list(range(2200, 2200 + 0x24))       # 0x1006 battery voltage: 2206 -> 220.6 V

# Reference vectors of PROTOCOLS.md section 5 (Hybrid), as on the wire.
BROADCAST_INFO = bytes.fromhex("FF 11 10 60 00 02 6D 08")
INFO_REPLY_BAD = bytes.fromhex("06 11 08 31 00 00 67 31 00 00 67 93 3A")
INFO_REPLY_GOOD = bytes.fromhex("09 11 08 22 00 00 6B 22 00 00 6B F2 77")
WRITE_102A = bytes.fromhex("06 18 10 2A 09 3C 03 36")
WRITE_ECHO_BAD = bytes.fromhex("06 18 08 31 00 00 67 10 2A 09 3C 2A 86")
RESTORE = bytes.fromhex("06 1F 10 24 00 7B 91 57")
RESTORE_CONFIRM = bytes.fromhex("06 1F 08 31 00 00 67 10 24 00 7B BD F1")
ERROR_REPLY_BAD = bytes.fromhex("06 FF 08 31 00 00 67 10 00 00 FF F8 C3")
NOISE = bytes.fromhex("00 13 37")
# Modbus user-defined 0x41: no length rule, so it is found only between pinned ends.
USER_FUNCTION = with_crc(bytes.fromhex("01 41 00 13 00 25"))


def gsl_flow(pcap):
    """Station 1 to 3 behind a gateway on port 4001; returns the packet number of each step."""
    at = {}
    flow = TcpFlow(pcap, server=("10.0.0.2", 4001))

    def mark(name):
        at[name] = len(pcap.records)

    first = rtu_read_request(1, 0x03, 1050, 7)
    flow.request(first); mark("req_a")
    flow.reply(gsl_read_reply(1, GSL_WORDS), after=0.04); mark("rep_a")
    split = rtu_read_request(1, 0x03, 1050, 7)
    flow.request(split[:1]); mark("req_b_piece")
    flow.request(split[1:]); mark("req_b")
    reply = gsl_read_reply(1, GSL_WORDS)
    flow.reply(reply[:5]); mark("rep_b_piece")
    flow.reply(reply[5:]); mark("rep_b")
    flow.request(rtu_read_request(2, 0x03, 1050, 2) + rtu_read_request(3, 0x03, 1050, 2))
    mark("req_c_d")
    flow.reply(with_bad_crc(bytes([2, 0x03, 4, 0x08, 0xFC, 0x09, 0x06]))); mark("rep_c_bad")
    flow.request(rtu_read_request(1, 0x03, 1056, 1) + NOISE + rtu_read_request(4, 0x03, 1056, 1))
    mark("req_f_g")
    flow.reply(gsl_read_reply(1, [5000])); mark("rep_f")
    flow.reply(gsl_read_reply(4, [4990])); mark("rep_g")
    flow.request(rtu_read_request(1, 0x03, 2000, 1)); mark("req_h")
    flow.reply(gsl_exception(1, 0x03, 2)); mark("rep_h_exception")
    flow.request(gsl_write_single(1, 2010, 0x5555)); mark("write")
    flow.reply(gsl_write_single(1, 2010, 0x5555)); mark("echo")
    flow.reply(gsl_read_reply(5, [1])); mark("unsolicited")
    flow.request(rtu_read_request(1, 0x03, 1056, 1)); mark("req_dup")
    flow.reply(gsl_read_reply(1, [4999])); mark("rep_dup_1")
    flow.reply(gsl_read_reply(1, [4999])); mark("rep_dup_2")
    flow.request(USER_FUNCTION); mark("user_function")
    # Undecided bytes at a segment's end wait for that direction's next segment.
    flow.request(rtu_read_request(1, 0x03, 1056, 1)); mark("after_user_function")
    flow.reply(gsl_read_reply(1, [4998])); mark("rep_after_user_function")
    # Past station 3's reply timeout: the first packet after it announces the timeout.
    flow.request(rtu_read_request(1, 0x03, 1056, 1), after=1.5); mark("late_req")
    flow.reply(gsl_read_reply(1, [4997])); mark("late_rep")
    return at


def hybrid_flow(pcap):
    """Hybrid controllers behind a gateway on port 8899, with the reference's vectors."""
    at = {}
    flow = TcpFlow(pcap, client=("10.0.0.1", 50001), server=("10.0.0.3", 8899), time=5.0)

    def mark(name):
        at[name] = len(pcap.records)

    flow.request(BROADCAST_INFO); mark("broadcast")
    flow.reply(INFO_REPLY_BAD); mark("info_bad")
    flow.reply(INFO_REPLY_GOOD); mark("info_good")
    flow.request(WRITE_102A, after=1.5); mark("write")
    flow.reply(WRITE_ECHO_BAD); mark("echo_bad")
    flow.request(RESTORE); mark("restore")
    flow.reply(RESTORE_CONFIRM); mark("confirm")
    flow.request(rtu_read_request(6, 0x12, 0x1000, 0x24)); mark("read")
    reply = hybrid_reply(6, 0x12, 0x31, 103, HYBRID_RUNNING)
    flow.reply(reply[:30]); mark("read_piece_1")
    flow.reply(reply[30:60]); mark("read_piece_2")
    flow.reply(reply[60:]); mark("read_reply")
    flow.request(rtu_read_request(6, 0x12, 0x1000, 0x24)); mark("short_read")
    flow.reply(hybrid_reply(6, 0x12, 0x31, 103, HYBRID_RUNNING[:0x20])); mark("short_reply")
    flow.request(rtu_read_request(6, 0x16, 0x1024, 0x27)); mark("settings")
    flow.reply(ERROR_REPLY_BAD); mark("error_bad")
    return at


class RtuOverTcp(PluginTestCase, unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        super().setUpClass()
        pcap = Pcap()
        cls.gsl = gsl_flow(pcap)
        cls.hybrid = hybrid_flow(pcap)
        cls.capture = cls.tshark.write("rtu.pcap", pcap)
        fields = ["frame.number", "invrtu.station", "invrtu.function", "invrtu.role",
                  "invrtu.crc.status", "invrtu.crc.expected", "invrtu.request_in",
                  "invrtu.response_in", "invrtu.response_time", "invrtu.gsl.grid_frequency",
                  "invrtu.gsl.grid_voltage_ab", "invrtu.hybrid.battery_voltage",
                  "invrtu.device.type", "invrtu.device.serial", "invrtu.exception_code",
                  "invrtu.noise", "invrtu.count", "_ws.col.Info", "invrtu.expected_count",
                  "invrtu.dialect", "invrtu.unknown_function"]
        cls.names = fields
        cls.rows = {int(r[0][0]): r for r in cls.tshark.fields(cls.capture, fields)}

    def cell(self, packet, field):
        return self.rows[packet][self.names.index(field)]

    def packets_matching(self, display_filter):
        return [int(r[0][0]) for r in self.tshark.fields(self.capture, ["frame.number"],
                                                          display_filter)]

    def test_gsl_frames_are_found_without_any_setting(self):
        g = self.gsl
        self.assertEqual(self.cell(g["req_a"], "invrtu.station"), ["1"])
        self.assertEqual(self.cell(g["req_a"], "invrtu.dialect"), ["2"])
        self.assertEqual(self.cell(g["rep_a"], "invrtu.gsl.grid_frequency"), ["60.01"])
        self.assertEqual(self.cell(g["rep_a"], "invrtu.gsl.grid_voltage_ab"), ["230"])

    def test_direction_comes_from_the_gateway_side(self):
        g = self.gsl
        self.assertEqual(self.cell(g["req_a"], "invrtu.role"), ["0"])
        self.assertEqual(self.cell(g["rep_a"], "invrtu.role"), ["1"])
        # A GSL write and its echo are byte for byte the same: only the side tells them apart.
        self.assertEqual(self.cell(g["write"], "invrtu.role"), ["0"])
        self.assertEqual(self.cell(g["echo"], "invrtu.role"), ["1"])
        self.assertEqual(self.cell(g["echo"], "invrtu.request_in"), [str(g["write"])])

    def test_frame_split_after_its_first_byte_is_reassembled(self):
        g = self.gsl
        self.assertEqual(self.cell(g["req_b_piece"], "invrtu.station"), [])
        self.assertEqual(self.cell(g["req_b"], "invrtu.station"), ["1"])
        self.assertEqual(self.cell(g["req_b"], "invrtu.count"), ["7"])
        self.assertEqual(self.cell(g["rep_b_piece"], "invrtu.station"), [])
        self.assertEqual(self.cell(g["rep_b"], "invrtu.gsl.grid_frequency"), ["60.01"])
        self.assertEqual(self.cell(g["rep_b"], "invrtu.request_in"), [str(g["req_b"])])

    def test_segment_with_two_frames_shows_both(self):
        g = self.gsl
        self.assertEqual(self.cell(g["req_c_d"], "invrtu.station"), ["2", "3"])
        info = self.cell(g["req_c_d"], "_ws.col.Info")
        self.assertIn("read holding registers request, station 2 | read holding registers "
                      "request, station 3", "|".join(info))

    def test_noise_between_frames_swallows_neither(self):
        g = self.gsl
        self.assertEqual(self.cell(g["req_f_g"], "invrtu.station"), ["1", "4"])
        self.assertEqual(self.cell(g["req_f_g"], "invrtu.noise"), ["001337"])
        self.assertIn(g["req_f_g"], self.packets_matching("invrtu.noise_run"))
        self.assertEqual(self.cell(g["rep_g"], "invrtu.request_in"), [str(g["req_f_g"])])

    def test_bad_crc_is_flagged_with_the_expected_value(self):
        g = self.gsl
        self.assertEqual(self.cell(g["rep_c_bad"], "invrtu.crc.status"), ["0"])
        expected = with_crc(bytes([2, 0x03, 4, 0x08, 0xFC, 0x09, 0x06]))[-2:]
        self.assertEqual(self.cell(g["rep_c_bad"], "invrtu.crc.expected"),
                         ["0x%04x" % (expected[0] | expected[1] << 8)])
        self.assertEqual(self.cell(g["rep_a"], "invrtu.crc.status"), ["1"])
        bad = self.packets_matching("invrtu.crc.bad")
        self.assertIn(g["rep_c_bad"], bad)
        self.assertNotIn(g["rep_a"], bad)

    def test_requests_and_replies_link_to_each_other(self):
        g = self.gsl
        self.assertEqual(self.cell(g["req_a"], "invrtu.response_in"), [str(g["rep_a"])])
        self.assertEqual(self.cell(g["rep_a"], "invrtu.request_in"), [str(g["req_a"])])
        # From the request's end to the reply's first byte, as pvtap audit measures it: the
        # reply's 19 bytes were on the wire before its segment was stamped 40 ms later.
        self.assertAlmostEqual(float(self.cell(g["rep_a"], "invrtu.response_time")[0]),
                               0.04 - 19 * 10 / 9600, places=6)
        self.assertEqual(self.cell(g["req_c_d"], "invrtu.response_in"), [str(g["rep_c_bad"])])

    def test_unanswered_request_is_announced_where_its_timeout_became_known(self):
        g = self.gsl
        # The expert is on the packet that announced it (the same in one pass and in two); the
        # request links to that packet.
        announced = self.packets_matching("invrtu.unanswered && invrtu.station == 3")
        self.assertEqual(announced, [g["late_req"]])
        self.assertIn("no reply to frame %d" % g["req_c_d"],
                      "|".join(self.cell(g["late_req"], "_ws.col.Info")))
        self.assertEqual(self.packets_matching("invrtu.unanswered_request == %d" % g["req_c_d"]),
                         announced)
        self.assertEqual(self.packets_matching("invrtu.timeout_in && invrtu.station == 3"),
                         [g["req_c_d"]])
        self.assertNotIn(g["req_a"], self.packets_matching("invrtu.timeout_in"))

    def test_reply_with_no_request(self):
        g = self.gsl
        self.assertEqual(self.packets_matching("invrtu.unsolicited"), [g["unsolicited"]])
        self.assertEqual(self.cell(g["unsolicited"], "invrtu.request_in"), [])

    def test_bad_crc_reply_shows_its_data_as_not_decoded(self):
        g = self.gsl
        self.assertIn(g["rep_c_bad"], self.packets_matching("invrtu.undecoded"))
        self.assertNotIn(g["rep_a"], self.packets_matching("invrtu.undecoded"))
        self.assertEqual(self.packets_matching("invrtu.undecoded == 08:fc:09:06"), [g["rep_c_bad"]])

    def test_duplicate_reply(self):
        g = self.gsl
        self.assertIn("(duplicate)", self.cell(g["rep_dup_2"], "_ws.col.Info")[0])
        self.assertNotIn("(duplicate)", self.cell(g["rep_dup_1"], "_ws.col.Info")[0])
        self.assertEqual(self.packets_matching("invrtu.duplicate"), [g["rep_dup_2"]])
        self.assertEqual(self.cell(g["req_dup"], "invrtu.response_in"), [str(g["rep_dup_1"])])

    def test_frame_of_a_user_defined_function_code(self):
        # Pinned by the frames around it and its CRC: a frame of that code, never noise.
        g = self.gsl
        self.assertEqual(self.packets_matching("invrtu.function == 0x41"),
                         [g["after_user_function"]])
        self.assertEqual(self.packets_matching("invrtu.unknown_function_frame"), [])
        self.assertEqual(self.packets_matching("invrtu.noise && frame.number >= %d"
                                               % g["user_function"]), [])

    def test_exception_reply(self):
        g = self.gsl
        self.assertEqual(self.cell(g["rep_h_exception"], "invrtu.exception_code"), ["2"])
        self.assertEqual(self.cell(g["rep_h_exception"], "invrtu.function"), ["0x83"])
        self.assertEqual(self.cell(g["rep_h_exception"], "invrtu.request_in"), [str(g["req_h"])])

    def test_hybrid_reference_vectors_keep_their_crc_verdicts(self):
        h = self.hybrid
        verdicts = {name: self.cell(h[name], "invrtu.crc.status")
                    for name in ["broadcast", "info_bad", "info_good", "write", "echo_bad",
                                 "restore", "confirm", "error_bad"]}
        self.assertEqual(verdicts, {"broadcast": ["1"], "info_bad": ["0"], "info_good": ["1"],
                                    "write": ["1"], "echo_bad": ["0"], "restore": ["1"],
                                    "confirm": ["1"], "error_bad": ["0"]})
        self.assertEqual(self.cell(h["info_bad"], "invrtu.crc.expected"), ["0xfa97"])
        self.assertEqual(self.cell(h["echo_bad"], "invrtu.crc.expected"), ["0x8a2b"])
        self.assertEqual(self.cell(h["error_bad"], "invrtu.crc.expected"), ["0xcff9"])

    def test_hybrid_broadcast_is_answered_by_each_station(self):
        h = self.hybrid
        self.assertEqual(self.cell(h["info_bad"], "invrtu.request_in"), [str(h["broadcast"])])
        self.assertEqual(self.cell(h["info_good"], "invrtu.request_in"), [str(h["broadcast"])])
        self.assertEqual(self.cell(h["info_good"], "invrtu.device.type"), ["0x22"])
        self.assertEqual(self.cell(h["info_good"], "invrtu.device.serial"), ["107"])

    def test_hybrid_reply_split_in_three_is_reassembled_and_decoded(self):
        h = self.hybrid
        for piece in ("read_piece_1", "read_piece_2"):
            self.assertEqual(self.cell(h[piece], "invrtu.station"), [])
        self.assertEqual(self.cell(h["read_reply"], "invrtu.hybrid.battery_voltage"), ["220.6"])
        self.assertEqual(self.cell(h["read_reply"], "invrtu.request_in"), [str(h["read"])])

    def test_byte_count_that_disagrees_with_the_request(self):
        h = self.hybrid
        self.assertEqual(self.cell(h["short_reply"], "invrtu.expected_count"), ["76"])
        self.assertEqual(self.packets_matching("invrtu.count_mismatch"), [h["short_reply"]])

    def test_check_verification_can_be_turned_off(self):
        rows = self.tshark.fields(self.capture, ["invrtu.crc.status"], "invrtu",
                                  options=["-o", "invrtu.verify_crc:FALSE"])
        statuses = {s for row in rows for s in row[0]}
        self.assertEqual(statuses, {"2"})
        self.assertEqual(self.tshark.fields(self.capture, ["frame.number"], "invrtu.crc.bad",
                                            options=["-o", "invrtu.verify_crc:FALSE"]), [])

    def test_no_dissector_bug_or_malformed_frame(self):
        text = self.tshark.verbose(self.capture)
        self.assertIn("Inverter RTU protocol", text)
        self.assertNotIn("Dissector bug", text)
        self.assertNotIn("Malformed", text)

    def test_every_frame_is_found(self):
        frames = sum(len(r[self.names.index("invrtu.function")]) for r in self.rows.values())
        # GSL: 24 frames (two segments hold two each; the user-defined 0x41 request is one);
        # Hybrid: 13 frames.
        self.assertEqual(frames, 37)


class RtuOnConfiguredPort(PluginTestCase, unittest.TestCase):
    """A port preference binds the gateway side from the first byte, heuristics off."""

    def test_port_preference_without_heuristics(self):
        pcap = Pcap()
        flow = TcpFlow(pcap, server=("10.0.0.9", 5020))
        request = rtu_read_request(1, 0x03, 1050, 7)
        flow.request(request[:1])
        flow.request(request[1:])
        flow.reply(gsl_read_reply(1, GSL_WORDS))
        capture = self.tshark.write("port.pcap", pcap)
        options = ["--disable-heuristic", "invrtu_tcp", "-o", "invrtu.tcp.port:5020"]
        rows = self.tshark.fields(capture, ["frame.number", "invrtu.role",
                                            "invrtu.gsl.grid_frequency", "invrtu.request_in"],
                                  "invrtu", options)
        self.assertEqual(rows, [[["5"], ["0"], [], []], [["6"], ["1"], ["60.01"], ["5"]]])
        unbound = self.tshark.fields(capture, ["frame.number"], "invrtu",
                                     ["--disable-heuristic", "invrtu_tcp"])
        self.assertEqual(unbound, [])


if __name__ == "__main__":
    unittest.main()
