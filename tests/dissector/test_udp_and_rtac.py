"""Datagram transports: UDP found by the heuristic; RTAC serial payloads, claimed by default."""

import struct
import unittest

from bus_frames import ascii_reply, ascii_request, gsl_read_reply, rtu_read_request
from pcap_writer import Pcap, udp_packet
from tshark_runner import PluginTestCase

LINKTYPE_RTAC_SERIAL = 250


def rtac_record(pcap, time, event, payload):
    pcap.add(time, struct.pack("!IIBBH", int(time), 0, event, 0, 0) + payload)


class DatagramTransports(PluginTestCase, unittest.TestCase):
    def test_udp_heuristic(self):
        pcap = Pcap()
        gateway = ("10.0.0.5", 26001)
        master = ("10.0.0.1", 40000)
        udp_packet(pcap, 1.00, ascii_request(1, 0x0050, 7), master, gateway)
        udp_packet(pcap, 1.05, ascii_reply(1, 0x0050, [217, 0, 0, 65, 0, 0, 601]), gateway, master)
        udp_packet(pcap, 1.10, rtu_read_request(1, 0x03, 1056, 1), master, gateway)
        capture = self.tshark.write("udp.pcap", pcap)
        rows = self.tshark.fields(capture, ["frame.number", "invascii.role",
                                            "invascii.line_frequency", "invascii.request_in",
                                            "invrtu.station"])
        self.assertEqual(rows[0][1], ["0"])
        self.assertEqual(rows[1][1:4], [["1"], ["60.1"], ["1"]])
        # The UDP flow is bound to invascii, but one gateway may carry ASCII and RTU stations:
        # the RTU frame in it is shown by invrtu.
        self.assertEqual(rows[2][4], ["1"])

    def test_a_station_that_turns_to_ascii_is_shown_without_invrtus_own_items(self):
        # Fuzz finding 11: the dialect change of a frame that invascii shows named invrtu's
        # expert info and field, which invascii never registered (a dissector bug).
        pcap = Pcap()
        gateway = ("10.0.0.5", 26001)
        master = ("10.0.0.1", 40000)
        udp_packet(pcap, 1.00, rtu_read_request(1, 0x03, 1056, 1), master, gateway)
        udp_packet(pcap, 1.05, gsl_read_reply(1, [7]), gateway, master)
        udp_packet(pcap, 2.00, ascii_request(1, 0x0050, 7), master, gateway)
        udp_packet(pcap, 2.05, ascii_reply(1, 0x0050, [217, 0, 0, 65, 0, 0, 601]), gateway, master)
        capture = self.tshark.write("turns_to_ascii.pcap", pcap)
        shown = self.tshark.verbose(capture)
        self.assertNotIn("Dissector bug", shown)
        self.assertNotIn("Unregistered", shown)
        rows = self.tshark.fields(capture, ["invascii.role", "invascii.line_frequency"])
        self.assertEqual(rows[3], [["1"], ["60.1"]])

    def test_rtac_serial_payloads_are_one_bus_reassembled_across_records(self):
        pcap = Pcap(LINKTYPE_RTAC_SERIAL)
        rtac_record(pcap, 2.00, 1, rtu_read_request(1, 0x03, 1056, 1))
        reply = gsl_read_reply(1, [4998])
        rtac_record(pcap, 2.04, 2, reply[:4])
        rtac_record(pcap, 2.045, 2, reply[4:])
        capture = self.tshark.write("rtac.pcap", pcap)
        fields = ["invrtu.role", "invrtu.gsl.grid_frequency", "invrtu.request_in"]
        for passes in ([], ["-2"]):
            rows = [r for r in self.tshark.run(passes + ["-r", capture, "-T", "fields"] + sum(
                (["-e", f] for f in fields), [])).stdout.splitlines()]
            self.assertEqual(rows, ["0\t\t", "\t\t", "1\t49.98\t1"], passes)
        # Decode As still chooses: invrtu itself takes each payload as a datagram of its own.
        rows = self.tshark.fields(capture, ["invrtu.role", "invrtu.noise"],
                                  options=["-d", "rtacser.data,invrtu"])
        self.assertEqual(rows[1], [[], ["01030213"]])


if __name__ == "__main__":
    unittest.main()
