"""Solarman V5 frames, encoded here from pysolarmanv5's protocol notes, independently of the
core, and the logger-stick flows the analyzer and plugin tests capture."""

import struct

from bus_frames import gsl_read_reply, rtu_read_request
from pcap_writer import TcpFlow

REQUEST, RESPONSE, HEARTBEAT, HEARTBEAT_REPLY = 0x4510, 0x1510, 0x4710, 0x1710
SERIAL = 2712345678
HEADER, TRAILER = 11, 2


def v5_frame(control, sequence, payload, serial=SERIAL, length=None):
    """start, length, control, sequence, serial (little endian), payload, checksum (sum of
    the bytes after the start byte, mod 256), end. `length` overrides the length field."""
    header = struct.pack("<BHHHI", 0xA5, len(payload) if length is None else length, control,
                         sequence, serial)
    body = header + payload
    return body + bytes([sum(body[1:]) & 0xFF, 0x15])


def with_bad_checksum(frame):
    out = bytearray(frame)
    out[-2] ^= 0x5A
    return bytes(out)


def request_payload(rtu):
    return bytes([0x02]) + struct.pack("<HIII", 0, 0, 0, 0) + rtu


def response_payload(rtu, quirk=False):
    return bytes([0x02, 0x01]) + struct.pack("<III", 1000, 200, 0) + rtu + (b"\0\0" if quirk else b"")


class StickFlow:
    """What a stick flow holds, for the counts the tests expect."""

    def __init__(self):
        self.v5 = dict(frames=0, rtu_frames=0, stick_frames=0, heartbeats=0, stick_answers=0,
                       quirk_frames=0,
                       quirk_bytes=0, bad_checksums=0, carrier_bytes=0, rtu_bytes=0,
                       truncated_frames=0, length_mismatches=0, broken_bytes=0, noise_bytes=0)
        self.requests = 0
        self.responses = 0
        self.timeouts = 0
        self.packets = {}  # name -> packet number (1-based, as tshark counts)

    def frame(self, frame, rtu=b"", quirk=0, stick=False, bad=False, answer=False):
        self.v5["frames"] += 1
        self.v5["rtu_frames"] += 1 if rtu else 0
        self.v5["rtu_bytes"] += len(rtu)
        self.v5["quirk_bytes"] += quirk
        self.v5["quirk_frames"] += 1 if quirk else 0
        self.v5["stick_frames"] += 1 if stick else 0
        self.v5["heartbeats"] += 1 if stick else 0  # the scripts' stick frames are heartbeats
        self.v5["stick_answers"] += 1 if answer else 0
        self.v5["bad_checksums"] += 1 if bad else 0
        self.v5["carrier_bytes"] += len(frame) - len(rtu) - quirk


class Step:
    """One V5 frame of a stick script: who sends it, its bytes, what it carries."""

    def __init__(self, name, from_stick, frame, rtu=b"", quirk=0, stick=False, bad=False,
                 after=0.05, answer=False):
        self.name, self.from_stick, self.frame = name, from_stick, frame
        self.rtu, self.quirk, self.stick, self.bad, self.after = rtu, quirk, stick, bad, after
        self.answer = answer


def stick_script(reads=30, drop=17, bad_checksum=23):
    """`reads` GSL reads through a stick; every fifth reply with the two extra zeros; a
    heartbeat and its answer after read 10; the reply to read `drop` never comes; read
    `bad_checksum`'s reply fails its V5 checksum. Returns the steps and their counts."""
    steps, s = [], StickFlow()
    for i in range(reads):
        rtu = rtu_read_request(1, 0x03, 1050 + i % 7, 1)
        steps.append(Step("request_%d" % i, False, v5_frame(REQUEST, 0x0100 + i,
                                                              request_payload(rtu)), rtu,
                          after=0.5))
        s.requests += 1
        if i == drop:
            s.timeouts += 1
        else:
            reply = gsl_read_reply(1, [2300 + i])
            quirk = i % 5 == 4
            frame = v5_frame(RESPONSE, 0x0100 + i, response_payload(reply, quirk))
            bad = i == bad_checksum
            steps.append(Step("reply_%d" % i, True, with_bad_checksum(frame) if bad else frame,
                              reply, quirk=2 if quirk else 0, bad=bad))
            s.responses += 1
        if i == 10:
            steps.append(Step("heartbeat", True, v5_frame(HEARTBEAT, 0x0001, b"\0"), stick=True,
                              after=0.1))
            steps.append(Step("heartbeat_answer", False,
                              v5_frame(HEARTBEAT_REPLY, 0x0001, bytes([0x02, 0x01]) + bytes(8)),
                              answer=True, after=0.01))
    for step in steps:
        s.frame(step.frame, step.rtu, quirk=step.quirk, stick=step.stick, bad=step.bad,
                answer=step.answer)
    return steps, s


def stick_reads(pcap, port=48899, time=1.0, **script):
    """The stick script captured on `port` (not 8899: structure, not the port, makes it V5);
    its counts, with the packet number of each step."""
    steps, s = stick_script(**script)
    flow = TcpFlow(pcap, client=("10.0.0.1", 50200), server=("10.0.0.7", port), time=time)
    for step in steps:
        flow.send(step.frame, step.from_stick, after=step.after)
        s.packets[step.name] = len(pcap.records)
    return s


def broken_stick(pcap, port=48900, time=100.0):
    """A stick flow with a reply whose length claims more than it holds (a finding, then the
    next frame is read), and a last reply cut short by the end of the capture."""
    s = StickFlow()
    flow = TcpFlow(pcap, client=("10.0.0.1", 50300), server=("10.0.0.8", port), time=time)
    for i in range(4):
        rtu = rtu_read_request(1, 0x03, 1050, 1)
        frame = v5_frame(REQUEST, i, request_payload(rtu))
        flow.request(frame, after=0.5)
        s.frame(frame, rtu)
        s.requests += 1
        reply = gsl_read_reply(1, [2300 + i])
        payload = response_payload(reply)
        if i == 1:
            lying = v5_frame(RESPONSE, i, payload, length=len(payload) + 30)
            flow.reply(lying, after=0.05)
            s.v5["length_mismatches"] += 1
            s.v5["broken_bytes"] += len(lying)
            s.timeouts += 1
        elif i == 3:
            cut = v5_frame(RESPONSE, i, payload)[:20]
            flow.reply(cut, after=0.05)
            s.v5["truncated_frames"] += 1
            s.v5["broken_bytes"] += len(cut)
            s.timeouts += 1
        else:
            frame = v5_frame(RESPONSE, i, payload)
            flow.reply(frame, after=0.05)
            s.frame(frame, reply)
            s.responses += 1
    # A last request after the timeout of the one whose reply was cut; its own reply is not
    # due before the capture ends.
    rtu = rtu_read_request(1, 0x03, 1051, 1)
    frame = v5_frame(REQUEST, 4, request_payload(rtu))
    flow.request(frame, after=1.5)
    s.frame(frame, rtu)
    s.requests += 1
    return s


# Text a stick sent before a V5 frame: bytes of no V5 frame, counted apart.
VERSION_TEXT = b"AT+YZCMPVER=MW3_16U_5406_1.53\r\n"


def threads_steps():
    """The stick of V5 client libraries' issue threads (issue 35), one logged line every 0.2 s:
    a heartbeat where the reply to 0x98 was due, that reply after request 0xd4; code 05 in
    place of a reply; a client that addressed logger 2111130827; text before a V5 frame."""
    stick, wrong = 4068039735, 2111130827
    read = rtu_read_request(1, 0x03, 1050, 1)
    answer = response_payload(gsl_read_reply(1, [2301]))  # 7 RTU bytes

    def request(seq, serial=stick, after=0.2):
        return Step("request_%02x" % seq, False,
                    v5_frame(REQUEST, seq, request_payload(read), serial=serial), after=after)

    def stick_frame(name, control, seq, payload, after=0.2, before=b""):
        return Step(name, True, before + v5_frame(control, seq, payload, serial=stick),
                    after=after)

    return [stick_frame("heartbeat", HEARTBEAT, 0x0101, b"\0", after=0.01),
            request(0x97), stick_frame("reply_97", RESPONSE, 0x0297, answer),
            request(0x98), stick_frame("heartbeat_for_98", HEARTBEAT, 0x0302, b"\0"),
            request(0xd4), stick_frame("reply_98", RESPONSE, 0x0498, answer),
            stick_frame("reply_d4", RESPONSE, 0x05d4, answer, after=0.4, before=VERSION_TEXT),
            request(0x10, after=5.0),
            stick_frame("code_05", RESPONSE, 0x0610, response_payload(b"\x05\x00"), after=0.5),
            request(0x11, serial=wrong, after=5.0),
            stick_frame("code_06", RESPONSE, 0x0711, response_payload(b"\x06\x00"),
                        after=0.05)]


def threads_stick(pcap):
    """threads_steps() captured, at their pace."""
    flow = TcpFlow(pcap, client=("10.0.0.1", 50800), server=("10.0.0.13", 8899), time=700.0)
    for step in threads_steps():
        flow.send(step.frame, step.from_stick, after=step.after)
