"""Every capture of the sample library: tshark with the plugin gives pvtap audit's verdicts.

The same frames (dialect, role, station, function, check verdict), the same noise runs and
bytes, the same unanswered requests, on the Wireshark series the plugin was built for. tshark
runs two-pass (-2), as a display filter typed after loading sees it, and one-pass, as a live
capture and a filter given at start-up see it: both passes show the same verdicts. USER0
captures are read as they are (the plugin claims USER0-15 and reassembles frames across
records) and as `pvtap audit --write` writes them (link type 252). USER0 captures go
through `pvtap audit --write` (link type 252), which the plugin reads; gateway and
exported-PDU captures are read as they are.

One difference is pvtap audit's, not the plugin's: reading an exported-PDU capture, audit
joins the noise records into one run (the bytes are the same), so there the runs are held
against the simulator's ground truth (the sample's .truth.json) instead.
"""
import collections
import glob
import json
import os
import shutil
import subprocess
import unittest

from tshark_runner import PluginTestCase

HERE = os.path.dirname(os.path.abspath(__file__))
SAMPLE_DIR = os.path.realpath(os.path.join(HERE, "..", "..", "captures", "samples"))
# The Modbus/TCP samples wait for the plugin's MBAP reader (issue 27).
SAMPLES = sorted(p for p in glob.glob(os.path.join(SAMPLE_DIR, "*.pcap"))
                 if not p.endswith(".mbap.pcap"))
DIALECTS = {"ascii": 0, "hybrid": 1, "gsl": 2, "modbus": 3}
ROLES = {"request": 0, "response": 1}
GOOD, BAD = 1, 0  # PROTO_CHECKSUM_E_GOOD, PROTO_CHECKSUM_E_BAD

PROTOCOLS = ("invrtu", "invascii")
# Verdicts of the plugin that pvtap audit reports otherwise; compared between the passes.
OTHER_VERDICTS = ("exception", "duplicate", "address_conflict", "unsolicited", "late_reply",
                  "count_mismatch", "malformed", "unknown_function_frame")


def pvtap_binary():
    path = os.environ.get("PVTAP_BINARY")
    if not path or not os.access(path, os.X_OK):
        raise RuntimeError("PVTAP_BINARY must name the built pvtap (got %r)" % path)
    return path


class Verdicts:
    """What one side says of a capture: frames as a multiset, noise and unanswered counts."""

    def __init__(self):
        self.frames = collections.Counter()
        self.noise_runs = 0
        self.noise_bytes = 0
        self.unanswered = 0
        self.others = collections.Counter()  # the plugin's other verdicts, by field

    def as_dict(self):
        return {"frames": self.frames, "noise_runs": self.noise_runs,
                "noise_bytes": self.noise_bytes, "unanswered": self.unanswered}


def audit_verdicts(capture, written=None):
    args = [pvtap_binary(), "audit", "--format", "jsonl", capture]
    if written:
        args += ["--write", written]
    out = subprocess.run(args, capture_output=True, text=True, timeout=120, check=True).stdout
    v = Verdicts()
    for line in out.splitlines():
        event = json.loads(line)
        kind = event["type"]
        if kind == "frame":
            v.frames[(DIALECTS[event["dialect"]], ROLES[event["role"]], event["station"],
                      event["function"], GOOD if event["check"] == "ok" else BAD)] += 1
        elif kind == "noise":
            v.noise_runs += 1
            v.noise_bytes += event["bytes"]
        elif kind == "timeout" or (kind == "unanswered" and event["reason"] != "input_ended"):
            # A request still waiting when the input ends: no packet comes after it to show
            # that in a first pass, so the plugin shows it in neither (dissector/README.md).
            v.unanswered += 1
    return v


def field_values(node, found):
    """Every field of one PDU's tree (subtrees and expert items included), by name."""
    if isinstance(node, list):
        for item in node:
            field_values(item, found)
    elif isinstance(node, dict):
        for key, value in node.items():
            if isinstance(value, (dict, list)):
                field_values(value, found)
            if not key.endswith("_tree") and not isinstance(value, dict):
                found.setdefault(key, []).append(value)
    return found


def add_pdu(v, name, pdu):
    """One PDU of one protocol as the plugin shows it: a frame, a noise run, or both."""
    f = field_values(pdu, {})
    check = "%s.%s.status" % (name, "crc" if name == "invrtu" else "checksum")
    if f.get(name + ".role"):
        key = (name + ".dialect", name + ".role", name + ".station", name + ".function", check)
        v.frames[tuple(int(f[k][0], 0) if f.get(k) else None for k in key)] += 1
    for run in f.get(name + ".noise", []):
        v.noise_runs += 1
        v.noise_bytes += len(run.replace(":", "")) // 2
    v.unanswered += len(f.get(name + ".unanswered", []))
    for verdict in OTHER_VERDICTS:
        v.others[name + "." + verdict] += len(f.get(name + "." + verdict, []))


def truth_noise_runs(sample):
    truth = os.path.join(SAMPLE_DIR, os.path.basename(sample).split(".")[0] + ".truth.json")
    with open(truth) as f:
        return sum(1 for event in json.load(f)["events"] if event.get("type") == "noise")


class SampleLibrary(PluginTestCase, unittest.TestCase):
    def plugin_verdicts(self, capture, passes=2):
        v = Verdicts()
        two_pass = ["-2"] if passes == 2 else []
        out = self.tshark.run(["-r", capture] + two_pass + ["-Y", " || ".join(PROTOCOLS), "-T",
                               "json", "--no-duplicate-keys", "-J", " ".join(PROTOCOLS)]).stdout
        for packet in json.loads(out):
            layers = packet["_source"]["layers"]
            for name in PROTOCOLS:
                pdus = layers.get(name, [])
                for pdu in pdus if isinstance(pdus, list) else [pdus]:
                    add_pdu(v, name, pdu)
        return v

    def readable_copy(self, path):
        """The capture in the tshark HOME, where the unprivileged tshark may read it."""
        copy = self.tshark.path(os.path.basename(path))
        shutil.copy(path, copy)
        self.tshark._hand_over()
        return copy

    def assert_both_passes_give(self, capture, audit):
        plugin = self.plugin_verdicts(capture)
        self.assertEqual(plugin.as_dict(), audit.as_dict())
        one_pass = self.plugin_verdicts(capture, passes=1)
        self.assertEqual((one_pass.as_dict(), one_pass.others), (plugin.as_dict(), plugin.others),
                         "one pass differs from two")

    def test_every_sample_gets_the_verdicts_of_pvtap_audit(self):
        self.assertGreater(len(SAMPLES), 20, "the sample library was not found")
        for sample in SAMPLES:
            name = os.path.basename(sample)
            with self.subTest(sample=name):
                capture = self.readable_copy(sample)
                written = None
                if ".user0." in name:
                    written = self.tshark.path(name.replace(".user0.", ".written."))
                audit = audit_verdicts(sample, written)
                self.assertGreater(sum(audit.frames.values()), 0)
                if ".pdu." in name:
                    audit.noise_runs = truth_noise_runs(sample)
                self.assert_both_passes_give(capture, audit)
                if written:
                    self.tshark._hand_over()
                    self.assertEqual(self.plugin_verdicts(written).as_dict(), audit.as_dict(),
                                     "the records pvtap audit --write wrote")

    def test_user_link_types_can_be_left_to_the_user_dlt_table(self):
        capture = self.readable_copy(os.path.join(SAMPLE_DIR, "gsl-clean.user0.pcap"))
        off = ["-o", "pvtap_serial.user_link_types:FALSE"]
        self.assertEqual(self.tshark.fields(capture, ["frame.number"], "invrtu", options=off), [])
        self.assertGreater(len(self.tshark.fields(capture, ["frame.number"], "invrtu")), 0)

    def test_noise_is_filed_under_the_dialect_it_resembles(self):
        capture = self.readable_copy(os.path.join(SAMPLE_DIR, "demo.gateway.pcap"))
        runs = {}
        for name in PROTOCOLS:
            out = self.tshark.run(["-r", capture, "-2", "-Y", name + ".noise", "-T", "fields",
                                   "-E", "occurrence=a", "-E", "aggregator=|", "-e",
                                   name + ".noise"]).stdout
            runs[name] = [run.replace(":", "") for line in out.split() for run in line.split("|")]
        # Damaged ASCII requests (ENQ, printable characters, EOT) go to invascii, the rest
        # of the noise on this mixed gateway to invrtu.
        self.assertGreater(len(runs["invascii"]), 0)
        self.assertTrue(all(run.startswith(("05", "06")) for run in runs["invascii"]), runs)
        self.assertGreater(len(runs["invrtu"]), 0)
        self.assertFalse(any(run.startswith("05") and run.endswith("04") for run in runs["invrtu"]),
                         runs)


if __name__ == "__main__":
    unittest.main()
