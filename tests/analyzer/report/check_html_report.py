#!/usr/bin/env python3
"""pvtap audit --html in a real browser: Debian's headless chromium opens the report of a
capture from disk with no network, and the page must show what the report model says.

  check_html_report.py PVTAP CAPTURE OUT_DIR

Checks: no console error or uncaught exception; no request for anything but the file itself;
the overview tiles equal the jsonl summary's numbers; the timeline holds as many marks of each
kind as the summary counts (and its request/reply buckets add up to the summary's requests and
responses); the last point of every numeric value chart equals that register's "latest value"
in the text report. A screenshot of the page goes to OUT_DIR/NAME.png.
Exit 77 (skipped) when chromium is not installed.
"""

import json
import os
import re
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from headless_chromium import HeadlessChromium, find_chromium  # noqa: E402

# The longest one program this test runs may take: a guard, not a timing check. On expiry
# subprocess raises TimeoutExpired, which names the command that was waited for.
RUN_GUARD_S = 120

# What the page is asked, from inside: the tiles as shown, the timeline's points per kind read
# back from the dygraph (requests/replies weighted by the bucket counts), and the last point of
# every series of every value chart.
PAGE_CHECK = r"""
(() => {
  const tiles = {};
  document.querySelectorAll('.tile').forEach(t => {
    tiles[t.dataset.key] = Number(t.querySelector('.value').textContent);
  });
  const g = pvtap.charts.timeline, labels = g.getLabels(), marks = {};
  for (let col = 1; col < labels.length; ++col) {
    const name = labels[col], kind = name.split('|')[0], details = pvtap.details[name];
    for (let row = 0; row < g.numRows(); ++row) {
      if (g.getValue(row, col) === null) continue;
      const x = g.getValue(row, 0);
      const n = details.counts ? details.counts.get(x) : 1;
      marks[kind] = (marks[kind] || 0) + n;
    }
  }
  const last = [];
  pvtap.charts.values.forEach(v => {
    v.series.forEach((s, i) => {
      if (s.step) return;
      for (let row = v.chart.numRows() - 1; row >= 0; --row) {
        const value = v.chart.getValue(row, i + 1);
        if (value === null || value === undefined) continue;
        // A banded chart's point is [min, last, max] of its bucket; a plain one's the last.
        last.push({label: s.label, lane: pvtap.data.lanes[s.lane].label, dialect: s.dialect,
                   address: s.address, key: s.key,
                   value: Array.isArray(value) ? value[1] : value});
        break;
      }
    });
  });
  return JSON.stringify({tiles, marks, last,
                         dropped: pvtap.data.marks_dropped});
})()
"""

# Where the first mark of a kind is on the screen, after scrolling the timeline into view.
MARK_POSITION = r"""
((kind) => {
  const g = pvtap.charts.timeline, details = pvtap.details[kind];
  if (!details || details.size === 0) return null;
  const labels = g.getLabels(), col = labels.indexOf(kind);
  document.getElementById('timeline-chart').scrollIntoView();
  for (let row = 0; row < g.numRows(); ++row) {
    const y = g.getValue(row, col);
    if (y === null) continue;
    const x = g.getValue(row, 0), [cx, cy] = g.toDomCoords(x, y);
    const box = document.getElementById('timeline-chart').getBoundingClientRect();
    return JSON.stringify({x: box.left + cx, y: box.top + cy, mark: details.get(x)});
  }
  return null;
})
"""

TILE_FIELDS = ["frames", "bad_checks", "timeouts", "unanswered_damaged_requests", "exceptions",
               "noise_bytes", "gaps"]
MARK_FIELDS = {"damaged": "bad_checks", "timeout": "timeouts",
               "unanswered_damaged": "unanswered_damaged_requests", "exception": "exceptions",
               "unsolicited": "unsolicited", "duplicate": "duplicates", "noise": "noise_runs",
               "gap": "gaps", "requests": "requests", "replies": "responses"}


def latest_values(text_report):
    """{(station, dialect, address): number} from the text report's latest values."""
    values, station = {}, None
    for line in text_report.splitlines():
        m = re.match(r"^  station (\d+)", line)
        if m:
            station = m.group(1)
            continue
        m = re.match(r"^    (\S+)\s+(\S+)\s+.*?\s(-?\d+(?:\.\d+)?)(?: \S+)?$", line)
        if m and station is not None:
            values[(station, m.group(1), m.group(2))] = float(m.group(3))
    return values


def hover_tooltip(browser, kind):
    """The tooltip shown with the mouse on the first mark of `kind` (None without such marks):
    (its text, the mark's fields)."""
    found = browser.evaluate(MARK_POSITION + "(%s)" % json.dumps(kind))
    if found is None:
        return None
    where = json.loads(found)
    browser.send("Input.dispatchMouseEvent",
                 {"type": "mouseMoved", "x": where["x"], "y": where["y"]})
    text = browser.evaluate("document.getElementById('timeline-tooltip').textContent")
    return text, where["mark"]


def run(args):
    result = subprocess.run(args, capture_output=True, text=True, timeout=RUN_GUARD_S)
    if result.returncode != 0:
        sys.exit("FAIL: %s exited %d: %s" % (" ".join(args), result.returncode, result.stderr))
    return result.stdout


def main():
    pvtap, capture, out_dir = sys.argv[1:4]
    chromium = find_chromium()
    if chromium is None:
        print("SKIP: no chromium (apt-get install chromium)")
        return 77
    os.makedirs(out_dir, exist_ok=True)
    name = os.path.basename(capture).rsplit(".pcap", 1)[0]
    html = os.path.join(out_dir, name + ".html")
    summary = json.loads(run([pvtap, "audit", "--format", "jsonl", "--summary-only", capture]))
    text = run([pvtap, "audit", "--summary-only", "--html", html, capture])

    browser = HeadlessChromium(chromium)
    failures = []
    try:
        browser.open_page(1200, 900)
        url = "file://" + os.path.abspath(html)
        started = time.monotonic()
        browser.navigate(url)
        while not browser.evaluate("!!(window.pvtap && window.pvtap.ready)"):
            if time.monotonic() - started > 30:
                sys.exit("FAIL: the page's script never finished")
            time.sleep(0.05)
        loaded = time.monotonic() - started
        page = json.loads(browser.evaluate(PAGE_CHECK))
        tooltip = hover_tooltip(browser, "timeout")
        shot = os.path.join(out_dir, name + ".png")
        browser.screenshot(shot)
        events = browser.drain()
    finally:
        browser.close()

    for e in events:
        method, params = e.get("method"), e.get("params", {})
        if method == "Runtime.exceptionThrown":
            failures.append("uncaught exception: %s" % params["exceptionDetails"])
        if method == "Runtime.consoleAPICalled" and params.get("type") in ("error", "assert"):
            failures.append("console error: %s" % params.get("args"))
        if method == "Log.entryAdded" and params["entry"].get("level") == "error":
            failures.append("browser error: %s" % params["entry"].get("text"))
        if method == "Network.requestWillBeSent" and params["request"]["url"] != url:
            failures.append("request leaving the file: %s" % params["request"]["url"])

    for field in TILE_FIELDS:
        if page["tiles"].get(field) != summary[field]:
            failures.append("tile %s shows %s, the summary says %s"
                            % (field, page["tiles"].get(field), summary[field]))
    for kind, field in MARK_FIELDS.items():
        if page["dropped"].get(kind, 0):
            failures.append("timeline dropped %s marks" % kind)
        if page["marks"].get(kind, 0) != summary[field]:
            failures.append("timeline has %s %s marks, the summary counts %s %s"
                            % (page["marks"].get(kind, 0), kind, summary[field], field))

    # The tooltip of a timeout names the request: its time, station lane, verdict, function.
    if summary["timeouts"] > 0:
        if tooltip is None:
            failures.append("no timeout mark to hover")
        else:
            shown, mark = tooltip
            t, dialect, function = mark[0], mark[2], mark[3]
            stamp = time.strftime("%H:%M:%S", time.gmtime(t))
            for word in (stamp, "timeout", dialect + " request", "(0x%02x)" % function):
                if word not in shown:
                    failures.append("the timeout's tooltip %r does not name %r" % (shown, word))

    latest = latest_values(text)
    if not page["last"]:
        failures.append("no value chart drawn")
    for point in page["last"]:
        station = point["lane"].split()[-1]
        key = (station, point["dialect"], point["address"])
        if key not in latest:
            failures.append("%s: no latest value in the text report" % point["label"])
        elif abs(latest[key] - point["value"]) > 1e-9:
            failures.append("%s: chart ends at %s, the text report's latest value is %s"
                            % (point["label"], point["value"], latest[key]))

    if tooltip:
        print("tooltip of the first timeout: " + tooltip[0])
    print("%s: %d tiles, %d mark kinds, %d value series checked; page ready in %.2f s; "
          "network %s; screenshot %s"
          % (name, len(TILE_FIELDS), len(MARK_FIELDS), len(page["last"]), loaded,
             "namespace" if browser.isolated else "flags", shot))
    for f in failures:
        print("FAIL: " + f)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
