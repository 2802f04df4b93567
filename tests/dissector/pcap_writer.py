"""Writes classic pcap files: Ethernet/IPv4 TCP and UDP flows, and exported-PDU records."""

import struct

LINKTYPE_ETHERNET = 1
LINKTYPE_WIRESHARK_UPPER_PDU = 252

EXP_PDU_TAG_END_OF_OPT = 0
EXP_PDU_TAG_DISSECTOR_NAME = 12
EXP_PDU_TAG_P2P_DIRECTION = 35
P2P_DIR_SENT = 0  # master -> slave
P2P_DIR_RECV = 1  # slave -> master


class Pcap:
    def __init__(self, linktype=LINKTYPE_ETHERNET):
        self.linktype = linktype
        self.records = []

    def add(self, time, data):
        self.records.append((time, bytes(data)))

    def write(self, path):
        with open(path, "wb") as f:
            f.write(struct.pack("<IHHiIII", 0xA1B2C3D4, 2, 4, 0, 0, 65535, self.linktype))
            for time, data in self.records:
                # Rounded as a whole, so that a time just under a second never reads x.1000000.
                seconds, micros = divmod(int(round(time * 1e6)), 1000000)
                f.write(struct.pack("<IIII", seconds, micros, len(data), len(data)))
                f.write(data)


def _ip_checksum(header):
    total = sum(struct.unpack("!%dH" % (len(header) // 2), header))
    while total >> 16:
        total = (total & 0xFFFF) + (total >> 16)
    return ~total & 0xFFFF


def _ipv4(src, dst, protocol, payload):
    header = struct.pack("!BBHHHBBH4s4s", 0x45, 0, 20 + len(payload), 0, 0x4000, 64, protocol,
                         0, bytes(src), bytes(dst))
    header = header[:10] + struct.pack("!H", _ip_checksum(header)) + header[12:]
    return header + payload


def _ethernet(payload):
    return b"\x00\x00\x5e\x00\x53\x02" + b"\x00\x00\x5e\x00\x53\x01" + b"\x08\x00" + payload


def _address(text):
    return [int(part) for part in text.split(".")]


class TcpFlow:
    """One TCP connection from a master (client) to a serial gateway (server)."""

    SYN, ACK_FLAG, PSH = 0x02, 0x10, 0x08

    def __init__(self, pcap, client=("10.0.0.1", 50000), server=("10.0.0.2", 4001), time=1.0):
        self.pcap = pcap
        self.client = (_address(client[0]), client[1])
        self.server = (_address(server[0]), server[1])
        self.seq = {True: 1000, False: 5000}  # by "from server"
        self.time = time
        self._handshake()

    def _segment(self, from_server, flags, payload=b"", ack=True):
        src, dst = (self.server, self.client) if from_server else (self.client, self.server)
        acknowledged = self.seq[not from_server] if ack else 0
        tcp = struct.pack("!HHIIBBHHH", src[1], dst[1], self.seq[from_server], acknowledged,
                          5 << 4, flags, 65535, 0, 0)
        self.pcap.add(self.time, _ethernet(_ipv4(src[0], dst[0], 6, tcp + payload)))
        self.seq[from_server] = (self.seq[from_server] + len(payload)) & 0xFFFFFFFF

    def _handshake(self):
        self.seq[False] -= 1
        self._segment(False, self.SYN, ack=False)
        self.seq[False] += 1
        self.seq[True] -= 1
        self._segment(True, self.SYN | self.ACK_FLAG)
        self.seq[True] += 1
        self._segment(False, self.ACK_FLAG)

    def send(self, payload, from_server, after=0.01):
        self.time += after
        self._segment(from_server, self.PSH | self.ACK_FLAG, payload)

    def request(self, payload, after=0.01):
        self.send(payload, False, after)

    def reply(self, payload, after=0.01):
        self.send(payload, True, after)


def udp_packet(pcap, time, payload, src=("10.0.0.1", 50001), dst=("10.0.0.2", 4002)):
    udp = struct.pack("!HHHH", src[1], dst[1], 8 + len(payload), 0) + payload
    pcap.add(time, _ethernet(_ipv4(_address(src[0]), _address(dst[0]), 17, udp)))


def _tag(tag, value):
    return struct.pack("!HH", tag, len(value)) + value


def exported_pdu_record(payload, direction=None, dissector=b"pvtap", pad=True):
    """A link type 252 record: dissector name (NUL-padded to 4 unless told), optional
    direction, end of options, then the payload."""
    name = dissector + b"\x00" * (-len(dissector) % 4 if pad else 0)
    tags = _tag(EXP_PDU_TAG_DISSECTOR_NAME, name)
    if direction is not None:
        tags += _tag(EXP_PDU_TAG_P2P_DIRECTION, struct.pack("!i", direction))
    return tags + _tag(EXP_PDU_TAG_END_OF_OPT, b"") + payload
