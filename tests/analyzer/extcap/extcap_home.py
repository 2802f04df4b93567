"""tshark with pvtap's plugin and pvtap as an extcap, both from the build tree, and a pty for
pvtap to find.

tshark 4.0 looks for extcaps in one folder only, the global one, unless WIRESHARK_EXTCAP_DIR
names another (honoured when tshark runs unprivileged, which TsharkHome arranges). pvtap goes
there as a copy of the built binary (`cmake --install` links it into the global folder).
"""
import os
import shutil
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "dissector"))
sys.path.insert(0, os.path.join(HERE, "..", "sniff"))

import pty_bus  # noqa: E402  (tests/analyzer/sniff: the pty and the paced writer)
import tshark_runner  # noqa: E402  (tests/dissector: the temporary HOME with the plugin)

EXTCAP_SUBDIR = ".local/lib/wireshark/extcap"


def pvtap_path():
    path = os.environ.get("PVTAP_BINARY")
    if not path or not os.access(path, os.X_OK):
        raise RuntimeError("PVTAP_BINARY must name the built pvtap (got %r)" % path)
    return os.path.abspath(path)


def interface_of(pty_path):
    """The interface name pvtap's discovery gives a port under /dev."""
    return "pvtap-" + os.path.relpath(pty_path, "/dev").replace("/", "-")


class ReadablePty(pty_bus.Pty):
    """A pty whose slave side the unprivileged tshark (and so pvtap) may open."""

    def __init__(self):
        super().__init__()
        if os.geteuid() == 0:
            os.chown(self.path, tshark_runner.NOBODY, tshark_runner.NOBODY)
        os.chmod(self.path, 0o660)

    def name(self):
        return os.path.relpath(self.path, "/dev")


class ExtcapHome(tshark_runner.TsharkHome):
    """TsharkHome with pvtap in an extcap folder and the variables pvtap needs passed on."""

    def __init__(self, serial_ports=()):
        super().__init__()
        self.extcap_dir = os.path.join(self.home, EXTCAP_SUBDIR)
        os.makedirs(self.extcap_dir)
        # A copy, not a link: the build tree may lie in a folder the unprivileged user
        # cannot enter (a CI checkout under a 0700 temporary folder).
        shutil.copy(pvtap_path(), os.path.join(self.extcap_dir, "pvtap"))
        self.serial_ports = list(serial_ports)
        self._hand_over()

    def environment(self):
        # tshark starts its extcaps with its own environment; that is how the ports reach pvtap.
        return super().environment() + ["WIRESHARK_EXTCAP_DIR=" + self.extcap_dir,
                                        "PVTAP_SERIAL_PORTS=" + ":".join(self.serial_ports)]

    def start(self, args):
        """tshark in the background, its output in pipes."""
        return subprocess.Popen(self.command(args), stdout=subprocess.PIPE,
                                stderr=subprocess.PIPE, text=True)


def holders_of(path):
    """The pids of other processes that hold `path` open."""
    real = os.path.realpath(path)
    pids = []
    for pid in filter(str.isdigit, os.listdir("/proc")):
        if int(pid) == os.getpid():
            continue
        try:
            fds = os.listdir("/proc/%s/fd" % pid)
        except OSError:
            continue
        for fd in fds:
            try:
                if os.readlink("/proc/%s/fd/%s" % (pid, fd)) == real:
                    pids.append(int(pid))
                    break
            except OSError:
                continue
    return pids
