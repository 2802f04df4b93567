"""Serial captures read as a bus: no blank row, the record that completes a frame, who talks.

In a USER0 capture a frame often spans several records. A record whose last byte waits for a
later record names its protocol and says "[part of a frame]", as TCP names a segment of a
reassembled PDU; once the first pass has seen the record that completes it (two passes:
tshark -2, the GUI's packet list), "[part of a frame, completed in #N]" and the field
pvtap_serial.completed_in. A single pass (a live capture, tshark without -2) cannot look ahead:
there, and only there, a waiting record shows no number and no talkers.

The Source and Destination columns name who talks: "master" for a request, "station N" for
the station that replies. A gateway's TCP packets and exported-PDU records with address tags
keep their addresses there.

Ground truth is the simulator's: the truth file of each sample lists every frame and noise run
with its bytes, and the records of its USER0 capture hold those bytes end to end, so the record
holding each frame's last byte is known without the plugin. A good frame is decided by its last
byte; a damaged frame or a noise run only by what follows it (a frame, a silence), so the record
that completes them may come later, never earlier. On the clean samples every waiting record is
completed exactly where its frame's last byte is.
"""
import bisect
import glob
import json
import os
import re
import shutil
import struct
import sys
import unittest

from bus_frames import gsl_read_reply, rtu_read_request
from pcap_writer import (LINKTYPE_WIRESHARK_UPPER_PDU, P2P_DIR_RECV, P2P_DIR_SENT, Pcap,
                         exported_pdu_record)
from tshark_runner import PluginTestCase

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "support"))
from pcap_records import read_pcap  # noqa: E402

SAMPLE_DIR = os.path.realpath(os.path.join(HERE, "..", "..", "captures", "samples"))
SERIAL_SAMPLES = sorted(glob.glob(os.path.join(SAMPLE_DIR, "*.user0.pcap")))
CLEAN = ("ascii-clean", "gsl-clean", "hybrid-clean")
COLUMNS = ["frame.number", "_ws.col.Protocol", "_ws.col.Info", "_ws.col.Source",
           "_ws.col.Destination", "pvtap_serial.completed_in"]
WAITING = re.compile(r"^\[part of a (frame|noise run)(, completed in #(\d+))?\]$")
IPV4 = re.compile(r"^\d+\.\d+\.\d+\.\d+$")


class Truth:
    """Where the simulator's frames and noise runs lie among a USER0 capture's records."""

    def __init__(self, sample):
        self.record_ends = []  # stream position after each record's last byte
        at = 0
        for record in read_pcap(sample).records:
            at += len(record.data)
            self.record_ends.append(at)
        with open(sample.replace(".user0.pcap", ".truth.json")) as f:
            events = [e for e in json.load(f)["events"] if "hex" in e]
        self.event_starts, self.events = [], []
        at = 0
        for event in events:
            self.event_starts.append(at)
            at += len(event["hex"]) // 2
            self.events.append((at, event))
        self.stream = at

    def record_of(self, position):
        """The number (from 1) of the record holding the byte at `position`."""
        return bisect.bisect_right(self.record_ends, position) + 1

    def waiting(self, number):
        """For record `number`: the event holding its last byte and the record holding that
        event's last byte."""
        last = self.record_ends[number - 1] - 1
        end, event = self.events[bisect.bisect_right(self.event_starts, last) - 1]
        return event, self.record_of(end - 1)

    def ends_within(self, number):
        """Whether an event ends within record `number` (it has something of its own to show)."""
        start = self.record_ends[number - 2] if number > 1 else 0
        ends = [end for end, _ in self.events]
        i = bisect.bisect_right(ends, start)
        return i < len(ends) and ends[i] <= self.record_ends[number - 1]


def talkers(role, station):
    """(source, destination) of a frame as a user reads a bus."""
    name = "station %d" % station
    return ("master", name) if role == "request" else (name, "master")


def names(cell):
    return set(cell.split(", ")) if cell else set()


class SerialRows(PluginTestCase, unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        super().setUpClass()
        cls.captures, cls.truth, cls.rows = {}, {}, {}
        for sample in SERIAL_SAMPLES:
            name = os.path.basename(sample)
            copy = cls.tshark.path(name)
            shutil.copy(sample, copy)
            cls.tshark._hand_over()
            cls.captures[name] = copy
            cls.truth[name] = Truth(sample)
            cls.rows[name] = {passes: cls.columns(copy, passes) for passes in (1, 2)}

    @classmethod
    def columns(cls, capture, passes):
        args = ["-r", capture] + (["-2"] if passes == 2 else []) + ["-T", "fields"]
        for column in COLUMNS:
            args += ["-e", column]
        rows = [line.split("\t") for line in cls.tshark.run(args).stdout.splitlines()]
        return {int(row[0]): dict(zip(COLUMNS[1:], row[1:])) for row in rows}

    def frames_shown(self, name):
        """Per record of a two-pass run: the role and station of every frame it shows."""
        out = self.tshark.run(["-r", self.captures[name], "-2", "-T", "json",
                               "--no-duplicate-keys", "-J", "invrtu invascii"]).stdout
        shown = {}
        for number, packet in enumerate(json.loads(out), start=1):
            layers = packet["_source"]["layers"]
            for proto in ("invrtu", "invascii"):
                pdus = layers.get(proto, [])
                for pdu in pdus if isinstance(pdus, list) else [pdus]:
                    if proto + ".role" in pdu and proto + ".station" in pdu:
                        role = "request" if pdu[proto + ".role"] == "0" else "response"
                        shown.setdefault(number, []).append(
                            (role, int(pdu[proto + ".station"], 0)))
        return shown

    def test_the_sample_library_has_serial_captures(self):
        self.assertGreaterEqual(len(SERIAL_SAMPLES), 8)
        self.assertTrue(all(self.truth[n].stream == self.truth[n].record_ends[-1]
                            for n in self.truth), "the records do not hold the truth's bytes")

    def test_no_row_is_blank(self):
        for name, passes in self.rows.items():
            for count, rows in passes.items():
                with self.subTest(sample=name, passes=count):
                    self.assertEqual(len(rows), len(self.truth[name].record_ends))
                    blank = [n for n, row in rows.items()
                             if not row["_ws.col.Protocol"] or not row["_ws.col.Info"]]
                    self.assertEqual(blank, [], "records with an empty Protocol or Info")

    def test_mixed_faults_records_name_the_record_that_completes_them(self):
        rows = self.rows["mixed-faults.user0.pcap"][2]
        self.assertEqual(rows[2]["_ws.col.Info"], "[part of a frame, completed in #3]")
        for number in range(8, 14):
            self.assertEqual(rows[number]["_ws.col.Protocol"], "invRTU")
            self.assertEqual(rows[number]["_ws.col.Info"], "[part of a frame, completed in #14]")
            self.assertEqual(rows[number]["pvtap_serial.completed_in"], "14")

    def test_a_waiting_record_is_completed_where_its_frame_ends(self):
        for name, truth in self.truth.items():
            rows = self.rows[name][2]
            clean = name.split(".")[0] in CLEAN
            with self.subTest(sample=name):
                waiting = 0
                for number, row in rows.items():
                    event, last = truth.waiting(number)
                    completed = row["pvtap_serial.completed_in"]
                    if last == number:
                        if clean:
                            self.assertEqual(completed, "", "record %d waits for nothing" % number)
                        continue
                    waiting += 1
                    self.assertNotEqual(completed, "", "record %d waits for #%d" % (number, last))
                    completed = int(completed)
                    # Never before the frame's last byte; later where what follows decides.
                    self.assertGreaterEqual(completed, last, "record %d" % number)
                    if clean:
                        self.assertEqual(completed, last, "record %d" % number)
                    self.assertIsNone(WAITING.match(rows[completed]["_ws.col.Info"]),
                                      "#%d completes record %d but shows nothing" % (completed,
                                                                                    number))
                    match = WAITING.match(rows[number]["_ws.col.Info"])
                    if clean and not truth.ends_within(number):
                        self.assertIsNotNone(match, "record %d shows nothing of its own" % number)
                    if match is None:
                        continue  # it shows pieces decided only now (a damaged frame before)
                    self.assertEqual(match.group(3), str(completed), "record %d" % number)
                    if event["type"] == "noise":  # a damaged frame may be read as noise
                        self.assertEqual(match.group(1), "noise run", "record %d" % number)
                    elif event["check"] == "ok":
                        self.assertEqual(match.group(1), "frame", "record %d" % number)
                self.assertGreater(waiting, 0)
                completions = [int(r["pvtap_serial.completed_in"]) for r in rows.values()
                               if r["pvtap_serial.completed_in"]]
                self.assertEqual(completions, sorted(completions), "completions go backwards")

    def test_one_pass_shows_the_same_but_what_it_cannot_know_yet(self):
        for name, passes in self.rows.items():
            with self.subTest(sample=name):
                for number, two in passes[2].items():
                    one = passes[1][number]
                    self.assertEqual(one["_ws.col.Protocol"], two["_ws.col.Protocol"])
                    self.assertEqual(one["pvtap_serial.completed_in"], "", "a first pass")
                    match = WAITING.match(two["_ws.col.Info"])
                    if match is None:
                        columns = [c for c in COLUMNS[1:] if c.startswith("_ws.col.")]
                        self.assertEqual([one[c] for c in columns], [two[c] for c in columns],
                                         "record %d" % number)
                        continue
                    # The completing record comes later: a single pass has not seen it.
                    self.assertEqual(one["_ws.col.Info"], "[part of a frame]")
                    self.assertEqual((one["_ws.col.Source"], one["_ws.col.Destination"]),
                                     ("", ""), "record %d" % number)

    def test_source_and_destination_name_who_talks(self):
        for name, truth in self.truth.items():
            rows = self.rows[name][2]
            shown = self.frames_shown(name)
            with self.subTest(sample=name):
                named = 0
                for number, row in rows.items():
                    frames = shown.get(number, [])
                    if not frames and WAITING.match(row["_ws.col.Info"]):
                        event, _ = truth.waiting(number)
                        if event["type"] != "frame" or event["check"] != "ok":
                            continue  # a damaged frame or noise: its talker is not known
                        frames = [(event["role"], event["station"])]
                    expected = [talkers(role, station) for role, station in frames]
                    self.assertEqual(names(row["_ws.col.Source"]), {s for s, _ in expected},
                                     "record %d" % number)
                    self.assertEqual(names(row["_ws.col.Destination"]), {d for _, d in expected},
                                     "record %d" % number)
                    named += bool(expected)
                self.assertGreater(named, len(rows) // 2)

    def test_a_gateway_keeps_its_addresses(self):
        capture = self.tshark.path("mixed-faults.gateway.pcap")
        shutil.copy(os.path.join(SAMPLE_DIR, "mixed-faults.gateway.pcap"), capture)
        self.tshark._hand_over()
        rows = self.columns(capture, 2)
        self.assertGreater(sum(r["_ws.col.Protocol"] == "invRTU" for r in rows.values()), 0)
        for number, row in rows.items():
            self.assertRegex(row["_ws.col.Source"], IPV4, "packet %d" % number)
            self.assertRegex(row["_ws.col.Destination"], IPV4, "packet %d" % number)

    def test_exported_pdu_records_name_talkers_unless_they_carry_addresses(self):
        request, reply = rtu_read_request(1, 0x03, 1056, 1), gsl_read_reply(1, [5002])
        pcap = Pcap(LINKTYPE_WIRESHARK_UPPER_PDU)
        pcap.add(100.0, exported_pdu_record(request, P2P_DIR_SENT))
        pcap.add(100.05, exported_pdu_record(reply, P2P_DIR_RECV))
        pcap.add(101.0, with_addresses(exported_pdu_record(request, P2P_DIR_SENT), request))
        capture = self.tshark.write("records.pcap", pcap)
        rows = self.columns(capture, 2)
        self.assertEqual([(r["_ws.col.Source"], r["_ws.col.Destination"]) for r in rows.values()],
                         [("master", "station 1"), ("station 1", "master"),
                          ("10.0.0.1", "10.0.0.2")])


def with_addresses(record, payload):
    """The record with IPv4 and TCP port tags of 10.0.0.1:50000 -> 10.0.0.2:4001 added before
    its end of options."""
    def tag(number, value):
        return struct.pack("!HH", number, len(value)) + value
    tags = (tag(20, bytes([10, 0, 0, 1])) + tag(21, bytes([10, 0, 0, 2])) +
            tag(24, struct.pack("!I", 2)) + tag(25, struct.pack("!I", 50000)) +
            tag(26, struct.pack("!I", 4001)))
    cut = len(record) - len(payload) - 4  # the end-of-options tag is 4 bytes
    return record[:cut] + tags + record[cut:]


if __name__ == "__main__":
    unittest.main()
