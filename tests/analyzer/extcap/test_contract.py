"""pvtap's answers to Wireshark's extcap calls, and its --capture on a real fifo and pty.

pvtap is run directly, as Wireshark runs it; the port it finds is a pty passed through
PVTAP_SERIAL_PORTS.
"""
import os
import select
import signal
import struct
import subprocess
import tempfile
import time
import unittest

from extcap_home import ReadablePty, interface_of, pty_bus, pvtap_path

# Longest wait for pvtap to start, answer or stop: a guard against hangs, not a timing check.
GUARD_S = 20
PCAP_HEADER = 24
RECORD_HEADER = 16
# A GSL (Modbus RTU) read request: station 1, function 3, start 0, count 10, CRC.
FRAME = bytes.fromhex("01030000000ac5cd")
# Station 1 reading one register, and its reply: a pair that settles a rate search.
PAIR_REQUEST = bytes.fromhex("010300000001840a")
PAIR_REPLY = bytes.fromhex("010302002a399b")


def run_pvtap(args, ports=()):
    env = dict(os.environ, PVTAP_SERIAL_PORTS=":".join(ports))
    return subprocess.run([pvtap_path()] + list(args), capture_output=True, text=True, env=env,
                          timeout=GUARD_S)


def read_exactly(fd, count):
    """`count` bytes from the fifo; fewer when it ends or nothing comes for GUARD_S."""
    got = b""
    while len(got) < count:
        ready, _, _ = select.select([fd], [], [], GUARD_S)
        if not ready:
            break
        try:
            chunk = os.read(fd, count - len(got))
        except BlockingIOError:
            continue
        if not chunk:
            break
        got += chunk
    return got


class Answers(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.pty = ReadablePty()
        cls.interface = interface_of(cls.pty.path)

    @classmethod
    def tearDownClass(cls):
        cls.pty.close()

    def test_interfaces_lists_the_pty_as_an_rs485_tap(self):
        result = run_pvtap(["--extcap-interfaces", "--extcap-version=4.0"], [self.pty.path])
        self.assertEqual(result.returncode, 0, result.stderr)
        lines = result.stdout.splitlines()
        self.assertTrue(lines[0].startswith("extcap {version="), lines)
        expected = "interface {value=%s}{display=RS485 tap (%s)}" % (self.interface,
                                                                   self.pty.name())
        self.assertIn(expected, lines)

    def test_interfaces_skip_ports_that_do_not_exist(self):
        result = run_pvtap(["--extcap-interfaces"], ["/dev/pts/does-not-exist"])
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertNotIn("does-not-exist", result.stdout)

    def test_dlts_is_exported_pdus(self):
        result = run_pvtap(["--extcap-dlts", "--extcap-interface", self.interface],
                           [self.pty.path])
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertEqual(len(result.stdout.splitlines()), 1)
        self.assertTrue(result.stdout.startswith("dlt {number=252}{name=pvtap}"), result.stdout)

    def test_config_offers_five_selectors_with_defaults(self):
        result = run_pvtap(["--extcap-config", "--extcap-interface", self.interface],
                           [self.pty.path])
        self.assertEqual(result.returncode, 0, result.stderr)
        args = [line for line in result.stdout.splitlines() if line.startswith("arg ")]
        expected = [("--baud", "9600"), ("--parity", "none"), ("--stop-bits", "1"),
                    ("--dialect", "auto"), ("--duplex-replies", "none")]
        self.assertEqual(len(args), len(expected), result.stdout)
        for number, (line, (call, default)) in enumerate(zip(args, expected)):
            self.assertIn("{number=%d}{call=%s}" % (number, call), line)
            self.assertIn("{type=selector}{default=%s}" % default, line)
            self.assertIn("value {arg=%d}{value=%s}" % (number, default), result.stdout)
        self.assertIn("value {arg=0}{value=auto}", result.stdout)

    def test_unknown_interface_is_refused(self):
        result = run_pvtap(["--capture", "--extcap-interface", "pvtap-nothing", "--fifo",
                            "/nonexistent/fifo"], [self.pty.path])
        self.assertEqual(result.returncode, 2)
        self.assertIn("no serial port for interface pvtap-nothing", result.stderr)

    def test_capture_filter_is_refused(self):
        check = run_pvtap(["--extcap-interface", self.interface, "--extcap-capture-filter",
                           "tcp port 502"], [self.pty.path])
        self.assertEqual(check.returncode, 0, check.stderr)
        self.assertIn("no capture filter", check.stdout)
        empty = run_pvtap(["--extcap-interface", self.interface, "--extcap-capture-filter", ""],
                          [self.pty.path])
        self.assertEqual((empty.returncode, empty.stdout), (0, ""))
        capture = run_pvtap(["--capture", "--extcap-interface", self.interface, "--fifo",
                             "/nonexistent/fifo", "--extcap-capture-filter", "tcp"],
                            [self.pty.path])
        self.assertEqual(capture.returncode, 2)
        self.assertIn("no capture filter", capture.stderr)

    def test_settings_outside_the_choices_are_refused(self):
        result = run_pvtap(["--capture", "--extcap-interface", self.interface, "--fifo",
                            "/nonexistent/fifo", "--baud", "1234"], [self.pty.path])
        self.assertEqual(result.returncode, 2)
        self.assertIn("--baud 1234", result.stderr)

    def test_a_replies_pair_that_is_missing_or_searched_is_refused(self):
        base = ["--capture", "--extcap-interface", self.interface, "--fifo", "/nonexistent/fifo"]
        for extra, words in ((["--duplex-replies", "pvtap-nothing"], "pvtap-nothing"),
                             (["--duplex-replies", self.interface], "own tap")):
            result = run_pvtap(base + extra, [self.pty.path])
            self.assertEqual(result.returncode, 2, result.stderr)
            self.assertIn(words, result.stderr)

    def test_no_question_is_a_usage_error(self):
        result = run_pvtap(["--extcap-interface", self.interface])
        self.assertEqual(result.returncode, 2)
        self.assertIn("needs --extcap-interfaces", result.stderr)


class Capture(unittest.TestCase):
    """`--capture --fifo`: the pcap header at once, a record per frame, a clean stop."""

    BAUD = "9600"

    def setUp(self):
        self.pty = ReadablePty()
        self.folder = tempfile.mkdtemp(prefix="pvtap-extcap-")
        self.fifo = os.path.join(self.folder, "fifo")
        os.mkfifo(self.fifo)
        env = dict(os.environ, PVTAP_SERIAL_PORTS=self.pty.path)
        self.proc = subprocess.Popen(
            [pvtap_path(), "--capture", "--extcap-interface", interface_of(self.pty.path),
             "--fifo", self.fifo, "--baud", self.BAUD, "--dialect", "gsl"],
            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=env)
        # As Wireshark does: the reader opens the fifo, pvtap's open completes with it. Not
        # blocking, so that a pvtap that never opens the fifo fails the test instead of hanging
        # it (until a writer came, select() does not see the fifo readable).
        self.reader = os.open(self.fifo, os.O_RDONLY | os.O_NONBLOCK)

    def tearDown(self):
        if self.proc.poll() is None:
            self.proc.kill()
        self.proc.communicate()
        if self.reader is not None:
            os.close(self.reader)
        self.pty.close()
        os.unlink(self.fifo)
        os.rmdir(self.folder)

    def header(self):
        data = read_exactly(self.reader, PCAP_HEADER)
        self.assertEqual(len(data), PCAP_HEADER, "no pcap header before any traffic")
        magic, _, _, _, _, _, link_type = struct.unpack("<IHHiIII", data)
        self.assertEqual(magic, 0xA1B2C3D4)
        return link_type

    def wait_open(self):
        for _ in range(GUARD_S * 100):
            if self.proc.poll() is not None:
                self.fail("pvtap exited %d: %s" % (self.proc.returncode, self.proc.stderr.read()))
            if os.path.exists("/proc/%d/fd" % self.proc.pid) and any(
                    os.path.realpath("/proc/%d/fd/%s" % (self.proc.pid, fd)) == self.pty.path
                    for fd in os.listdir("/proc/%d/fd" % self.proc.pid)):
                return
            time.sleep(0.01)
        self.fail("pvtap never opened " + self.pty.path)

    def stop(self):
        self.proc.send_signal(signal.SIGTERM)
        try:
            self.proc.wait(GUARD_S)
        except subprocess.TimeoutExpired:
            self.fail("pvtap did not stop on SIGTERM")
        return self.proc.returncode

    def test_header_comes_at_once_and_frames_as_they_complete(self):
        self.assertEqual(self.header(), 252)
        self.wait_open()
        os.write(self.pty.master, FRAME)
        record = read_exactly(self.reader, RECORD_HEADER)
        self.assertEqual(len(record), RECORD_HEADER, "no record for the frame")
        _, _, caplen, _ = struct.unpack("<IIII", record)
        body = read_exactly(self.reader, caplen)
        self.assertTrue(body.endswith(FRAME), body.hex())
        self.assertIn(b"pvtap\0", body)
        self.assertEqual(self.stop(), 0, self.proc.stderr.read())

    def test_sigterm_on_a_quiet_bus_exits_zero(self):
        self.header()
        self.wait_open()
        self.assertEqual(self.stop(), 0, self.proc.stderr.read())
        self.assertEqual(read_exactly(self.reader, 1), b"", "data after the capture ended")

    def test_a_closed_fifo_ends_the_capture(self):
        self.header()
        self.wait_open()
        os.close(self.reader)
        self.reader = None
        # The record of this frame is written into a broken pipe.
        os.write(self.pty.master, FRAME)
        try:
            self.proc.wait(GUARD_S)
        except subprocess.TimeoutExpired:
            self.fail("pvtap kept capturing after the reader left")
        self.assertNotEqual(self.proc.returncode, -signal.SIGPIPE, "killed by SIGPIPE")
        self.assertEqual(self.proc.returncode, 0, self.proc.stderr.read())


class AutoBaudCapture(Capture):
    """The baud selector's Auto: the tap searches its settings; a pty carries any rate, so the
    first one tried settles on a request and its reply, and both reach the fifo."""

    BAUD = "auto"

    def record_body(self):
        record = read_exactly(self.reader, RECORD_HEADER)
        self.assertEqual(len(record), RECORD_HEADER, "no record")
        _, _, caplen, _ = struct.unpack("<IIII", record)
        return read_exactly(self.reader, caplen)

    def test_header_comes_at_once_and_frames_as_they_complete(self):
        self.assertEqual(self.header(), 252)
        self.wait_open()
        os.write(self.pty.master, PAIR_REQUEST)
        time.sleep(0.1)
        os.write(self.pty.master, PAIR_REPLY)
        self.assertTrue(self.record_body().endswith(PAIR_REQUEST))
        self.assertTrue(self.record_body().endswith(PAIR_REPLY))
        self.assertEqual(self.stop(), 0, self.proc.stderr.read())

    def test_a_closed_fifo_ends_the_capture(self):
        self.header()
        self.wait_open()
        os.close(self.reader)
        self.reader = None
        os.write(self.pty.master, PAIR_REQUEST + PAIR_REPLY)
        try:
            self.proc.wait(GUARD_S)
        except subprocess.TimeoutExpired:
            self.fail("pvtap kept capturing after the reader left")
        self.assertEqual(self.proc.returncode, 0, self.proc.stderr.read())


if __name__ == "__main__":
    unittest.main()


class DuplexCapture(unittest.TestCase):
    """A 4-wire bus: the capture's interface on the requests' pair, --duplex-replies naming the
    tap on the replies' pair; the request and its reply reach the fifo as one bus's records."""

    def setUp(self):
        self.requests, self.replies = ReadablePty(), ReadablePty()
        self.folder = tempfile.mkdtemp(prefix="pvtap-extcap-")
        self.fifo = os.path.join(self.folder, "fifo")
        os.mkfifo(self.fifo)
        env = dict(os.environ, PVTAP_SERIAL_PORTS=self.requests.path + ":" + self.replies.path)
        self.proc = subprocess.Popen(
            [pvtap_path(), "--capture", "--extcap-interface", interface_of(self.requests.path),
             "--fifo", self.fifo, "--baud", "9600", "--dialect", "gsl",
             "--duplex-replies", interface_of(self.replies.path)],
            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=env)
        self.reader = os.open(self.fifo, os.O_RDONLY | os.O_NONBLOCK)

    def tearDown(self):
        if self.proc.poll() is None:
            self.proc.kill()
        self.proc.communicate()
        os.close(self.reader)
        self.requests.close()
        self.replies.close()
        os.unlink(self.fifo)
        os.rmdir(self.folder)

    def opened(self, path):
        fds = "/proc/%d/fd" % self.proc.pid
        return os.path.exists(fds) and any(
            os.path.realpath(os.path.join(fds, fd)) == path for fd in os.listdir(fds))

    def record_body(self):
        record = read_exactly(self.reader, RECORD_HEADER)
        self.assertEqual(len(record), RECORD_HEADER, "no record")
        _, _, caplen, _ = struct.unpack("<IIII", record)
        return read_exactly(self.reader, caplen)

    def test_request_and_reply_from_two_taps_are_one_bus(self):
        self.assertEqual(len(read_exactly(self.reader, PCAP_HEADER)), PCAP_HEADER)
        for _ in range(GUARD_S * 100):
            if self.opened(self.requests.path) and self.opened(self.replies.path):
                break
            if self.proc.poll() is not None:
                self.fail("pvtap exited %d: %s" % (self.proc.returncode, self.proc.stderr.read()))
            time.sleep(0.01)
        os.write(self.requests.master, PAIR_REQUEST)
        time.sleep(0.1)
        os.write(self.replies.master, PAIR_REPLY)
        first, second = self.record_body(), self.record_body()
        self.assertTrue(first.endswith(PAIR_REQUEST), first.hex())
        self.assertTrue(second.endswith(PAIR_REPLY), second.hex())
        bus = (self.requests.path + "+" + self.replies.path).encode()
        self.assertIn(bus, first + second, "the records do not name the one bus of both taps")
        self.proc.send_signal(signal.SIGTERM)
        self.assertEqual(self.proc.wait(GUARD_S), 0, self.proc.stderr.read())
        self.assertEqual(self.requests.drain_master() + self.replies.drain_master(), b"",
                         "pvtap wrote to a tap")
