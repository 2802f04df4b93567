"""Frames of the three dialects, encoded here from PROTOCOLS.md, independently of the core.

The plugin tests build their captures from these, so a fault shared by the core's encoder
and its decoder cannot hide itself.
"""

ENQ, ACK, EOT = 0x05, 0x06, 0x04


def crc16_modbus(data):
    crc = 0xFFFF
    for byte in data:
        crc ^= byte
        for _ in range(8):
            crc = (crc >> 1) ^ 0xA001 if crc & 1 else crc >> 1
    return crc


def with_crc(body):
    crc = crc16_modbus(body)
    return bytes(body) + bytes([crc & 0xFF, crc >> 8])


def with_bad_crc(body):
    """The frame with its CRC's low byte flipped."""
    frame = bytearray(with_crc(body))
    frame[-2] ^= 0xFF
    return bytes(frame)


def words_be(words):
    out = bytearray()
    for w in words:
        out += bytes([w >> 8, w & 0xFF])
    return bytes(out)


def rtu_read_request(station, function, start, count):
    return with_crc(bytes([station, function]) + words_be([start, count]))


def gsl_read_reply(station, words, function=0x03):
    data = words_be(words)
    return with_crc(bytes([station, function, len(data)]) + data)


def gsl_write_single(station, register, value):
    return with_crc(bytes([station, 0x06]) + words_be([register, value]))


def gsl_exception(station, function, code):
    return with_crc(bytes([station, function | 0x80, code]))


def hybrid_reply(station, function, type_code, serial, words):
    device = bytes([type_code, (serial >> 16) & 0xFF, (serial >> 8) & 0xFF, serial & 0xFF])
    data = device + words_be(words)
    return with_crc(bytes([station, function, len(data)]) + data)


def ascii_checksum(body):
    return ("%04x" % (sum(body) & 0xFFFF)).encode()


def ascii_request(station, start, count):
    body = ("%02x" % station).encode() + b"R" + ("%04x" % start).encode() + ("%02x" % count).encode()
    return bytes([ENQ]) + body + ascii_checksum(body) + bytes([EOT])


def ascii_reply(station, start, words):
    body = ("%02x" % station).encode() + b"R" + ("%04x" % start).encode()
    body += b"".join(("%04x" % w).encode() for w in words)
    return bytes([ACK]) + body + ascii_checksum(body) + bytes([EOT])


def with_bad_checksum(frame):
    """An ASCII frame whose last checksum digit is changed."""
    out = bytearray(frame)
    out[-2] = ord("0") if out[-2] != ord("0") else ord("1")
    return bytes(out)
