"""Runs the real tshark with the plugin under test loaded from a temporary personal folder.

tshark run as root ignores the personal plugin folder (and WIRESHARK_PLUGIN_DIR), so as root
it runs as the unprivileged user 65534 through setpriv.

A pvtap.so in tshark's global plugin folder (an installed pvtap package) would be loaded as
well as the one under test and make every run fail on duplicate registrations; TsharkHome
refuses to start then, saying so (refuse_system_plugin).
"""

import functools
import glob
import json
import os
import re
import shutil
import subprocess
import tempfile

NOBODY = 65534
# tshark -T fields writes a boolean field as 1/0 up to 4.0 and as True/False from 4.2 on.
BOOLEANS = {"True": "1", "False": "0"}


def plugin_path():
    path = os.environ.get("PVTAP_PLUGIN")
    if not path or not os.path.isfile(path):
        raise RuntimeError("PVTAP_PLUGIN must name the built pvtap.so (got %r)" % path)
    return path


@functools.lru_cache(maxsize=None)
def wireshark_series():
    """The major.minor of the tshark on PATH ("4.4"): a plugin loads only from the personal
    folder of the series it was built for."""
    banner = subprocess.run(["env", "-i", "PATH=/usr/sbin:/usr/bin:/sbin:/bin", "LC_ALL=C.UTF-8",
                             "tshark", "--version"], capture_output=True, text=True,
                            timeout=60).stdout
    match = re.search(r"TShark \(Wireshark\) (\d+)\.(\d+)\.", banner)
    if not match:
        raise RuntimeError("tshark --version names no Wireshark version:\n" + banner[:200])
    return "%s.%s" % match.groups()


def plugin_subdir():
    """The personal plugin folder for epan plugins, relative to HOME."""
    return os.path.join(".local", "lib", "wireshark", "plugins", wireshark_series(), "epan")


@functools.lru_cache(maxsize=None)
def global_plugin_folder():
    """tshark's global plugin folder, as `tshark -G folders` names it (asked once)."""
    listing = subprocess.run(["env", "-i", "PATH=/usr/sbin:/usr/bin:/sbin:/bin", "LC_ALL=C.UTF-8",
                              "tshark", "-G", "folders"], capture_output=True, text=True,
                             timeout=60).stdout
    for line in listing.splitlines():
        name, _, folder = line.partition(":")
        if name.strip() == "Global Plugins":
            return folder.strip()
    raise RuntimeError("tshark -G folders names no global plugin folder:\n" + listing)


def system_plugin_copies():
    """The pvtap.so files that tshark would load from its global plugin folder."""
    folder = global_plugin_folder()
    return sorted(glob.glob(os.path.join(folder, "pvtap.so")) +
                  glob.glob(os.path.join(folder, "*", "pvtap.so")))


def refuse_system_plugin():
    """Fails with the reason when a system-wide pvtap.so would be loaded next to the test's."""
    copies = system_plugin_copies()
    if copies:
        raise RuntimeError(
            "a system-wide pvtap.so is installed (%s): tshark would load it as well as the "
            "plugin under test, and every test would fail on duplicate protocol registrations. "
            "Remove it first (dpkg -r pvtap, or delete the file left by cmake --install)."
            % ", ".join(copies))


# The longest one tshark run may take before it is given up (see TsharkHome.run).
RUN_TIMEOUT_S = 90


def as_text(output):
    """What a killed process had printed (bytes or text, or None)."""
    if output is None:
        return ""
    return output.decode(errors="replace") if isinstance(output, bytes) else output


class TsharkHome:
    """A temporary HOME holding the plugin, user register maps and the test captures."""

    def __init__(self, user_maps=None):
        refuse_system_plugin()
        self.home = tempfile.mkdtemp(prefix="pvtap-tshark-")
        plugins = os.path.join(self.home, plugin_subdir())
        os.makedirs(plugins)
        shutil.copy(plugin_path(), os.path.join(plugins, "pvtap.so"))
        config = os.path.join(self.home, ".config", "wireshark")
        os.makedirs(config)
        for name, text in (user_maps or {}).items():
            os.makedirs(os.path.join(config, "pvtap"), exist_ok=True)
            with open(os.path.join(config, "pvtap", name), "w") as f:
                f.write(text)
        self._hand_over()

    def _hand_over(self):
        if os.geteuid() != 0:
            return
        for root, dirs, files in os.walk(self.home):
            for name in [root] + [os.path.join(root, n) for n in dirs + files]:
                os.chown(name, NOBODY, NOBODY)

    def path(self, name):
        return os.path.join(self.home, name)

    def write_text(self, name, text, config=False):
        """A file in HOME, or with config=True in the personal configuration folder (a UAT's
        file, for example); returns its path."""
        path = os.path.join(self.home, ".config", "wireshark", name) if config else self.path(name)
        with open(path, "w") as f:
            f.write(text)
        self._hand_over()
        return path

    def write(self, name, pcap):
        path = self.path(name)
        pcap.write(path)
        self._hand_over()
        return path

    def environment(self):
        """tshark's whole environment (it starts with none)."""
        return ["HOME=" + self.home, "PATH=/usr/sbin:/usr/bin:/sbin:/bin", "LC_ALL=C.UTF-8"]

    def command(self, args):
        command = ["env", "-i"] + self.environment() + ["tshark"] + list(args)
        if os.geteuid() == 0:
            command = ["setpriv", "--reuid=%d" % NOBODY, "--regid=%d" % NOBODY,
                       "--clear-groups"] + command
        return command

    def run(self, args, check=True, timeout=RUN_TIMEOUT_S):
        """tshark ARGS to its end. A guard, not a timing check: a tshark that has not ended
        after `timeout` seconds is killed, and the failure says which run it was and what it
        had printed, before the test's own CTest timeout can end it without a word."""
        try:
            result = subprocess.run(self.command(args), capture_output=True, text=True,
                                    timeout=timeout)
        except subprocess.TimeoutExpired as e:
            raise AssertionError("tshark %s: still running after %d s (killed); it printed:\n%s%s"
                                 % (" ".join(args), timeout, as_text(e.stdout),
                                    as_text(e.stderr))) from None
        if check and result.returncode != 0:
            raise AssertionError("tshark %s failed (%d):\n%s" % (" ".join(args), result.returncode,
                                                                 result.stderr))
        return result

    def loaded_plugins(self):
        return self.run(["-G", "plugins"]).stdout

    def fields(self, capture, fields, display_filter=None, options=()):
        """One row per packet: a list of occurrence lists, one per field."""
        args = ["-r", capture, "-2", "-T", "fields", "-E", "occurrence=a", "-E",
                "aggregator=|"]
        for field in fields:
            args += ["-e", field]
        if display_filter:
            args += ["-Y", display_filter]
        rows = []
        for line in self.run(list(options) + args).stdout.splitlines():
            cells = line.split("\t")
            rows.append([[BOOLEANS.get(v, v) for v in cell.split("|")] if cell else []
                         for cell in cells])
        return rows

    def json(self, capture, options=()):
        out = self.run(list(options) + ["-r", capture, "-2", "-T", "json",
                                        "--no-duplicate-keys"]).stdout
        return json.loads(out)

    def verbose(self, capture, options=()):
        return self.run(list(options) + ["-r", capture, "-2", "-V"]).stdout

    def close(self):
        shutil.rmtree(self.home, ignore_errors=True)


class PluginTestCase:
    """Mixin for unittest.TestCase: a TsharkHome per class, and the plugin-loaded assertion."""

    user_maps = None

    @classmethod
    def setUpClass(cls):
        cls.tshark = TsharkHome(cls.user_maps)
        listing = cls.tshark.loaded_plugins()
        if "pvtap.so" not in listing:
            cls.tshark.close()
            raise AssertionError("tshark did not load pvtap.so:\n" + listing)

    @classmethod
    def tearDownClass(cls):
        cls.tshark.close()
