"""invmbap: Modbus/TCP read with pvtap's maps and verdicts when the user asks for it by Decode
As (or the invmbap.tcp.port preference); without that, port 502 stays Wireshark's mbtcp."""

import struct
import unittest

import mbap_capture
from pcap_writer import Pcap, TcpFlow
from tshark_runner import PluginTestCase

DECODE_AS = ["-d", "tcp.port==502,invmbap"]
FIELDS = ["invmbap.transaction", "invrtu.station", "invrtu.function", "invrtu.response_time",
          "invrtu.request_in", "invrtu.exception_code", "invrtu.crc.status"]


def lying_header_flow(pcap):
    """A client whose second ADU says protocol id 1."""
    flow = TcpFlow(pcap, client=("10.0.0.1", 50210), server=("10.0.0.10", 502), time=200.0)
    flow.request(mbap_capture.adu(1, 1, mbap_capture.read_request(0, 1)))
    flow.reply(mbap_capture.adu(1, 1, mbap_capture.read_reply([4])))
    flow.request(struct.pack("!HHHB", 2, 1, 6, 1) + mbap_capture.read_request(0, 1))


def silent_request_flow(pcap):
    """Unit 3 never answers tid 2; the client polls on for 15 s, past the 10 s a request is
    held for its reply, so that the silence is decided inside the capture."""
    flow = TcpFlow(pcap, client=("10.0.0.1", 50230), server=("10.0.0.12", 502), time=300.0)
    flow.request(mbap_capture.adu(1, 3, mbap_capture.read_request(0, 1)))
    flow.reply(mbap_capture.adu(1, 3, mbap_capture.read_reply([1])), after=0.02)
    flow.request(mbap_capture.adu(2, 3, mbap_capture.read_request(0, 1)), after=1.0)
    for tid in range(3, 18):
        flow.request(mbap_capture.adu(tid, 3, mbap_capture.read_request(0, 1)), after=1.0)
        flow.reply(mbap_capture.adu(tid, 3, mbap_capture.read_reply([tid])), after=0.02)


class ModbusTcpByDecodeAs(PluginTestCase, unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        super().setUpClass()
        cls.capture = cls.tshark.path("mbap.pcap")
        mbap_capture.build(cls.capture, lying_length=False)
        cls.on_1502 = cls.tshark.path("mbap_1502.pcap")
        mbap_capture.build(cls.on_1502, port=1502, lying_length=False)
        pcap = Pcap()
        lying_header_flow(pcap)
        cls.liar = cls.tshark.write("liar.pcap", pcap)
        pcap = Pcap()
        silent_request_flow(pcap)
        cls.silent = cls.tshark.write("silent.pcap", pcap)

    def rows(self, capture, options, passes=("-2",)):
        args = ["-r", capture, *passes, "-T", "fields", "-E", "occurrence=a", "-E",
                "aggregator=|", "-Y", "invmbap"] + list(options)
        for field in FIELDS:
            args += ["-e", field]
        return [line.split("\t") for line in self.tshark.run(args).stdout.splitlines()]

    def test_mbtcp_keeps_port_502_by_default(self):
        protocols = self.tshark.run(["-r", self.capture, "-T", "fields", "-e", "frame.protocols",
                                     "-Y", "tcp.len > 0"]).stdout.splitlines()
        layers = [p.split(":") for p in protocols]
        # Every data segment but the first half of the split ADU (which waits for its second).
        self.assertEqual(sum("mbtcp" in p for p in layers), len(layers) - 1)
        for p in layers:
            self.assertNotIn("invrtu", p)
            self.assertNotIn("invmbap", p)

    def test_every_adu_is_a_frame_with_its_check_not_present(self):
        rows = self.rows(self.capture, DECODE_AS)
        tids = [t for row in rows for t in row[0].split("|")]
        # Each transaction's request and reply; 11 got no reply.
        self.assertEqual(sorted(map(int, tids)),
                         [1, 1, 2, 2, 3, 3, 4, 4, 5, 5, 7, 7, 8, 8, 9, 9, 10, 10, 11, 12, 12])
        statuses = {s for row in rows for s in row[6].split("|")}
        self.assertEqual(statuses, {"3"})  # Wireshark's "Not present"

    def test_pipelined_replies_pair_by_transaction_id(self):
        rows = self.rows(self.capture, DECODE_AS)
        replies = [row for row in rows if row[3]]
        latencies = [round(float(r[3]) * 1000, 3) for r in replies[:3]]
        self.assertEqual(latencies, [40.0, 55.0, 40.0])  # as pvtap audit measures them

    def test_exceptions_and_the_gateways_0x0b(self):
        codes = [row[5] for row in self.rows(self.capture, DECODE_AS) if row[5]]
        self.assertEqual(codes, ["2", "11"])

    def test_one_pass_shows_what_two_passes_show(self):
        self.assertEqual(self.rows(self.capture, DECODE_AS, passes=()),
                         self.rows(self.capture, DECODE_AS))

    def test_the_port_preference_on_another_port(self):
        rows = self.rows(self.on_1502, ["-o", "invmbap.tcp.port:1502"])
        self.assertEqual(len(rows), len(self.rows(self.capture, DECODE_AS)))

    def test_a_header_that_lied_is_an_expert_finding(self):
        out = self.tshark.run(["-r", self.liar, "-2", *DECODE_AS, "-T", "fields", "-e",
                               "_ws.expert.message", "-Y", "invmbap"]).stdout
        self.assertIn("MBAP header that lied (protocol id not 0, or a length that does not "
                      "fit): 12 bytes skipped", out)

    def test_a_request_never_answered_is_announced_in_one_pass_and_two(self):
        # pvtap audit counts it as one timeout; the plugin announces it in the packet whose
        # time decided it, naming the request's packet, the same in one pass and two.
        for passes in ((), ("-2",)):
            out = self.tshark.run(["-r", self.silent, *passes, *DECODE_AS, "-T", "fields",
                                   "-e", "invrtu.unanswered_request", "-e", "_ws.expert.message",
                                   "-Y", "invrtu.unanswered_request"]).stdout.splitlines()
            self.assertEqual(len(out), 1, passes)
            request_packet = out[0].split("\t")[0]
            tid = self.tshark.run(["-r", self.silent, "-T", "fields", *DECODE_AS,
                                   "-e", "invmbap.transaction", "-Y",
                                   "frame.number == " + request_packet]).stdout.strip()
            self.assertEqual(tid, "2", passes)


if __name__ == "__main__":
    unittest.main()
