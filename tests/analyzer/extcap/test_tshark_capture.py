"""A real `tshark -i <pvtap interface>` capture, unprivileged, with pvtap's plugin and pvtap
as extcap from the build tree: a simulated bus is paced onto a pty, tshark shows its frames;
the options dialog's settings (tshark's -o) reach pvtap, and pvtap's refusals reach the user.
"""
import json
import os
import shutil
import subprocess
import tempfile
import time
import unittest

from extcap_home import ExtcapHome, ReadablePty, holders_of, interface_of, pty_bus

# The longest one program this test runs may take: a guard, not a timing check. On expiry
# subprocess raises TimeoutExpired, which names the command that was waited for.
RUN_GUARD_S = 120

BAUD = 9600
# tshark's own stop; the bus below plays for 3 s once pvtap has opened the pty, well before.
CAPTURE_S = 10
# Longest wait for pvtap to open the pty: a guard against hangs, not a timing check.
GUARD_S = 30
FIELDS = ["exported_pdu.exported_pdu", "invrtu.station", "invrtu.function", "invascii.station",
          "invascii.function"]


def simulate(folder):
    sim = os.environ.get("PVTAP_SIM")
    if not sim or not os.access(sim, os.X_OK):
        raise RuntimeError("PVTAP_SIM must name the built pvtap-sim (got %r)" % sim)
    truth_path = os.path.join(folder, "truth.json")
    subprocess.run([sim, "--baud", str(BAUD), "--period", "1", "--dialect", "gsl,hybrid,ascii",
                    "--inverters", "3", "--duration", "3", "--seed", "5", "--truth", truth_path],
                   check=True, capture_output=True, timeout=RUN_GUARD_S)
    with open(truth_path, encoding="utf-8") as f:
        return json.load(f)


def decoded(line):
    """(raw hex, station, function) of one tshark fields line; the dissector is invrtu or
    invascii, whichever filled its fields."""
    raw, rtu_station, rtu_function, ascii_station, ascii_function = line.split("\t")
    station = rtu_station or ascii_station
    function = rtu_function or ascii_function
    return (raw.replace(":", "").lower(), int(station, 0) if station else None,
            int(function, 0) if function else None)


class TsharkCapture(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        # Class cleanups run even when this set-up fails half-way.
        cls.folder = tempfile.mkdtemp(prefix="pvtap-extcap-truth-")
        cls.addClassCleanup(shutil.rmtree, cls.folder, ignore_errors=True)
        cls.truth = simulate(cls.folder)
        cls.pty = ReadablePty()
        cls.addClassCleanup(cls.pty.close)
        cls.interface = interface_of(cls.pty.path)
        cls.tshark = ExtcapHome([cls.pty.path])
        cls.addClassCleanup(cls.tshark.close)
        listing = cls.tshark.loaded_plugins()
        if "pvtap.so" not in listing:
            raise AssertionError("tshark did not load pvtap.so:\n" + listing)

    def test_interface_list_shows_the_rs485_tap(self):
        listing = self.tshark.run(["-D"]).stdout
        expected = "%s (RS485 tap (%s))" % (self.interface, self.pty.name())
        self.assertIn(expected, listing)

    def test_capture_of_a_quiet_bus_ends_on_time(self):
        # tshark counts `-a duration` from the pcap header on; pvtap must send it at once.
        result = self.tshark.run(["-i", self.interface, "-a", "duration:2"])
        self.assertIn("0 packets captured", result.stderr)

    def setting(self, name, value):
        """tshark's -o for one of the options dialog's settings (the dialog saves them under
        this preference name: the interface with '_' for '-', the call without dashes)."""
        key = "extcap.%s.%s" % (self.interface.replace("-", "_").lower(), name)
        return ["-o", "%s:%s" % (key, value)]

    def test_dialog_settings_reach_pvtap(self):
        args = ["-i", self.interface, "-a", "duration:2"]
        # Parity stays none: a Linux pty drops PARENB, and pvtap refuses a line the driver
        # did not set as asked (the refusal is how a user learns their adapter cannot).
        args += self.setting("baud", "19200") + self.setting("parity", "none")
        args += self.setting("stopbits", "2") + self.setting("dialect", "gsl")
        tshark = self.tshark.start(args)
        self.wait_for_pvtap(tshark)
        with open("/proc/%d/cmdline" % holders_of(self.pty.path)[0]) as f:
            command = f.read().split("\0")
        out, err = self.finish(tshark, GUARD_S)
        self.assertEqual(tshark.returncode, 0, err)
        for option, value in (("--baud", "19200"), ("--parity", "none"), ("--stop-bits", "2"),
                              ("--dialect", "gsl")):
            self.assertIn(option, command)
            self.assertEqual(command[command.index(option) + 1], value, command)

    def test_a_setting_pvtap_refuses_is_shown_by_tshark(self):
        result = self.tshark.run(["-i", self.interface, "-a", "duration:2"] +
                                 self.setting("baud", "1234"), check=False)
        self.assertNotEqual(result.returncode, 0)
        self.assertIn("pvtap: --baud 1234: not one of", result.stderr)

    def finish(self, tshark, seconds):
        """The output of a tshark that stops by its own -a duration; a guard, not a timing
        check: one still running `seconds` later is killed and the failure says so."""
        try:
            return tshark.communicate(timeout=seconds)
        except subprocess.TimeoutExpired:
            tshark.kill()
            out, err = tshark.communicate()
            self.fail("tshark still running %d s after its -a duration ended (killed); it "
                      "printed:\n%s%s" % (seconds, out, err))

    def wait_for_pvtap(self, tshark):
        deadline = time.monotonic() + GUARD_S
        while not holders_of(self.pty.path):
            if tshark.poll() is not None or time.monotonic() > deadline:
                tshark.kill()
                out, err = tshark.communicate()
                self.fail("pvtap never opened %s; tshark: %s%s" % (self.pty.path, out, err))
            time.sleep(0.01)

    def test_live_capture_shows_the_bus_frames_decoded(self):
        args = ["-i", self.interface, "-a", "duration:%d" % CAPTURE_S, "-l", "-T", "fields"]
        for field in FIELDS:
            args += ["-e", field]
        tshark = self.tshark.start(args)
        self.wait_for_pvtap(tshark)
        events = self.truth["events"]
        pty_bus.play(self.pty.master, pty_bus.byte_schedule(events, BAUD), time.monotonic())
        out, err = self.finish(tshark, CAPTURE_S + GUARD_S)
        self.assertEqual(tshark.returncode, 0, err)
        found = [decoded(line) for line in out.splitlines()]
        expected = [(e["hex"].lower(), e["station"], e["function"]) for e in events
                    if e["type"] == "frame"]
        self.assertEqual(len([e for e in events if e["type"] != "frame"]), 0,
                         "the seed's bus should carry frames only")
        self.assertGreater(len(expected), 10)
        self.assertEqual([f[0] for f in found], [e[0] for e in expected],
                         "raw bytes differ; tshark said:\n" + err)
        self.assertEqual(found, expected)


if __name__ == "__main__":
    unittest.main()
