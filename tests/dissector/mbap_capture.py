"""A Modbus/TCP capture with known content: a client and a gateway at 10.0.0.9:502, ADUs
pipelined, answered out of order, an exception, a 0x0B, a length that lies, an ADU split over
two segments and two ADUs in one segment. EXPECTED holds what pvtap must count in it."""

import struct
import sys

from pcap_writer import Pcap, TcpFlow

GATEWAY = ("10.0.0.9", 502)


def adu(tid, unit, pdu, length=None):
    """An MBAP ADU; `length` overrides the one that holds."""
    return struct.pack("!HHHB", tid, 0, len(pdu) + 1 if length is None else length, unit) + pdu


def read_request(start, count, function=3):
    return struct.pack("!BHH", function, start, count)


def read_reply(words, function=3):
    return struct.pack("!BB", function, 2 * len(words)) + b"".join(
        struct.pack("!H", w) for w in words)


def build(path, port=502, client_port=50200, lying_length=True):
    pcap = Pcap()
    flow = TcpFlow(pcap, client=("10.0.0.1", client_port), server=(GATEWAY[0], port), time=100.0)
    # Pipelined: three requests to unit 3 before any reply; the replies come 2, 1, 3.
    flow.request(adu(1, 3, read_request(0, 2)))
    flow.request(adu(2, 3, read_request(0x10, 1)))
    flow.request(adu(3, 3, read_request(0x20, 1, function=4)))
    flow.reply(adu(2, 3, read_reply([7])), after=0.030)
    flow.reply(adu(1, 3, read_reply([1, 2])), after=0.005)
    flow.reply(adu(3, 3, read_reply([9], function=4)), after=0.005)
    # An exception: illegal data address.
    flow.request(adu(4, 3, read_request(0x9000, 1)), after=0.2)
    flow.reply(adu(4, 3, bytes([0x83, 0x02])), after=0.02)
    # A silent device behind the gateway: the gateway answers 0x0B after its own timeout.
    flow.request(adu(5, 7, read_request(0, 1)), after=0.2)
    flow.reply(adu(5, 7, bytes([0x83, 0x0B])), after=0.5)
    # A length that lies: says 30, carries 6; the next request is whole and gets its reply.
    if lying_length:
        flow.request(adu(6, 3, read_request(0, 1), length=30), after=0.2)
    flow.request(adu(7, 3, read_request(0, 1)), after=0.01)
    flow.reply(adu(7, 3, read_reply([5])), after=0.02)
    # An ADU split over two segments.
    split = adu(8, 3, read_reply([1, 2, 3, 4]))
    flow.request(adu(8, 3, read_request(0, 4)), after=0.2)
    flow.reply(split[:9], after=0.02)
    flow.reply(split[9:], after=0.001)
    # Two ADUs in one segment each way.
    flow.request(adu(9, 3, read_request(0, 1)) + adu(10, 3, read_request(1, 1)), after=0.2)
    flow.reply(adu(9, 3, read_reply([11])) + adu(10, 3, read_reply([12])), after=0.02)
    # A request the gateway never answers at all, then one it does, 2 s later.
    flow.request(adu(11, 3, read_request(0, 1)), after=0.2)
    flow.request(adu(12, 3, read_request(0, 1)), after=2.0)
    flow.reply(adu(12, 3, read_reply([13])), after=0.02)
    pcap.write(path)


# Requests 1-5 and 7-12 (11), replies to all but 11 (10); the lying ADU's 12 bytes are given
# up; ADUs carry 6 header bytes each.
EXPECTED = {
    "adus": 21,
    "requests": 11,
    "responses": 10,
    "exceptions": 1,
    "gateway_timeouts": 1,
    "timeouts": 2,  # the request never answered, and the 0x0B: a timeout behind the gateway
    "findings": 1,
    "skipped_bytes": 12,
    "carrier_bytes": 21 * 6,
}

if __name__ == "__main__":
    build(sys.argv[1])
