#!/usr/bin/env python3
"""The HTML report of a day of a large bus: its size and how long Chromium takes to show it.

  bench/html_report_bench.py [--build build] [--hours 24] [--inverters 16] [--repeat 3]

pvtap-sim writes HOURS of a mixed bus of INVERTERS stations (GSL, Hybrid and ASCII in turn,
a poll round every 5 s at 9600 baud, 1 % of each fault kind) as a link type 252 capture,
`pvtap audit --summary-only --html` turns it into a report (timed, with its peak RSS), and
Debian's headless chromium opens the file with no network (see tests/analyzer/report): the
figure is the time from navigation to the page's script having drawn every chart
(window.pvtap.ready), median of REPEAT fresh browsers. Targets (issue "See the bus"): under 10 MB, under 3 s.
"""

import argparse
import os
import statistics
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "tests", "analyzer", "report"))
from headless_chromium import HeadlessChromium, find_chromium  # noqa: E402

FAULTS = ("corrupt=1,missing=1,slow=1,noise=1,error_reply=1,count_mismatch=1,duplicate=1,"
          "corrupt_request=1")


def load_time(chromium, html):
    browser = HeadlessChromium(chromium)
    try:
        browser.open_page(1200, 900)
        started = time.monotonic()
        browser.navigate("file://" + os.path.abspath(html), timeout=120)
        while not browser.evaluate("!!(window.pvtap && window.pvtap.ready)"):
            time.sleep(0.02)
        return time.monotonic() - started
    finally:
        browser.close()


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--build", default=os.path.join(HERE, "..", "build"))
    p.add_argument("--hours", type=float, default=24)
    p.add_argument("--inverters", type=int, default=16)
    p.add_argument("--repeat", type=int, default=3)
    p.add_argument("--keep", help="folder to keep the capture and the report in")
    a = p.parse_args()
    chromium = find_chromium()
    if chromium is None:
        sys.exit("html_report_bench: no chromium (apt-get install chromium)")
    work = a.keep or tempfile.mkdtemp(prefix="pvtap-html-bench-")
    os.makedirs(work, exist_ok=True)
    capture, html = os.path.join(work, "bus.pcap"), os.path.join(work, "report.html")
    subprocess.run([os.path.join(a.build, "captures", "pvtap-sim"), "--seed", "24",
                    "--dialect", "gsl,hybrid,ascii", "--inverters", str(a.inverters),
                    "--duration", str(a.hours * 3600), "--period", "5",
                    "--start", "1782000000", "--faults", FAULTS, "--pdu", capture], check=True)
    started = time.monotonic()
    audit = subprocess.Popen([os.path.join(a.build, "analyzer", "pvtap"), "audit",
                              "--summary-only", "--html", html, capture],
                             stdout=subprocess.DEVNULL)
    _, status, usage = os.wait4(audit.pid, 0)  # this child's own peak, not the simulator's
    audit.returncode = os.waitstatus_to_exitcode(status)
    audit_s = time.monotonic() - started
    if audit.returncode != 0:
        sys.exit("html_report_bench: pvtap audit exited %d" % audit.returncode)
    rss_mb = usage.ru_maxrss / 1024
    loads = [load_time(chromium, html) for _ in range(a.repeat)]
    print("capture: %.1f h, %d stations, %.1f MB" % (a.hours, a.inverters,
                                                     os.path.getsize(capture) / 1e6))
    print("pvtap audit --summary-only --html: %.2f s, peak RSS %.0f MB" % (audit_s, rss_mb))
    print("report: %.2f MB" % (os.path.getsize(html) / 1e6))
    print("chromium, navigation to all charts drawn: %s s (median %.2f s)"
          % (", ".join("%.2f" % t for t in loads), statistics.median(loads)))


if __name__ == "__main__":
    main()
