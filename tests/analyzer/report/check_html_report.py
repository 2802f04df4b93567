#!/usr/bin/env python3
"""pvtap audit --html in a real browser: Debian's headless chromium opens the report of a
capture from disk with no network, and the page must show what the report model says.

  check_html_report.py PVTAP CAPTURE OUT_DIR [TRUTH]

Checks: no console error or uncaught exception; no request for anything but the file itself;
the overview tiles equal the jsonl summary's numbers; the timeline holds as many marks of each
kind as the summary counts (and its request/reply buckets add up to the summary's requests and
responses); the last point of every numeric value chart equals that register's "latest value"
in the text report; where a bus's timing is judged (a logic recording), its timing histogram's
counts beyond t1.5 and t3.5 equal the summary's violations, and both lines are drawn where the
summary puts t1.5 and t3.5 (and, given a logic sample's TRUTH, the counts beyond them are its
planted violations). A screenshot of the page goes to OUT_DIR/NAME.png.
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

# Each timing histogram read back from its dygraph: per series, the silences beyond its line
# (rows are buckets at their lower edge, and the line is an edge: inside a frame, the buckets
# from t1.5 up; between frames, those below t3.5) and in all; where the page's verdicts say
# what; and how many pixels of each line's color stand in a column at the line's place on the
# chart's canvases (a drawn line covers much of the plot's height, dashed).
SILENCE_CHECK = r"""
(() => {
  const hex = c => [1, 3, 5].map(i => parseInt(c.substr(i, 2), 16));
  function linePixels(g, ms, color) {
    // Where `ms` is on the log axis (toDomXCoord would place it linearly).
    const area = g.getArea(), [lo, hi] = g.xAxisRange().map(Math.log), want = hex(color);
    const x = Math.round(area.x + area.w * (Math.log(ms) - lo) / (hi - lo));
    let found = 0;
    g.graphDiv.querySelectorAll('canvas').forEach(canvas => {
      const ctx = canvas.getContext('2d');
      for (let y = Math.ceil(area.y); y < area.y + area.h; ++y) {
        for (let dx = -1; dx <= 1; ++dx) {
          const p = ctx.getImageData(x + dx, y, 1, 1).data;
          if (p[3] > 200 && want.every((v, i) => Math.abs(p[i] - v) <= 8)) { ++found; break; }
        }
      }
    });
    return {found: found, height: Math.floor(area.h)};
  }
  return JSON.stringify((pvtap.charts.silences || []).map((s, n) => {
    const g = s.chart, sums = {inner_beyond: 0, inner_total: 0, between_beyond: 0,
                               between_total: 0};
    for (let row = 0; row < g.numRows(); ++row) {
      const x = g.getValue(row, 0), inner = g.getValue(row, 1), between = g.getValue(row, 2);
      if (inner !== null) {
        sums.inner_total += inner;
        if (x >= s.t15_ms) sums.inner_beyond += inner;
      }
      if (between !== null) {
        sums.between_total += between;
        if (x < s.t35_ms) sums.between_beyond += between;
      }
    }
    const shown = {};
    document.getElementById('silence-chart-' + n).closest('.bus-timing')
      .querySelectorAll('[data-key]').forEach(e => {
        shown[e.dataset.key] = Number(e.textContent);
      });
    return {bus: s.bus, t15_ms: s.t15_ms, t35_ms: s.t35_ms, sums: sums, shown: shown,
            t15_line: linePixels(g, s.t15_ms, pvtap.silenceLineColors.t15),
            t35_line: linePixels(g, s.t35_ms, pvtap.silenceLineColors.t35)};
  }));
})()
"""

TILE_FIELDS = ["frames", "bad_checks", "timeouts", "unanswered_damaged_requests", "exceptions",
               "noise_bytes", "gaps"]
MARK_FIELDS = {"damaged": "bad_checks", "timeout": "timeouts",
               "unanswered_damaged": "unanswered_damaged_requests", "exception": "exceptions",
               "unsolicited": "unsolicited", "duplicate": "duplicates", "noise": "noise_runs",
               "gap": "gaps", "collision": "collisions", "requests": "requests",
               "replies": "responses"}


def latest_values(text_report):
    """{(station, dialect, address): number} from the text report's latest values."""
    values, station = {}, None
    for line in text_report.splitlines():
        m = re.match(r"^  station (\d+)", line)
        if m:
            station = m.group(1)
            continue
        # A word no map names: its table, its hex and decimal reading, keyed as its chart is.
        m = re.match(r"^    (\S+)\s+0x([0-9A-F]+)\s+(holding|input) register\s+0x[0-9A-F]+ "
                     r"\((\d+)\)$", line)
        if m and station is not None:
            key = "%sreg_0x%s" % ("input_" if m.group(3) == "input" else "", m.group(2).lower())
            values[(station, m.group(1), key)] = float(m.group(4))
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


def check_silences(summary, charts):
    """One timing histogram per bus whose timing is judged, and none for the others: its counts
    beyond t1.5 and t3.5 are the bus's violations, the page's verdicts say the same, its lines
    stand where the summary's t1.5 and t3.5 are, drawn."""
    failures = []
    judged = [b for b in summary["buses"] if b["timing"]["judged"]]
    names = [b["bus"] or "serial" for b in judged]
    if [c["bus"] for c in charts] != names:
        return ["timing histograms for %s, the judged buses are %s"
                % ([c["bus"] for c in charts], names)]
    for bus, c in zip(judged, charts):
        timing, sums, name = bus["timing"], c["sums"], c["bus"]
        pairs = ((sums["inner_beyond"], timing["t15_violations"], "over t1.5 inside"),
                 (sums["between_beyond"], timing["t35_violations"], "under t3.5 between"),
                 (c["shown"].get("t15_violations"), timing["t15_violations"],
                  "page's t1.5 verdict"),
                 (c["shown"].get("t35_violations"), timing["t35_violations"],
                  "page's t3.5 verdict"),
                 (c["t15_ms"], timing["t15_ms"], "t1.5 line (ms)"),
                 (c["t35_ms"], timing["t35_ms"], "t3.5 line (ms)"))
        for got, expected, what in pairs:
            if isinstance(got, float) and abs(got - expected) <= 1e-3:
                continue
            if got != expected:
                failures.append("%s: histogram %s is %s, the summary says %s"
                                % (name, what, got, expected))
        # Every frame of the samples checked here is RTU: each has its largest inner silence,
        # and there is one silence fewer between them.
        if sums["inner_total"] != bus["frames"] or sums["between_total"] != bus["frames"] - 1:
            failures.append("%s: histogram holds %d inner and %d between silences for %d frames"
                            % (name, sums["inner_total"], sums["between_total"], bus["frames"]))
        for line in ("t15_line", "t35_line"):
            if c[line]["found"] < c[line]["height"] // 3:
                failures.append("%s: the %s is %d pixels of a %d pixel high plot"
                                % (name, line, c[line]["found"], c[line]["height"]))
    return failures


def run(args):
    result = subprocess.run(args, capture_output=True, text=True, timeout=RUN_GUARD_S)
    if result.returncode != 0:
        sys.exit("FAIL: %s exited %d: %s" % (" ".join(args), result.returncode, result.stderr))
    return result.stdout


def main():
    pvtap, capture, out_dir = sys.argv[1:4]
    truth = None
    if len(sys.argv) > 4:
        with open(sys.argv[4], encoding="utf-8") as f:
            truth = json.load(f)
    chromium = find_chromium()
    if chromium is None:
        print("SKIP: no chromium (apt-get install chromium)")
        return 77
    os.makedirs(out_dir, exist_ok=True)
    name = os.path.splitext(os.path.basename(capture))[0]
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
        silences = json.loads(browser.evaluate(SILENCE_CHECK))
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
            # A logic recording has no wall clock: its times count from its start.
            stamp = ("+%.6f s" % t if capture.endswith(".sr")
                     else time.strftime("%H:%M:%S", time.gmtime(t)))
            for word in (stamp, "timeout", dialect + " request", "(0x%02x)" % function):
                if word not in shown:
                    failures.append("the timeout's tooltip %r does not name %r" % (shown, word))

    latest = latest_values(text)
    if not page["last"]:
        failures.append("no value chart drawn")
    for point in page["last"]:
        station = point["lane"].split()[-1]
        mapped = not re.match(r"^(input_)?reg_0x[0-9a-f]{4}$", point["key"] or "")
        key = (station, point["dialect"], point["address"] if mapped else point["key"])
        if key not in latest:
            failures.append("%s: no latest value in the text report" % point["label"])
        elif abs(latest[key] - point["value"]) > 1e-9:
            failures.append("%s: chart ends at %s, the text report's latest value is %s"
                            % (point["label"], point["value"], latest[key]))

    failures += check_silences(summary, silences)
    # A logic sample's planted violations, as its truth lists them, beyond the lines of every
    # bus (each bus of the sample carries every frame).
    if truth is not None:
        planted = (truth["logic"]["pauses_in_frames"], truth["logic"]["early_replies"])
        for c in silences:
            found = (c["sums"]["inner_beyond"], c["sums"]["between_beyond"])
            if found != planted:
                failures.append("%s: beyond t1.5 and t3.5 %s, the truth planted %s"
                                % (c["bus"], found, planted))
        if not silences:
            failures.append("no timing histogram for a logic sample")

    if tooltip:
        print("tooltip of the first timeout: " + tooltip[0])
    for c in silences:
        print("timing histogram of %s: %d of %d frames with a silence over t1.5 inside, %d of %d "
              "silences between frames under t3.5; lines of %d and %d pixels"
              % (c["bus"], c["sums"]["inner_beyond"], c["sums"]["inner_total"],
                 c["sums"]["between_beyond"], c["sums"]["between_total"],
                 c["t15_line"]["found"], c["t35_line"]["found"]))
    print("%s: %d tiles, %d mark kinds, %d value series checked; page ready in %.2f s; "
          "network %s; screenshot %s"
          % (name, len(TILE_FIELDS), len(MARK_FIELDS), len(page["last"]), loaded,
             "namespace" if browser.isolated else "flags", shot))
    for f in failures:
        print("FAIL: " + f)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
