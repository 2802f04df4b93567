"""invrtu on plain Modbus RTU devices behind a gateway: coils, diagnostics, device names,
masks, FIFO, exceptions with Modbus texts, quantity findings, and no claim on Modbus/TCP."""

import struct
import unittest

from bus_frames import with_crc
from pcap_writer import Pcap, TcpFlow
from tshark_runner import PluginTestCase


def frame(hex_text):
    return with_crc(bytes.fromhex(hex_text))


def text_bytes(text):
    return text.encode("ascii").hex()


# Station 20: a meter that names itself by device identification.
COILS_REQUEST = frame("14 01 0011 0011")        # 17 coils from 17
COILS_REPLY = frame("14 01 03 CD 6B 01")        # coil 17 on, 18 off, 19 on, 20 on ...
IDENT_REQUEST = frame("14 2B 0E 01 00")
IDENT_REPLY = frame("14 2B 0E 01 01 00 00 03 00 04" + text_bytes("ACME") + "01 05" +
                    text_bytes("PM100") + "02 04" + text_bytes("v1.2"))
DIAG_REQUEST = frame("14 08 0000 1234")         # return query data
TOO_MANY_COILS = frame("14 01 0000 0BB8")       # 3000 coils: the specification allows 2000
EXCEPTION_03 = frame("14 81 03")
MASK_WRITE = frame("14 16 0004 00F2 0025")
READ_WRITE = frame("14 17 0003 0006 000E 0003 06 00FF 00FE 00FD")
READ_WRITE_REPLY = frame("14 17 0C" + "0001" * 6)
FIFO_REQUEST = frame("14 18 04DE")
FIFO_REPLY = frame("14 18 0006 0002 01B8 1284")
READ_REGISTERS = frame("14 03 0100 0001")
ADDRESS_EXCEPTION = frame("14 83 02")
# Station 21 names itself by report server ID.
SERVER_ID_REQUEST = frame("15 11")
SERVER_ID_REPLY = frame("15 11 09 2A FF" + text_bytes("METER21"))


def modbus_flow(pcap, server=("10.0.0.7", 4001)):
    """A gateway with plain Modbus devices; returns the packet number of each step."""
    at = {}
    flow = TcpFlow(pcap, client=("10.0.0.1", 50007), server=server)

    def step(name, payload, reply=False):
        (flow.reply if reply else flow.request)(payload)
        at[name] = len(pcap.records)

    step("coils_req", COILS_REQUEST)
    step("coils_rep", COILS_REPLY, True)
    step("diag_req", DIAG_REQUEST)
    step("diag_echo", DIAG_REQUEST, True)
    step("too_many", TOO_MANY_COILS)
    step("too_many_exc", EXCEPTION_03, True)
    step("ident_req", IDENT_REQUEST)
    step("ident_rep", IDENT_REPLY, True)
    step("coils_req_2", COILS_REQUEST)
    step("coils_rep_2", COILS_REPLY, True)
    step("mask", MASK_WRITE)
    step("mask_echo", MASK_WRITE, True)
    step("rw", READ_WRITE)
    step("rw_rep", READ_WRITE_REPLY, True)
    step("fifo", FIFO_REQUEST)
    step("fifo_rep", FIFO_REPLY, True)
    step("read", READ_REGISTERS)
    step("read_exc", ADDRESS_EXCEPTION, True)
    step("sid_req", SERVER_ID_REQUEST)
    step("sid_rep", SERVER_ID_REPLY, True)
    step("sid_after", frame("15 01 0000 0008"))
    step("sid_after_rep", frame("15 01 01 81"), True)
    return at


FIELDS = ["frame.number", "invrtu.station", "invrtu.function", "invrtu.dialect",
          "invrtu.coil.address", "invrtu.coil.state", "invrtu.diagnostics.sub_function",
          "invrtu.device_id.vendor", "invrtu.device_id.product", "invrtu.device_id.revision",
          "invrtu.device_id.object", "invrtu.station_name", "invrtu.exception_code",
          "invrtu.and_mask", "invrtu.or_mask", "invrtu.write_start", "invrtu.write_count",
          "invrtu.byte_count", "invrtu.fifo.count", "invrtu.fifo.value", "invrtu.server_id.text",
          "invrtu.quantity.max", "_ws.col.Info", "invrtu.request_in", "invrtu.response_in",
          "invrtu.word"]


class ModbusDevices(PluginTestCase, unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        super().setUpClass()
        pcap = Pcap()
        cls.at = modbus_flow(pcap)
        cls.capture = cls.tshark.write("modbus.pcap", pcap)
        cls.rows = {int(r[0][0]): r for r in cls.tshark.fields(cls.capture, FIELDS)}

    def cell(self, packet, field):
        return self.rows[self.at[packet]][FIELDS.index(field)]

    def info(self, packet):
        return "|".join(self.cell(packet, "_ws.col.Info"))

    def test_coils_are_addressed_bits(self):
        self.assertEqual(self.cell("coils_rep", "invrtu.coil.address"),
                         [str(a) for a in range(17, 34)])
        # 0xCD 0x6B 0x01, bit 0 of the first byte first
        bits = [(0xCD >> i) & 1 for i in range(8)] + [(0x6B >> i) & 1 for i in range(8)] + [1]
        self.assertEqual(self.cell("coils_rep", "invrtu.coil.state"),
                         ["1" if b else "0" for b in bits])
        self.assertEqual(self.info("coils_rep"), "read coils response, station 20: 17 coils from 17")
        self.assertEqual(self.info("coils_req"), "read coils request, station 20: 17 coils from 17")

    def test_diagnostics_sub_function(self):
        self.assertEqual(self.cell("diag_req", "invrtu.diagnostics.sub_function"), ["0x0000"])
        self.assertIn("return query data", self.info("diag_req"))
        self.assertEqual(self.cell("diag_echo", "invrtu.request_in"), [str(self.at["diag_req"])])

    def test_device_identification_objects(self):
        self.assertEqual(self.cell("ident_rep", "invrtu.device_id.vendor"), ["ACME"])
        self.assertEqual(self.cell("ident_rep", "invrtu.device_id.product"), ["PM100"])
        self.assertEqual(self.cell("ident_rep", "invrtu.device_id.revision"), ["v1.2"])
        self.assertEqual(self.cell("ident_rep", "invrtu.device_id.object"), ["0x00", "0x01", "0x02"])

    def test_station_named_after_it_named_itself(self):
        self.assertEqual(self.cell("coils_req", "invrtu.station_name"), [])
        self.assertEqual(self.cell("ident_rep", "invrtu.station_name"), ["ACME PM100 v1.2"])
        self.assertEqual(self.cell("coils_rep_2", "invrtu.station_name"), ["ACME PM100 v1.2"])
        self.assertIn("station 20 (ACME PM100 v1.2)", self.info("coils_rep_2"))
        self.assertEqual(self.cell("sid_rep", "invrtu.server_id.text"), ["METER21"])
        self.assertEqual(self.cell("sid_after", "invrtu.station_name"), ["METER21"])
        self.assertEqual(self.cell("sid_req", "invrtu.station_name"), [])

    def test_exceptions_read_as_modbus_names_them(self):
        self.assertEqual(self.cell("read_exc", "invrtu.exception_code"), ["2"])
        self.assertIn("illegal data address", self.info("read_exc"))
        self.assertIn("illegal data value", self.info("too_many_exc"))

    def test_quantity_out_of_range(self):
        self.assertEqual(self.cell("too_many", "invrtu.quantity.max"), ["2000"])
        self.assertEqual(self.cell("coils_req", "invrtu.quantity.max"), [])
        found = [int(r[0][0]) for r in self.tshark.fields(self.capture, ["frame.number"],
                                                          "invrtu.quantity_out_of_range")]
        self.assertEqual(found, [self.at["too_many"]])

    def test_masks_read_write_and_fifo(self):
        self.assertEqual(self.cell("mask", "invrtu.and_mask"), ["0x00f2"])
        self.assertEqual(self.cell("mask", "invrtu.or_mask"), ["0x0025"])
        self.assertEqual(self.cell("rw", "invrtu.write_start"), ["0x000e"])
        self.assertEqual(self.cell("rw", "invrtu.write_count"), ["3"])
        self.assertEqual(self.cell("rw", "invrtu.byte_count"), ["6"])
        self.assertEqual(self.cell("fifo_rep", "invrtu.fifo.count"), ["2"])
        self.assertEqual(self.cell("fifo_rep", "invrtu.fifo.value"), ["0x01b8", "0x1284"])
        self.assertIn("2 values in the FIFO", self.info("fifo_rep"))

    def test_one_pass_shows_what_two_passes_show(self):
        args = ["-r", self.capture, "-T", "fields", "-E", "occurrence=a", "-E", "aggregator=|"]
        for field in FIELDS:
            args += ["-e", field]
        one = self.tshark.run(args).stdout.splitlines()
        two = self.tshark.run(["-2"] + args).stdout.splitlines()
        # A request's link to its reply needs a later pass; every other field agrees.
        links = FIELDS.index("invrtu.response_in")
        strip = lambda rows: [[c for i, c in enumerate(r.split("\t")) if i != links] for r in rows]
        self.assertEqual(strip(one), strip(two))
        self.assertTrue(any("ACME PM100 v1.2" in r for r in one))

    def test_no_dissector_bug_or_malformed_frame(self):
        for passes in ([], ["-2"]):
            out = self.tshark.run(["-r", self.capture, "-V"] + passes).stdout
            self.assertNotIn("Dissector bug", out)
            self.assertNotIn("Malformed", out)
            self.assertIn("coil 17: on", out)


def crc16(data):
    crc = 0xFFFF
    for byte in data:
        crc ^= byte
        for _ in range(8):
            crc = (crc >> 1) ^ 0xA001 if crc & 1 else crc >> 1
    return crc


def mbap_that_reads_as_rtu():
    """A Modbus/TCP read request whose first 8 bytes are also an RTU read request with a good
    CRC: transaction id = RTU station and function, protocol id and length = start and count,
    unit id and function code = the CRC. Only a rule that knows MBAP keeps invrtu off it."""
    for tid in range(0x0100, 0x10000):
        if tid & 0xFF not in (0x01, 0x02, 0x03, 0x04):
            continue
        head = struct.pack(">HHH", tid, 0, 6)
        crc = crc16(head)
        if crc >> 8 in (0x01, 0x02, 0x04):  # the MBAP function code: a read
            unit = crc & 0xFF
            return tid, head + bytes([unit, crc >> 8]) + struct.pack(">HH", 0, 10)
    raise AssertionError("no such transaction id")


def mbap_flow(pcap, port, client_port):
    tid, request = mbap_that_reads_as_rtu()
    flow = TcpFlow(pcap, client=("10.0.1.1", client_port), server=("10.0.1.2", port))
    unit, function = request[6], request[7]
    reply_pdu = bytes([unit, function, 20]) + bytes(range(20))
    for i in range(3):
        flow.request(request)
        flow.reply(struct.pack(">HHH", tid, 0, len(reply_pdu)) + reply_pdu)


class ModbusTcpIsLeftToMbtcp(PluginTestCase, unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        super().setUpClass()
        pcap = Pcap()
        mbap_flow(pcap, 502, 50100)
        mbap_flow(pcap, 5020, 50101)
        modbus_flow(pcap, server=("10.0.1.9", 4001))
        cls.capture = cls.tshark.write("mbap.pcap", pcap)

    def protocols_by_port(self, passes):
        rows = self.tshark.run(["-r", self.capture, "-T", "fields", "-e", "tcp.srcport", "-e",
                                "tcp.dstport", "-e", "frame.protocols", "-Y", "tcp.len > 0"]
                               + passes).stdout.splitlines()
        by_port = {}
        for row in rows:
            src, dst, protocols = row.split("\t")
            port = min(int(src), int(dst))
            by_port.setdefault(port, set()).update(protocols.split(":"))
        return by_port

    def test_the_forged_request_has_a_good_rtu_crc(self):
        _, request = mbap_that_reads_as_rtu()
        self.assertEqual(crc16(request[:6]), request[6] | request[7] << 8)

    def test_mbap_is_never_invrtu_and_rtu_is(self):
        for passes in ([], ["-2"]):
            by_port = self.protocols_by_port(passes)
            self.assertNotIn("invrtu", by_port[502])
            self.assertIn("mbtcp", by_port[502])
            self.assertNotIn("invrtu", by_port[5020])
            self.assertIn("invrtu", by_port[4001])


if __name__ == "__main__":
    unittest.main()
