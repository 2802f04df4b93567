"""Classic pcap files as a header and a list of records, to cut, reorder and re-time them
in tests (pcapng goes through editcap)."""

import struct

MICRO = (b"\xd4\xc3\xb2\xa1", b"\xa1\xb2\xc3\xd4")
NANO = (b"\x4d\x3c\xb2\xa1", b"\xa1\xb2\x3c\x4d")


class Record:
    def __init__(self, seconds, fraction, original_length, data):
        self.seconds, self.fraction = seconds, fraction
        self.original_length, self.data = original_length, data


class Pcap:
    def __init__(self, header, records):
        self.header, self.records = header, records
        magic = header[:4]
        if magic not in MICRO + NANO:
            raise ValueError("not a classic pcap file")
        self.endian = "<" if magic in (MICRO[0], NANO[0]) else ">"
        self.per_second = 1_000_000_000 if magic in NANO else 1_000_000

    def time(self, record):
        return record.seconds + record.fraction / self.per_second

    def shifted(self, record, seconds):
        """The record moved by a whole number of seconds."""
        return Record(record.seconds + seconds, record.fraction, record.original_length,
                      record.data)

    def write(self, path, records):
        with open(path, "wb") as f:
            f.write(self.header)
            for r in records:
                f.write(struct.pack(self.endian + "IIII", r.seconds, r.fraction, len(r.data),
                                    r.original_length))
                f.write(r.data)


def read_pcap(path):
    with open(path, "rb") as f:
        data = f.read()
    header = data[:24]
    pcap = Pcap(header, [])
    at = 24
    while at + 16 <= len(data):
        seconds, fraction, length, original = struct.unpack(pcap.endian + "IIII",
                                                            data[at:at + 16])
        pcap.records.append(Record(seconds, fraction, original, data[at + 16:at + 16 + length]))
        at += 16 + length
    return pcap
