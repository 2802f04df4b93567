// pvtap HTML report: builds the charts from the JSON in #pvtap-data with dygraphs (inlined
// before this script). Times are epoch milliseconds as plain numbers, so that frames less than
// a millisecond apart stay apart; the axes print them as UTC, or (a recording without wall-clock
// time) as seconds from the recording's start.
(function () {
  'use strict';
  const data = JSON.parse(document.getElementById('pvtap-data').textContent);
  const lanes = data.lanes;
  const pvtap = { data: data, charts: {}, details: {}, ready: false,
                  started: performance.now() };
  window.pvtap = pvtap;

  const KIND_COLORS = {
    requests: '#8aa4c8', replies: '#7fbf8f', damaged: '#d62728', timeout: '#ff7f0e',
    unanswered_damaged: '#9467bd', exception: '#e377c2', unsolicited: '#8c564b',
    duplicate: '#17becf', noise: '#7f7f7f', gap: '#000000', collision: '#bcbd22'
  };
  const KIND_TEXT = {
    requests: 'requests', replies: 'replies', damaged: 'damaged frame (bad check)',
    timeout: 'timeout', unanswered_damaged: 'damaged request, rightly unanswered',
    exception: 'exception / error reply', unsolicited: 'unsolicited reply',
    duplicate: 'duplicate reply', noise: 'noise', gap: 'data-loss gap',
    collision: 'collision (two transmissions at once)'
  };
  // Where a kind sits within its lane, so that kinds at one moment do not hide each other.
  const KIND_OFFSET = {
    requests: 0.3, replies: 0.18, damaged: 0.0, timeout: -0.06, unanswered_damaged: -0.12,
    exception: -0.18, unsolicited: -0.24, duplicate: -0.3, noise: 0.06, gap: -0.06,
    collision: 0.12
  };

  // A chart of a few lines shows each bucket's min..max as a band around its line; with more
  // lines the bands would only smear into each other (and cost the browser seconds to paint
  // on a day of 16 stations), so the lines carry the bucket's last reading (latency: its mean)
  // and a value chart's legend names the bucket's min and max.
  const MAX_BANDED_SERIES = 8;

  const bucketTime = i => (data.start + (i + 0.5) * data.bucket) * 1000;
  const pad = n => (n < 10 ? '0' : '') + n;
  function clockText(d, withSeconds, millis) {
    let t = pad(d.getUTCHours()) + ':' + pad(d.getUTCMinutes());
    if (withSeconds) t += ':' + pad(d.getUTCSeconds());
    if (millis > 0) t += '.' + String(d.getUTCMilliseconds()).padStart(3, '0').slice(0, millis);
    return t;
  }
  // A moment in full, for tooltips and legends: the UTC time of day, or (a recording without
  // wall-clock time, such as a logic analyzer's) the seconds from the recording's start.
  function timeText(ms) {
    if (!data.wall_clock) return '+' + (ms / 1000).toFixed(6) + ' s';
    return clockText(new Date(ms), true, 3) + ' UTC';
  }

  // The time axes. dygraphs' date ticker picks the ticks for the span shown at the chart's
  // width, at any zoom, and hands their granularity to the label formatter, which writes the
  // digits that granularity needs: neighbouring labels always differ. UTC throughout, so that
  // ticks also fall on round seconds from a recording's start.
  const G = Dygraph.Granularity;
  function decimalsOf(granularity) {
    if (granularity >= G.SECONDLY) return 0;
    if (granularity >= G.HUNDRED_MILLISECONDLY) return 1;
    return granularity >= G.TEN_MILLISECONDLY ? 2 : 3;
  }
  function axisTime(v, granularity) {
    const d = v instanceof Date ? v : new Date(v);
    if (!data.wall_clock) return (d.getTime() / 1000).toFixed(decimalsOf(granularity));
    if (granularity >= G.DAILY) return d.toISOString().slice(0, 10);
    const midnight = d.getTime() % 86400000 === 0;
    if (granularity >= G.MINUTELY) return midnight ? d.toISOString().slice(0, 10) : clockText(d);
    return clockText(d, true, decimalsOf(granularity));
  }
  const xAxis = {
    valueFormatter: timeText,
    axisLabelFormatter: axisTime,
    ticker: Dygraph.dateTicker,
    axisLabelWidth: 84,
    pixelsPerLabel: 80
  };
  // The axis title says the time base: a recording without a wall clock counts from its start
  // (the page's head says so in full).
  const xLabel = data.wall_clock ? 'time (UTC)' : 'seconds from the recording\'s start';

  // A quantity's axis starts at 0 and writes large numbers with SI prefixes (12.5k, 3.2M)
  // rather than in exponent form, which no label width holds.
  function quantityAxis(points) {
    let largest = 0;
    points.forEach(list => list.forEach(p => {
      const v = Array.isArray(p[1]) ? p[1][2] : p[1];
      if (Math.abs(v) > largest) largest = Math.abs(v);
    }));
    return { labelsKMB: largest >= 1e4, axisLabelWidth: 60 };
  }
  const AXIS_FONT = 12;
  // Axis titles in 14 px type (dygraphs sizes them 2 px below their box), so that a long one
  // still fits a phone's chart.
  const TITLES = { xLabelHeight: 16, yLabelWidth: 16 };

  // A legend under the chart, shown before any hover, which names the series by their colour
  // (and, on hover, gives their values).
  function legendAfter(chart) {
    const legend = document.createElement('div');
    legend.className = 'legend chart-legend';
    chart.after(legend);
    return legend;
  }
  function chartOptions(chart) {
    return Object.assign({ legend: 'always', labelsDiv: legendAfter(chart),
                           labelsSeparateLines: false, labelsUTC: true,
                           axisLabelFontSize: AXIS_FONT, includeZero: true }, TITLES);
  }

  // Rows for dygraphs from several series of [x, y] points: one row per distinct x, null
  // where a series has no point.
  function rowsOf(seriesPoints) {
    const rows = new Map();
    seriesPoints.forEach((points, s) => {
      points.forEach(([x, y]) => {
        let row = rows.get(x);
        if (!row) {
          row = new Array(seriesPoints.length + 1).fill(null);
          row[0] = x;
          rows.set(x, row);
        }
        row[s + 1] = y;
      });
    });
    return Array.from(rows.values()).sort((a, b) => a[0] - b[0]);
  }

  function element(id) {
    return document.getElementById(id);
  }

  function note(container, text) {
    const p = document.createElement('p');
    p.className = 'hint';
    p.textContent = text;
    container.replaceWith(p);
  }

  function functionName(dialect, fn) {
    if (fn === null) return '';
    return data.functions[dialect + ' ' + fn] || ('function ' + fn);
  }

  function markText(kind, m) {
    const [t, lane, dialect, fn, isRequest, start, count, detail] = m;
    const parts = [timeText(t * 1000), lanes[lane].label, KIND_TEXT[kind]];
    if (fn !== null) parts.push(dialect + ' ' + (isRequest ? 'request ' : 'reply ') + functionName(dialect, fn));
    if (start !== null) parts.push('block start ' + start + (count !== null ? ' count ' + count : ''));
    if (kind === 'noise') parts.push(detail + ' bytes');
    if (kind === 'gap') parts.push(detail > 0 ? detail + ' bytes lost' : 'size unknown');
    if (kind === 'exception' && detail > 0) parts.push('code 0x' + detail.toString(16).padStart(2, '0'));
    return parts.join(' · ');
  }

  // One series per kind, every lane in it (y = lane): a chart's cost grows with series times
  // rows, so kinds must not multiply by lanes. Points of one kind at the same moment on two
  // lanes are kept apart by a microsecond per lane, far below what the axis can show.
  const laneX = (ms, lane) => ms + lane * 1e-3;

  function timelineSeries() {
    const names = [], points = [], colors = [];
    const add = (kind, list, details) => {
      if (list.length === 0) return;
      names.push(kind);
      points.push(list);
      colors.push(KIND_COLORS[kind]);
      pvtap.details[kind] = details;
    };
    // The tooltip's words are made when a point is hovered; only what they need is kept.
    ['requests', 'replies'].forEach(kind => {
      const details = new Map(), list = [];
      details.counts = new Map();
      details.text = x => {
        const [l, n] = details.get(x);
        return timeText(x) + ' · ' + lanes[l].label + ' · ' + n + ' ' + kind + ' in ' +
               data.bucket.toFixed(2) + ' s';
      };
      lanes.forEach((lane, l) => {
        lane[kind].forEach(([i, n]) => {
          const x = laneX(bucketTime(i), l);
          details.set(x, [l, n]);
          details.counts.set(x, n);
          list.push([x, l + KIND_OFFSET[kind]]);
        });
      });
      add(kind, list, details);
    });
    Object.keys(data.marks).forEach(kind => {
      const details = new Map();
      details.text = x => markText(kind, details.get(x));
      add(kind, data.marks[kind].map(m => {
        const x = laneX(m[0] * 1000, m[1]);
        details.set(x, m);
        return [x, m[1] + KIND_OFFSET[kind]];
      }), details);
    });
    return { names, points, colors };
  }

  function laneTicker() {
    return lanes.map((lane, l) => ({ v: l, label: lane.label }));
  }

  function timelineLegend() {
    const legend = element('timeline-legend');
    Object.keys(KIND_COLORS).forEach(kind => {
      const span = document.createElement('span');
      span.innerHTML = '<i style="background:' + KIND_COLORS[kind] + '"></i>';
      span.appendChild(document.createTextNode(KIND_TEXT[kind]));
      legend.appendChild(span);
    });
  }

  function buildTimeline() {
    const s = timelineSeries();
    const tooltip = element('timeline-tooltip');
    timelineLegend();
    const chart = element('timeline-chart');
    chart.style.height = Math.max(220, 36 * lanes.length + 60) + 'px';
    return new Dygraph(chart, rowsOf(s.points), Object.assign({
      labels: ['time'].concat(s.names),
      colors: s.colors,
      strokeWidth: 0,
      drawPoints: true,
      pointSize: 2.5,
      highlightCircleSize: 5,
      connectSeparatedPoints: false,
      legend: 'never', labelsUTC: true, axisLabelFontSize: AXIS_FONT, xlabel: xLabel,
      valueRange: [-0.6, lanes.length - 0.4],
      axes: { x: xAxis, y: { ticker: laneTicker, axisLabelWidth: 110, drawGrid: true } },
      highlightSeriesOpts: { highlightCircleSize: 6 },
      highlightCallback: (event, x, points, row, seriesName) => {
        const details = pvtap.details[seriesName];
        tooltip.textContent = details && details.has(x) ? details.text(x) : '';
        tooltip.style.display = tooltip.textContent ? 'block' : 'none';
      },
      unhighlightCallback: () => { tooltip.style.display = 'none'; }
    }, TITLES));
  }

  function buildLoad() {
    const names = [], points = [];
    data.loads.forEach(load => {
      const bus = data.loads.length > 1 ? (load.bus || 'serial') + ' ' : '';
      [['to_slave', 'to the slaves'], ['from_slave', 'from the slaves'],
       ['unknown', 'noise, direction unknown']].forEach(([key, text]) => {
        if (load[key].length === 0) return;
        names.push(bus + text + ' (B/s)');
        points.push(load[key].map(([i, sum]) => [bucketTime(i), sum / data.bucket]));
      });
    });
    if (names.length === 0) return null;
    const chart = element('load-chart');
    return new Dygraph(chart, rowsOf(points), Object.assign(chartOptions(chart), {
      labels: ['time'].concat(names), stepPlot: true, fillGraph: true, xlabel: xLabel,
      axes: { x: xAxis, y: quantityAxis(points) }, ylabel: 'bytes/s'
    }));
  }

  function buildLatency() {
    const timed = lanes.filter(lane => lane.latency.length > 0);
    if (timed.length === 0) return null;
    const banded = timed.length <= MAX_BANDED_SERIES;
    const points = timed.map(lane => lane.latency.map(([i, lo, mean, hi]) =>
      [bucketTime(i), banded ? [lo, mean, hi] : mean]));
    const chart = element('latency-chart');
    return new Dygraph(chart, rowsOf(points), Object.assign(chartOptions(chart), {
      labels: ['time'].concat(timed.map(lane => lane.label + ' (ms)')), customBars: banded,
      axes: { x: xAxis, y: quantityAxis(points) }, xlabel: xLabel,
      ylabel: banded ? 'ms, min / mean / max' : 'ms, mean per bucket', connectSeparatedPoints: true
    }));
  }

  function buildHistogram() {
    const names = [], columns = [];
    lanes.forEach(lane => {
      if (lane.histogram.every(n => n === 0)) return;
      names.push(lane.label);
      columns.push(lane.histogram);
    });
    if (names.length === 0) return null;
    const rows = [];
    for (let b = 0; b < columns[0].length; ++b) {
      rows.push([Math.pow(10, b / 10)].concat(columns.map(c => c[b])));
    }
    const chart = element('histogram-chart');
    return new Dygraph(chart, rows, Object.assign(chartOptions(chart), {
      labels: ['ms'].concat(names), stepPlot: true, fillGraph: true,
      xlabel: 'latency, ms (log scale)', ylabel: 'replies',
      axes: { x: { logscale: true }, y: quantityAxis(columns.map(c => c.map(n => [0, n]))) }
    }));
  }

  function buildValueChart(group, container) {
    const box = document.createElement('div');
    box.className = 'value-group';
    const title = document.createElement('h3');
    title.textContent = group.group === 'states' ? 'States (enumerations, bits, raw words)' : group.group;
    const div = document.createElement('div');
    div.className = 'chart';
    box.append(title, div);
    container.appendChild(box);
    const banded = group.series.length <= MAX_BANDED_SERIES;
    const ranges = group.series.map(() => new Map());
    const points = group.series.map((s, k) => s.points.map(([i, lo, last, hi]) => {
      const x = bucketTime(i);
      ranges[k].set(x, [lo, hi]);
      return [x, banded ? [lo, last, hi] : last];
    }));
    const labels = group.series.map(s => s.label);
    const valueFormatter = (y, opts, seriesName, g, row) => {
      const k = labels.indexOf(seriesName);
      const range = k >= 0 ? ranges[k].get(g.getValue(row, 0)) : undefined;
      const text = Array.isArray(y) ? String(y[1]) : String(y);
      return range && range[0] !== range[1] ? text + ' (' + range[0] + '..' + range[1] + ')' : text;
    };
    // Registers' values start at 0 too: readings here are magnitudes (power, energy,
    // voltage), and a level that only looks like a cliff because the axis began just below it
    // misleads more than a flat line; a chart with negative values reaches down to them.
    const y = Object.assign(quantityAxis(points), { valueFormatter: valueFormatter });
    return new Dygraph(div, rowsOf(points), Object.assign(chartOptions(div), {
      labels: ['time'].concat(labels), customBars: banded,
      stepPlot: group.series.some(s => s.step), axes: { x: xAxis, y: y }, xlabel: xLabel,
      ylabel: group.group === 'states' ? 'value' : group.group, connectSeparatedPoints: true
    }));
  }

  function buildValues() {
    const container = element('value-charts');
    if (data.values.length === 0) {
      container.textContent = data.plot_chosen
        ? 'No register that --plot names was read with a numeric value.'
        : 'No numeric register changed its value.';
      return [];
    }
    return data.values.map(group => ({ group: group.group, series: group.series,
                                       chart: buildValueChart(group, container) }));
  }

  // A silence histogram's rows: each bucket at its lower edge (log axis: the bucket below the
  // lowest edge, which holds zero and overlaps, a quarter octave lower), then one row past the
  // highest edge where the step ends. The line is an edge, so the rows on either side of it
  // are exactly the silences on either side.
  const QUARTER_OCTAVE = Math.pow(2, 0.25);
  function silenceRows(h) {
    const e = h.edges_ms, last = e[e.length - 1];
    const rows = h.counts.map((n, i) => [i === 0 ? e[0] / QUARTER_OCTAVE : e[i - 1], n]);
    rows.push([last * QUARTER_OCTAVE, 0]);
    return rows;
  }

  // The rules' limits as vertical lines under the bars, named where they stand.
  const SILENCE_LINE_COLORS = { t15: '#d62728', t35: '#9467bd' };
  pvtap.silenceLineColors = SILENCE_LINE_COLORS;
  function silenceLines(s) {
    return (ctx, area, g) => {
      // toDomXCoord is linear even on a log axis: place the line by the logarithms.
      const [lo, hi] = g.xAxisRange().map(Math.log);
      const lines = [[s.t15_ms, 't1.5', SILENCE_LINE_COLORS.t15],
                     [s.t35_ms, 't3.5', SILENCE_LINE_COLORS.t35]];
      lines.forEach(([ms, text, color]) => {
        // On a pixel's middle, so that the line is crisp rather than smeared over two.
        const x = Math.round(area.x + area.w * (Math.log(ms) - lo) / (hi - lo)) + 0.5;
        if (x < area.x || x > area.x + area.w) return;
        ctx.save();
        ctx.strokeStyle = color;
        ctx.fillStyle = color;
        ctx.lineWidth = 1.5;
        ctx.setLineDash([5, 3]);
        ctx.beginPath();
        ctx.moveTo(x, area.y);
        ctx.lineTo(x, area.y + area.h);
        ctx.stroke();
        ctx.fillText(text, x + 3, area.y + 12);
        ctx.restore();
      });
    };
  }

  const SILENCE_SERIES = [['largest silence inside a frame (against t1.5)', '#ff7f0e'],
                          ['silence between frames (against t3.5)', '#1f77b4']];

  function buildSilenceChart(s, n) {
    const chart = element('silence-chart-' + n);
    const points = [silenceRows(s.inner), silenceRows(s.between)];
    return new Dygraph(chart, rowsOf(points), Object.assign(chartOptions(chart), {
      labels: ['ms'].concat(SILENCE_SERIES.map(([text]) => text)),
      colors: SILENCE_SERIES.map(([, color]) => color), stepPlot: true, fillGraph: true,
      connectSeparatedPoints: true,
      xlabel: 'silence, ms (log scale; one character is ' + s.char_ms.toFixed(3) + ' ms)',
      ylabel: 'silences', axes: { x: { logscale: true }, y: quantityAxis(points) },
      underlayCallback: silenceLines(s)
    }));
  }

  function buildSilences() {
    return data.silences.map((s, n) => ({ bus: s.bus, t15_ms: s.t15_ms, t35_ms: s.t35_ms,
                                          chart: buildSilenceChart(s, n) }));
  }

  if (!data.has_timestamps) {
    ['timeline-chart', 'load-chart', 'latency-chart', 'histogram-chart'].forEach(id =>
      note(element(id), 'Not drawn: the input has no timestamps.'));
    pvtap.ready = true;
    return;
  }
  // How long each chart took to build, for bench/html_report_bench.py.
  pvtap.timings = {};
  const timed_build = (name, build) => {
    const t0 = performance.now();
    pvtap.charts[name] = build();
    pvtap.timings[name] = performance.now() - t0;
  };
  timed_build('timeline', buildTimeline);
  timed_build('load', buildLoad);
  timed_build('latency', buildLatency);
  timed_build('histogram', buildHistogram);
  timed_build('values', buildValues);
  timed_build('silences', buildSilences);
  const timed = [pvtap.charts.timeline, pvtap.charts.load, pvtap.charts.latency]
    .concat(pvtap.charts.values.map(v => v.chart)).filter(g => g);
  const t0 = performance.now();
  if (timed.length > 1) Dygraph.synchronize(timed, { zoom: true, selection: false, range: false });
  pvtap.timings.synchronize = performance.now() - t0;
  pvtap.timings.script_end = performance.now();
  pvtap.ready = true;
})();
