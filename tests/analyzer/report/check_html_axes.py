#!/usr/bin/env python3
"""The HTML report's axes and legends as a reader sees them: Debian's headless chromium renders
the report of each capture at three widths and, on the time charts, three zooms (the whole
span, a tenth, a hundredth), and the labels are read back from the DOM after drawing.

  check_html_axes.py PVTAP OUT_DIR CAPTURE...

Fails on: adjacent tick labels that repeat; a label whose text is cut by its box, spills out
of its chart (axis titles too), or overlaps its neighbour; a time chart with fewer than two time labels; a chart
of more than one series without a legend, visible before any hover, that shows every series'
colour; a quantity axis (every chart but the timeline's lanes) that does not start at 0 where
its values are not negative, or has no label (its unit); a date in 1970 (the epoch: a
recording without a wall clock read as UTC) on the page, in a label or in the text report.
A logic recording (.sr: no wall-clock time) must say on its time axes, on the page and in the
text report that its times count from the recording's start; any other capture's time axes
must say UTC.
Exit 77 (skipped) when chromium is not installed.
"""

import json
import os
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from headless_chromium import HeadlessChromium, find_chromium  # noqa: E402

RUN_GUARD_S = 120
WIDTHS = (480, 1024, 1920)
ZOOMS = (1.0, 0.1, 0.01)
RELATIVE_WORDS = "recording's start"

# Zooms every time chart to `fraction` of its span (around the middle of its data), then reads
# back what every chart shows: tick labels with the boxes of their divs and of their text,
# the legend next to the chart, the y range and the axis titles.
READ_CHARTS = r"""
((fraction) => {
  const rect = e => { const b = e.getBoundingClientRect();
                      return [b.left, b.top, b.right, b.bottom]; };
  const textRect = e => { const r = document.createRange(); r.selectNodeContents(e);
                          return rect(r); };
  const probe = document.createElement('span');
  document.body.appendChild(probe);
  const rgb = c => { probe.style.color = ''; probe.style.color = c;
                     return getComputedStyle(probe).color; };
  const c = pvtap.charts, charts = [];
  const add = (name, g, time, quantity) => { if (g) charts.push({name, g, time, quantity}); };
  add('timeline', c.timeline, true, false);
  add('load', c.load, true, true);
  add('latency', c.latency, true, true);
  add('latency histogram', c.histogram, false, true);
  (c.values || []).forEach(v => add('values ' + v.group, v.chart, true, true));
  (c.silences || []).forEach(s => add('silences ' + s.bus, s.chart, false, true));
  charts.filter(x => x.time).forEach(x => {
    const [lo, hi] = x.g.xAxisExtremes(), mid = (lo + hi) / 2, half = (hi - lo) * fraction / 2;
    x.g.updateOptions({dateWindow: fraction >= 1 ? null : [mid - half, mid + half]});
  });
  const out = charts.map(x => {
    const g = x.g, div = g.graphDiv;
    // A log axis leaves its minor ticks without a label: those are not labels.
    const labels = cls => Array.from(div.querySelectorAll('.' + cls))
      .filter(e => e.textContent.trim() !== '')
      .map(e => ({text: e.textContent, box: rect(e), ink: textRect(e)}));
    let dataMin = Infinity;
    for (let row = 0; row < g.numRows(); ++row) {
      for (let col = 1; col < g.numColumns(); ++col) {
        const v = g.getValue(row, col);
        if (v === null || v === undefined) continue;
        const low = Array.isArray(v) ? v[0] : v;
        if (low !== null && !isNaN(low)) dataMin = Math.min(dataMin, low);
      }
    }
    // dygraphs draws into a div of its own inside the page's: a legend beside the chart is
    // beside the page's div.
    const box = div.parentElement;
    const legends = [g.getOption('labelsDiv'), div.querySelector('.dygraph-legend'),
                     box.previousElementSibling, box.nextElementSibling]
      .filter(e => e && e.nodeType === 1 && (e === g.getOption('labelsDiv') ||
                                             e.classList.contains('legend') ||
                                             e.classList.contains('dygraph-legend')));
    const legendColors = new Set(), legendText = [];
    legends.forEach(e => {
      if (e.offsetHeight === 0 || getComputedStyle(e).display === 'none') return;
      legendText.push(e.innerText.trim());
      [e].concat(Array.from(e.querySelectorAll('*'))).forEach(n => {
        const s = getComputedStyle(n);
        [s.backgroundColor, s.borderBottomColor, s.color].forEach(v => legendColors.add(v));
      });
    });
    const text = cls => { const e = div.querySelector('.' + cls);
                          return e ? e.textContent.trim() : ''; };
    // An axis title is a label too: it must not run out of the chart (over what follows it).
    const titles = ['dygraph-xlabel', 'dygraph-ylabel'].map(cls => div.querySelector('.' + cls))
      .filter(e => e && e.textContent.trim() !== '')
      .map(e => ({text: e.textContent.trim(), ink: textRect(e)}));
    return {name: x.name, time: x.time, quantity: x.quantity, chart: rect(div),
            x: labels('dygraph-axis-label-x'), y: labels('dygraph-axis-label-y'),
            series: g.getLabels().length - 1, colors: g.getColors().map(rgb),
            legendColors: Array.from(legendColors), legendText: legendText.join(' '),
            yRange: g.yAxisRange(), dataMin: dataMin === Infinity ? null : dataMin,
            xlabel: text('dygraph-xlabel'), ylabel: text('dygraph-ylabel'), titles: titles};
  });
  probe.remove();
  return JSON.stringify({charts: out, page: document.body.innerText});
})
"""

SLACK_PX = 1.0  # subpixel text layout


def inside(inner, outer):
    return (inner[0] >= outer[0] - SLACK_PX and inner[1] >= outer[1] - SLACK_PX
            and inner[2] <= outer[2] + SLACK_PX and inner[3] <= outer[3] + SLACK_PX)


def overlap(a, b):
    return (min(a[2], b[2]) - max(a[0], b[0]) > SLACK_PX
            and min(a[3], b[3]) - max(a[1], b[1]) > SLACK_PX)


def check_labels(where, axis, labels):
    failures = []
    for n, label in enumerate(labels):
        if not inside(label["ink"], label["box"]):
            failures.append("%s: %s label %r is cut (text %s, box %s)"
                            % (where, axis, label["text"], label["ink"], label["box"]))
        if "1970" in label["text"] or "Jan" in label["text"]:
            failures.append("%s: %s label %r is in 1970" % (where, axis, label["text"]))
        if n == 0:
            continue
        before = labels[n - 1]
        if label["text"] == before["text"]:
            failures.append("%s: %s labels repeat: %r, %r"
                            % (where, axis, before["text"], label["text"]))
        if overlap(label["ink"], before["ink"]):
            failures.append("%s: %s labels %r and %r overlap"
                            % (where, axis, before["text"], label["text"]))
    return failures


def check_chart(where, c, relative):
    failures = []
    failures += check_labels(where, "x", sorted(c["x"], key=lambda l: l["box"][0]))
    failures += check_labels(where, "y", sorted(c["y"], key=lambda l: -l["box"][1]))
    for label in c["x"] + c["y"] + c["titles"]:
        if not inside(label["ink"], c["chart"]):
            failures.append("%s: label %r spills out of the chart (text %s, chart %s)"
                            % (where, label["text"], label["ink"], c["chart"]))
    if c["time"] and len(c["x"]) < 2:
        failures.append("%s: %d time labels" % (where, len(c["x"])))
    if c["series"] > 1:
        missing = [color for color in c["colors"] if color not in c["legendColors"]]
        if not c["legendText"] or missing:
            failures.append("%s: %d series and no legend showing %s"
                            % (where, c["series"], missing or "any"))
    if c["quantity"]:
        low = c["yRange"][0]
        if c["dataMin"] is not None and c["dataMin"] >= 0 and low != 0:
            failures.append("%s: the y axis of a quantity starts at %s" % (where, low))
        if c["dataMin"] is not None and c["dataMin"] < 0 and low > 0:
            failures.append("%s: the y axis starts at %s, above 0" % (where, low))
        if not c["ylabel"]:
            failures.append("%s: the y axis has no label" % where)
    if c["time"]:
        want = RELATIVE_WORDS if relative else "UTC"
        if want not in c["xlabel"]:
            failures.append("%s: the time axis is titled %r, not saying %r"
                            % (where, c["xlabel"], want))
    return failures


def run(args):
    result = subprocess.run(args, capture_output=True, text=True, timeout=RUN_GUARD_S)
    if result.returncode != 0:
        sys.exit("FAIL: %s exited %d: %s" % (" ".join(args), result.returncode, result.stderr))
    return result.stdout


def wait_ready(browser):
    started = time.monotonic()
    while not browser.evaluate("!!(window.pvtap && window.pvtap.ready)"):
        if time.monotonic() - started > 30:
            sys.exit("FAIL: the page's script never finished")
        time.sleep(0.05)


def check_capture(browser, pvtap, out_dir, capture):
    name = os.path.splitext(os.path.basename(capture))[0]
    relative = capture.endswith(".sr")
    html = os.path.abspath(os.path.join(out_dir, name + ".axes.html"))
    text = run([pvtap, "audit", "--summary-only", "--html", html, capture])
    failures, checked = [], 0
    if "1970-01-01" in text:
        failures.append("%s: the text report is dated 1970" % name)
    span = [line for line in text.splitlines() if line.startswith("time:")]
    if relative and not any(RELATIVE_WORDS in line for line in span):
        failures.append("%s: the text report's time %s does not say %r"
                        % (name, span, RELATIVE_WORDS))
    for width in WIDTHS:
        browser.send("Emulation.setDeviceMetricsOverride",
                     {"width": width, "height": 900, "deviceScaleFactor": 1, "mobile": False})
        browser.navigate("file://" + html)
        wait_ready(browser)
        for zoom in ZOOMS:
            shown = json.loads(browser.evaluate(READ_CHARTS + "(%r)" % zoom))
            if "1970-01-01" in shown["page"]:
                failures.append("%s at %d px: the page shows a date of 1970" % (name, width))
            if relative and RELATIVE_WORDS not in shown["page"]:
                failures.append("%s at %d px: the page does not say its times count from %r"
                                % (name, width, RELATIVE_WORDS))
            for c in shown["charts"]:
                if not c["time"] and zoom != 1.0:
                    continue
                where = "%s at %d px, zoom %g, %s" % (name, width, zoom, c["name"])
                failures += check_chart(where, c, relative)
                checked += 1
    return failures, checked


def main():
    pvtap, out_dir, captures = sys.argv[1], sys.argv[2], sys.argv[3:]
    chromium = find_chromium()
    if chromium is None:
        print("SKIP: no chromium (apt-get install chromium)")
        return 77
    os.makedirs(out_dir, exist_ok=True)
    browser = HeadlessChromium(chromium)
    failures, checked = [], 0
    started = time.monotonic()
    try:
        browser.open_page(WIDTHS[0], 900)
        for capture in captures:
            found, n = check_capture(browser, pvtap, out_dir, capture)
            failures += found
            checked += n
    finally:
        browser.close()
    print("%d chart views checked (%d captures, widths %s, zooms %s) in %.1f s"
          % (checked, len(captures), WIDTHS, ZOOMS, time.monotonic() - started))
    for f in failures:
        print("FAIL: " + f)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
