"""A second device answering to an inverter's address (pvtap-sim --address-conflict): the
plugin raises an address-conflict expert info on each second reply with other contents, as
many as pvtap audit counts and the simulator's truth holds, in both passes; a repeated
identical reply stays a duplicate, and no other station gets one. A tap whose adapter echoes
every request (pvtap-sim --echo): each echo an echo expert info linked to its request, '(echo)'
in Info, as many as pvtap audit counts and the truth holds, and the replies paired with the
requests, so that no request of the truth's is left unanswered. Two masters that collide
(pvtap-sim --masters 2): a collision expert info for each collision pvtap audit names, in one
pass and in two.
"""
import json
import os
import subprocess
import tempfile
import unittest

from tshark_runner import PluginTestCase


def binary(variable):
    path = os.environ.get(variable)
    if not path or not os.access(path, os.X_OK):
        raise RuntimeError("%s must name a built program (got %r)" % (variable, path))
    return path


class SimulatedBus(PluginTestCase):
    """A bus pvtap-sim writes as link type 252 with SIM_ARGS, handed to tshark's user as
    `capture`, with pvtap audit's summary of it and the simulator's truth."""

    NAME = ""
    SIM_ARGS = []

    @classmethod
    def setUpClass(cls):
        super().setUpClass()
        cls.work = tempfile.TemporaryDirectory(prefix="pvtap-%s-" % cls.NAME)
        capture = os.path.join(cls.work.name, cls.NAME + ".pdu.pcap")
        truth = os.path.join(cls.work.name, cls.NAME + ".truth.json")
        subprocess.run([binary("PVTAP_SIM"), *cls.SIM_ARGS, "--pdu", capture, "--truth", truth],
                       check=True, timeout=120)
        with open(truth) as f:
            cls.truth = json.load(f)
        cls.capture = cls.tshark.write_text(cls.NAME + ".pdu.pcap", "")
        with open(capture, "rb") as src, open(cls.capture, "wb") as dst:
            dst.write(src.read())
        cls.tshark._hand_over()
        summary = subprocess.run([binary("PVTAP_BINARY"), "audit", "--summary-only", "--format",
                                  "jsonl", capture], capture_output=True, text=True,
                                 check=True, timeout=120).stdout.splitlines()[-1]
        cls.summary = json.loads(summary)

    @classmethod
    def tearDownClass(cls):
        cls.work.cleanup()
        super().tearDownClass()


class AddressConflict(SimulatedBus, unittest.TestCase):
    NAME = "conflict"
    SIM_ARGS = ["--seed", "11", "--inverters", "3", "--period", "1", "--address-conflict", "2",
                "--duration", "40"]

    def conflicts_by_station(self, passes):
        options = ["-2"] if passes == 2 else []
        rows = self.tshark.fields(self.capture, ["invrtu.station"],
                                  "invrtu.address_conflict", options=options)
        stations = {}
        for row in rows:
            for station in row[0]:
                stations[int(station, 0)] = stations.get(int(station, 0), 0) + 1
        return stations

    def test_each_second_reply_with_other_contents_is_an_expert_info(self):
        # The second device's replies whose bytes differ from the reply before them: where
        # both devices hold the same values (a name block), its reply is a duplicate.
        want, last = {}, {}
        for e in self.truth["events"]:
            if e["type"] != "frame" or e["role"] != "response":
                continue
            if e.get("fault") == "address_conflict" and last.get(e["station"]) != e["hex"]:
                want[e["station"]] = want.get(e["station"], 0) + 1
            last[e["station"]] = e["hex"]
        self.assertEqual(list(want), [2])
        self.assertGreater(want[2], 50)
        audit = {int(k): s["address_conflicts"] for k, s in self.summary["stations"].items()
                 if s["address_conflicts"]}
        self.assertEqual(audit, want)
        second = self.truth["address_conflicts"][0]["second_replies"]
        self.assertEqual(self.summary["stations"]["2"]["duplicates"], second - want[2])
        self.assertEqual(self.conflicts_by_station(2), want)
        self.assertEqual(self.conflicts_by_station(1), want)


class Echo(SimulatedBus, unittest.TestCase):
    NAME = "echo"
    SIM_ARGS = ["--seed", "5", "--inverters", "3", "--period", "1", "--echo", "--faults",
                "missing=5", "--duration", "30"]

    def test_each_echo_is_one_expert_info_linked_to_its_request(self):
        self.assertGreater(self.truth["echoes"], 50)
        self.assertEqual(self.summary["echoes"], self.truth["echoes"])
        for options in ([], ["-2"]):
            rows = self.tshark.fields(self.capture, ["frame.number", "invrtu.request_in",
                                                     "_ws.col.Info"], "invrtu.echo",
                                      options=options)
            self.assertEqual(len(rows), self.truth["echoes"], options)
            for number, request_in, info in rows:
                # The request it repeats is the frame just before it.
                self.assertEqual([int(n) for n in request_in], [int(number[0]) - 1])
                self.assertTrue(info[0].endswith("(echo)"), info)

    def test_only_the_truths_timeouts_are_unanswered(self):
        rows = self.tshark.fields(self.capture, ["frame.number"], "invrtu.unanswered",
                                  options=["-2"])
        self.assertEqual(len(rows), self.truth["summary"]["timeouts"])
        self.assertEqual(self.summary["timeouts"], self.truth["summary"]["timeouts"])


class Collision(SimulatedBus, unittest.TestCase):
    NAME = "shared"
    SIM_ARGS = ["--seed", "37", "--inverters", "2", "--period", "1", "--timeout", "0.3",
                "--masters", "2", "--duration", "60"]

    def collisions(self, passes):
        args = ["-r", self.capture, "-T", "fields",
                "-E", "occurrence=a", "-E", "aggregator=|", "-e", "_ws.expert.message",
                "-Y", "invrtu.collision"]
        out = self.tshark.run((["-2"] if passes == 2 else []) + args).stdout
        return sum(1 for line in out.splitlines() for message in line.split("|")
                   if message.startswith("Collision"))

    def test_each_collision_audit_names_is_one_expert_info(self):
        self.assertGreater(self.summary["collisions"], 20)
        for passes in (1, 2):
            self.assertEqual(self.collisions(passes), self.summary["collisions"], passes)


if __name__ == "__main__":
    unittest.main()
