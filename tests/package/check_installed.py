"""The installed pvtap package, used as a field engineer would: as an unprivileged user, with a
clean environment (no WIRESHARK_* variable), tshark and pvtap from PATH.

Run by check_install.sh (as root) between dpkg -i and dpkg -r.
Usage: check_installed.py --version VERSION --home DIR
"""
import argparse
import json
import os
import re
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "analyzer", "extcap"))
sys.path.insert(0, os.path.join(HERE, "..", "dissector"))
sys.path.insert(0, os.path.join(HERE, "..", "analyzer", "sniff"))

import extcap_home  # noqa: E402  (tests/analyzer/extcap: ptys the unprivileged user may open)
import tshark_runner  # noqa: E402  (tests/dissector: the unprivileged user's id)

NOBODY = tshark_runner.NOBODY
EXAMPLES = "/usr/share/doc/pvtap/examples"
DEMO = os.path.join(EXAMPLES, "demo.gateway.pcap")
PLUGIN_FOLDER = tshark_runner.global_plugin_folder()


def demo_truth():
    """The summary of the installed demo's ground truth."""
    with open(os.path.join(EXAMPLES, "demo.truth.json"), encoding="utf-8") as f:
        return json.load(f)["summary"]


class Checks:
    def __init__(self):
        self.failures = []

    def true(self, what, condition, detail=""):
        print(("ok: " if condition else "FAIL: ") + what)
        if not condition:
            self.failures.append(what)
            if detail:
                print("  " + detail.replace("\n", "\n  ")[:3000])


class User:
    """Commands run as the unprivileged user, with only HOME, PATH and LC_ALL set."""

    def __init__(self, home):
        self.home = home
        os.makedirs(home, exist_ok=True)
        os.chown(home, NOBODY, NOBODY)

    def run(self, args, extra_env=(), timeout=120):
        command = ["setpriv", "--reuid=%d" % NOBODY, "--regid=%d" % NOBODY, "--clear-groups",
                   "env", "-i", "HOME=" + self.home, "PATH=/usr/bin:/bin", "LC_ALL=C.UTF-8",
                   *extra_env, *args]
        return subprocess.run(command, capture_output=True, text=True, timeout=timeout,
                              cwd="/")


def check_program(user, version, checks):
    result = user.run(["pvtap", "--version"])
    lines = result.stdout.splitlines()
    checks.true("pvtap --version is the package's version %s" % version,
                result.returncode == 0 and lines[:1] == ["pvtap " + version], result.stdout)
    installed = re.fullmatch(r"Wireshark plugin for Wireshark \d+\.\d+: installed, "
                             r"(/usr/lib/\S+/wireshark/plugins/\d+\.\d+/epan/pvtap\.so)",
                             lines[1] if len(lines) == 2 else "")
    checks.true("pvtap --version names the installed plugin of the package",
                installed is not None and os.path.isfile(installed.group(1)), result.stdout)
    frames = demo_truth()["frames"]
    result = user.run(["pvtap", "audit", "--summary-only", DEMO])
    checks.true("pvtap audit prints the report of the installed demo capture (%d frames)"
                % frames,
                result.returncode == 0 and "== pvtap audit report ==" in result.stdout
                and ("frames: %d " % frames) in result.stdout, result.stdout + result.stderr)
    maps = sorted(os.listdir("/usr/share/pvtap/maps"))
    checks.true("the built-in maps and their format are in /usr/share/pvtap/maps",
                maps == ["README.md", "ascii.toml", "gsl.toml", "hybrid.toml"], str(maps))
    for name in ("ascii.toml", "gsl.toml", "hybrid.toml"):
        result = user.run(["pvtap", "audit", "--summary-only", "--map",
                           os.path.join("/usr/share/pvtap/maps", name), DEMO])
        checks.true("the installed %s loads as a --map" % name, result.returncode == 0,
                    result.stderr)


def check_plugin(user, checks):
    result = user.run(["tshark", "-G", "plugins"])
    plugin = os.path.join(PLUGIN_FOLDER, "epan", "pvtap.so")
    rows = [line for line in result.stdout.splitlines() if line.startswith("pvtap.so")]
    checks.true("tshark -G plugins lists pvtap.so once, from %s" % plugin,
                len(rows) == 1 and rows[0].split("\t")[-1] == plugin, result.stdout)
    result = user.run(["tshark", "-r", DEMO, "-Y", "invrtu || invascii"])
    checks.true("tshark -r demo.gateway.pcap shows decoded frames",
                result.returncode == 0 and len(result.stdout.splitlines()) > 100
                and "invrtu" in result.stdout.lower(),
                result.stdout[:500] + result.stderr)
    # The link-type-252 copy of the demo, frame for frame against its ground truth.
    summary = demo_truth()
    result = user.run(["tshark", "-r", os.path.join(EXAMPLES, "demo.pdu.pcap"), "-T", "fields",
                       "-e", "invrtu.crc.status", "-e", "invascii.checksum.status"])
    verdicts = result.stdout.split()
    checks.true("tshark on demo.pdu.pcap: %d frames, %d bad checks as in demo.truth.json"
                % (summary["frames"], summary["bad_checks"]),
                result.returncode == 0 and len(verdicts) == summary["frames"]
                and verdicts.count("0") == summary["bad_checks"],
                "%d verdicts, %d bad\n%s" % (len(verdicts), verdicts.count("0"), result.stderr))


def check_capture_interfaces(user, checks):
    ptys = [extcap_home.ReadablePty(), extcap_home.ReadablePty()]
    try:
        ports = "PVTAP_SERIAL_PORTS=" + ":".join(p.path for p in ptys)
        result = user.run(["tshark", "-D"], [ports])
        for pty in ptys:
            name = extcap_home.interface_of(pty.path)
            line = [row for row in result.stdout.splitlines() if name in row]
            checks.true("tshark -D lists the RS485 tap %s" % name,
                        len(line) == 1 and "RS485 tap" in line[0], result.stdout + result.stderr)
    finally:
        for pty in ptys:
            pty.close()


def check_man_pages(user, checks):
    for page in ("pvtap", "pvtap-audit", "pvtap-sniff", "pvtap-diff"):
        result = user.run(["man", "-w", page])
        expected = "/usr/share/man/man1/%s.1.gz" % page
        checks.true("man -w %s finds %s" % (page, expected),
                    result.returncode == 0 and result.stdout.strip() == expected,
                    result.stdout + result.stderr)
    result = user.run(["man", "pvtap-sniff"], ["MANWIDTH=200"])
    checks.true("man pvtap-sniff explains serial access (dialout, the udev rule)",
                result.returncode == 0 and "dialout" in result.stdout
                and "60-pvtap-ftdi-latency.rules" in result.stdout, result.stderr)


def check_completion_and_udev(user, checks):
    script = ("source /usr/share/bash-completion/bash_completion; "
              "__load_completion pvtap && complete -p pvtap")
    result = user.run(["bash", "-c", script])
    checks.true("bash-completion loads the installed completion for pvtap",
                result.returncode == 0 and "-F _pvtap pvtap" in result.stdout,
                result.stdout + result.stderr)
    rule = "/usr/share/pvtap/udev/60-pvtap-ftdi-latency.rules"
    enabled = [d for d in ("/etc/udev/rules.d", "/lib/udev/rules.d", "/usr/lib/udev/rules.d")
               if os.path.exists(os.path.join(d, os.path.basename(rule)))]
    checks.true("the udev rule is shipped but not enabled", os.path.isfile(rule) and not enabled,
                str(enabled))


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--version", required=True)
    parser.add_argument("--home", required=True)
    options = parser.parse_args()
    if os.geteuid() != 0:
        print("check_installed.py: needs root (to drop to user %d)" % NOBODY)
        return 1
    user = User(options.home)
    checks = Checks()
    check_program(user, options.version, checks)
    check_plugin(user, checks)
    check_capture_interfaces(user, checks)
    check_man_pages(user, checks)
    check_completion_and_udev(user, checks)
    if checks.failures:
        print("%d check(s) of the installed package failed" % len(checks.failures))
        return 1
    print("all checks of the installed package hold")
    return 0


if __name__ == "__main__":
    sys.exit(main())
