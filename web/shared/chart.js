// Thin wrappers around uPlot (vendored in vendor/, see vendor/README.md). Each chart follows its
// container's width, and records how many points and series it draws in data-points / data-series so
// that the browser tests check what is actually plotted.
import uPlot from '../vendor/uPlot.esm.js';
import { SERIES_STYLES, fmtExp, fmtH, fmtSeconds, superscript } from './labels.js';
import { spreadText } from './repeats.js';
import { exportBar } from './chart_export.js';
import { el } from './dom.js';

// Labels only every k-th decade so that long ranges (1e0 .. 1e-16) stay readable on small charts.
function logAxisValues(u, splits, axisIdx) {
  const axis = u.axes[axisIdx];
  const { min, max } = u.scales[axis.scale];
  const vertical = axis.side % 2 === 1;
  const room = (vertical ? u.bbox.height : u.bbox.width) / devicePixelRatio / (vertical ? 22 : 48);
  const step = Math.max(1, Math.ceil(Math.log10(max / min) / Math.max(1, room)));
  return splits.map((v) => {
    const k = Math.round(Math.log10(v));
    return v != null && Math.abs(Math.log10(v) - k) < 1e-9 && k % step === 0 ? `1e${k}` : '';
  });
}

// Over more than 4 decades only whole decades get ticks and grid lines: the 1..9 sub-decade lines of a
// 16-decade axis would read as grey banding.
function decadeFilter(u, splits, axisIdx) {
  const { min, max } = u.scales[u.axes[axisIdx].scale];
  if (Math.log10(max / min) <= 4) return splits;
  return splits.map((v) => (v != null && Math.abs(Math.log10(v) - Math.round(Math.log10(v))) < 1e-9 ? v : null));
}

function logAxis(label, extra = {}) {
  return { label, values: logAxisValues, filter: decadeFilter, size: 60, space: 24, gap: 4, ...extra };
}

// Log scales cannot show 0 or negative values: those become gaps, the x count is kept.
const positive = (y) => (typeof y === 'number' && y > 0 && Number.isFinite(y) ? y : null);

// Whole decades around the data, within 1e-20..1e20: uPlot 1.6.32's log-axis tick loop never ends below
// about 1e-22 (its decimal rounding breaks down) or on all-null data. Smaller values are clipped at the
// floor; the legend still shows them exactly.
function decades(u, min, max) {
  if (!(min > 0) || !Number.isFinite(max)) return [1e-16, 1];
  const lo = Math.min(19, Math.max(-20, Math.floor(Math.log10(min))));
  const hi = Math.min(20, Math.max(lo + 1, Math.ceil(Math.log10(max))));
  return [10 ** lo, 10 ** hi];
}

const mounted = new WeakMap(); // container -> { plot, observer } of the chart it shows now

// Destroys the container's chart, if any: a detached uPlot that still resizes recomputes its axes with no data,
// and its log-axis tick loop then never ends.
function unmount(container) {
  const old = mounted.get(container);
  if (old) {
    old.observer.disconnect();
    old.plot.destroy();
    mounted.delete(container);
  }
  container.replaceChildren();
  container.classList.remove('chart-message');
}

// A sentence where a chart would be (nothing to draw): the chart, its Save buttons and its series count go.
export function chartMessage(container, text) {
  unmount(container);
  if (container.nextElementSibling?.classList.contains('chart-export')) container.nextElementSibling.remove();
  delete container.dataset.series;
  delete container.dataset.points;
  container.classList.add('chart-message');
  container.append(el('p', { class: 'hint' }, text));
}

// Replaces the container's chart.
function mount(container, opts, data) {
  unmount(container);
  const width = () => Math.max(280, container.clientWidth);
  const plot = new uPlot({ ...opts, width: width(), height: opts.height ?? 300 }, data, container);
  const observer = new ResizeObserver(() => {
    if (container.clientWidth > 0) plot.setSize({ width: width(), height: plot.height });
  });
  observer.observe(container);
  mounted.set(container, { plot, observer });
  // Save as PNG / SVG under the chart, once per container: it saves whichever chart the container shows.
  if (!container.nextElementSibling?.classList.contains('chart-export')) {
    container.after(exportBar(container, () => mounted.get(container).plot));
  }
  return plot;
}

function record(container, plot) {
  container.dataset.points = String(plot.data[0].length);
  container.dataset.series = String(plot.series.length - 1);
}

// A series in the i-th server style: colour and dash, with markers (drawn by drawMarkers) so that identical
// curves stay visible under one another.
function styledLine(label, i) {
  const st = seriesStyle(i);
  return { label, stroke: st.color, dash: st.dash, width: 2, _color: st.color, _marker: st.marker,
    points: { show: false }, value: (u, v) => fmtExp(v) };
}

// Residual ||f(y_n)|| against n on a log axis, one series per run; xs are iteration numbers.
export function residualChart(container, labels) {
  const series = [{ label: 'n', class: 'x-series' }].concat(labels.map((text, i) => styledLine(text, i)));
  const opts = {
    series,
    scales: { x: { time: false }, y: { distr: 3, log: 10, range: decades } },
    // Iterations are whole numbers: ticks at steps of 1, 2, 5, 10, ... only.
    // The drawn ticks are recorded in data-x-ticks for the browser test.
    axes: [{ label: 'iteration n', incrs: [1, 2, 5, 10, 20, 50, 100, 200, 500, 1000],
      values: (u, splits) => { container.dataset.xTicks = splits.join(' '); return splits.map(String); } },
    logAxis('\u2016f(y\u2099)\u2016')],
    legend: { live: true },
    hooks: { draw: [drawMarkers] },
  };
  const plot = mount(container, opts, [[], ...labels.map(() => [])]);
  record(container, plot);
  return {
    // columns: one residual array per series, each as long as it has records so far.
    set(columns) {
      const len = Math.max(0, ...columns.map((c) => c.length));
      const xs = Array.from({ length: len }, (_, i) => i);
      plot.setData([xs, ...columns.map((c) => xs.map((i) => (i < c.length ? positive(c[i]) : null)))]);
      record(container, plot);
      // The residuals as given, for the browser tests (the downloads must hold the same numbers).
      (window.__lienewtonCharts ??= {})[container.id] = { columns: columns.map((c) => [...c]) };
    },
  };
}

// Markers of the server's series styles (x-lienewton.series_styles), drawn r pixels from the centre.
const MARKERS = {
  circle: (c, x, y, r) => c.arc(x, y, r, 0, 2 * Math.PI),
  square: (c, x, y, r) => c.rect(x - r, y - r, 2 * r, 2 * r),
  'triangle-up': (c, x, y, r) => { c.moveTo(x, y - r); c.lineTo(x + r, y + r); c.lineTo(x - r, y + r); c.closePath(); },
  'triangle-down': (c, x, y, r) => { c.moveTo(x, y + r); c.lineTo(x + r, y - r); c.lineTo(x - r, y - r); c.closePath(); },
  diamond: (c, x, y, r) => { c.moveTo(x, y - r); c.lineTo(x + r, y); c.lineTo(x, y + r); c.lineTo(x - r, y); c.closePath(); },
  cross: (c, x, y, r) => { c.moveTo(x - r, y - r); c.lineTo(x + r, y + r); c.moveTo(x + r, y - r); c.lineTo(x - r, y + r); },
};

export function seriesStyle(i) {
  const s = SERIES_STYLES[i % SERIES_STYLES.length];
  return { color: s.color, dash: s.dash_pattern?.length ? s.dash_pattern : undefined, marker: s.marker };
}

// Draws each shown series' markers at its points (uPlot draws only circles).
// Hollow, and each series' a little smaller than the one before: where curves coincide (the same iterates
// by two methods) every marker's outline still shows around the later ones.
const EXCLUDED_GREY = '#9a9a9a';

function drawMarkers(u) {
  const c = u.ctx;
  c.save();
  c.lineWidth = 1.5 * devicePixelRatio;
  for (let i = 1; i < u.series.length; i++) {
    const s = u.series[i];
    if (!s.show) continue;
    const r = (6 - 0.8 * ((i - 1) % 4)) * devicePixelRatio;
    const shape = MARKERS[s._marker];
    // A marker name the server's style table has and this map lacks is an error, not a line without markers.
    if (!shape) throw new Error(`no marker shape for "${s._marker}"`);
    const [xs, ys] = u.mode === 2 ? u.data[i] : [u.data[0], u.data[i]];
    // The series' own colour, then (work precision) its points left out of the fit in grey.
    for (const grey of [false, true]) {
      c.beginPath();
      for (let k = 0; k < xs.length; k++) {
        if (ys[k] == null || Boolean(s._excluded?.[k]) !== grey) continue;
        const x = u.valToPos(xs[k], 'x', true);
        const y = u.valToPos(ys[k], 'y', true);
        c.moveTo(x + r, y);
        shape(c, x, y, r);
      }
      c.strokeStyle = grey ? EXCLUDED_GREY : s._color;
      c.stroke();
    }
  }
  c.restore();
}

// The point nearest the cursor (within 14 px) among shown series: [series index, point index] or null.
function nearest(u) {
  const { left, top } = u.cursor;
  if (left == null || left < 0) return null;
  let best = null; let bestD = 14 * 14;
  for (let i = 1; i < u.series.length; i++) {
    if (!u.series[i].show) continue;
    const [xs, ys] = u.data[i];
    for (let k = 0; k < xs.length; k++) {
      const d = (u.valToPos(xs[k], 'x') - left) ** 2 + (u.valToPos(ys[k], 'y') - top) ** 2;
      if (d < bestD) { bestD = d; best = [i, k]; }
    }
  }
  return best;
}

// Work-precision diagram as DiffEqDevTools and the server's render/work-precision draw it: global error (x)
// against solver CPU seconds (y), both log; one line per choice joining its step sizes in order of h, with its
// style's colour, dash and marker, each marker labelled with its h (k of h = 2^k), and its fitted order p in the
// legend. Clicking a legend entry hides or shows that series. Hovering a
// marker shows its h, CPU time, error and iterations in `hover`. uPlot's mode 2: every series has its own xs.
export function workPrecisionChart(container, runs, hover) {
  const tables = runs.map((r) => {
    const pts = r.points.filter((p) => positive(p.cpu_seconds) && positive(p.global_error)).sort((a, b) => b.h - a.h);
    return { pts, xy: [pts.map((p) => p.global_error), pts.map((p) => p.cpu_seconds)] };
  });
  const all = (k) => tables.flatMap((t) => t.xy[k]);
  const xr = decades(null, Math.min(...all(0)), Math.max(...all(0)));
  const yr = decades(null, Math.min(...all(1)), Math.max(...all(1)));
  const series = [{}].concat(runs.map((r, i) => {
    const st = seriesStyle(i);
    // Points the order is not fitted from (in_fit false) are drawn grey: drawMarkers reads _excluded.
    return { label: r.label, stroke: st.color, dash: st.dash, width: 2, _color: st.color, _marker: st.marker,
      _excluded: tables[i].pts.map((p) => p.in_fit === false),
      facets: [{ scale: 'x', auto: false }, { scale: 'y', auto: false }], paths: uPlot.paths.linear(),
      points: { show: false } };
  }));
  const show = (u) => {
    const hit = nearest(u);
    if (!hit) { hover.textContent = 'Hover a marker to read its h, CPU time, error and iterations.'; return; }
    const [i, k] = hit;
    const p = tables[i - 1].pts[k];
    const cpu = p.cpu_runs ? `median ${spreadText(p.cpu_runs)} of ${p.cpu_runs.length} runs` : fmtSeconds(p.cpu_seconds);
    hover.textContent = `${runs[i - 1].label}: h = ${fmtH(p.h)}, solver CPU time ${cpu}, ` +
      `global error ${fmtExp(p.global_error)}, ${p.iterations} iterations` +
      (p.in_fit === false && p.excluded ? `; not in the fit: ${p.excluded}` : '');
    hover.dataset.h = String(p.h);
  };
  const opts = {
    mode: 2,
    series,
    scales: { x: { time: false, distr: 3, log: 10, range: () => xr }, y: { distr: 3, log: 10, range: () => yr } },
    axes: [logAxis('global error at t_end', { size: 50 }), logAxis('solver CPU time [s]')],
    legend: { live: false },
    cursor: { drag: { x: false, y: false }, points: { show: false } },
    hooks: { draw: [drawMarkers, (u) => drawHLabels(u, tables)], setCursor: [show] },
    height: 380,
  };
  const plot = mount(container, opts, [null, ...tables.map((t) => t.xy)]);
  container.dataset.points = String(tables.reduce((a, t) => a + t.pts.length, 0));
  container.dataset.series = String(runs.length);
  show(plot);
  // What is plotted, for the browser tests (as data-points / data-series are): CPU times per series in drawing
  // order, each series' style, and the page position of the first marker.
  (window.__lienewtonCharts ??= {})[container.id] = {
    cpu: tables.map((t) => t.xy[1]),
    styles: runs.map((_, i) => ({ color: seriesStyle(i).color, marker: seriesStyle(i).marker })),
    firstMarker() {
      const box = plot.over.getBoundingClientRect();
      return { x: box.left + plot.valToPos(tables[0].xy[0][0], 'x'), y: box.top + plot.valToPos(tables[0].xy[1][0], 'y') };
    },
  };
  return plot;
}

// Each shown marker's h (as 2^k where it is a power of two) just above it, in its series' colour on a halo of the
// chart's background; a label that would cover one already drawn is left out (coinciding series share theirs).
function drawHLabels(u, tables) {
  const c = u.ctx;
  const px = devicePixelRatio;
  c.save();
  c.font = `${11 * px}px system-ui, sans-serif`;
  c.textAlign = 'center';
  c.textBaseline = 'bottom';
  c.lineWidth = 3 * px;
  c.strokeStyle = getComputedStyle(u.root).getPropertyValue('--card').trim() || '#fff';
  const drawn = [];
  tables.forEach((t, i) => {
    if (!u.series[i + 1].show) return;
    t.pts.forEach((p, k) => {
      c.fillStyle = p.in_fit === false ? EXCLUDED_GREY : u.series[i + 1]._color;
      const kk = Math.log2(p.h);
      const text = Number.isInteger(kk) ? `2${superscript(kk)}` : String(p.h);
      const x = u.valToPos(t.xy[0][k], 'x', true);
      const y = u.valToPos(t.xy[1][k], 'y', true) - 8 * px;
      const w = c.measureText(text).width;
      const box = [x - w / 2, y - 12 * px, x + w / 2, y];
      if (drawn.some((d) => box[0] < d[2] && d[0] < box[2] && box[1] < d[3] && d[1] < box[3])) return;
      drawn.push(box);
      c.strokeText(text, x, y);
      c.fillText(text, x, y);
    });
  });
  c.restore();
}

// An invariant's error over time (energy, vertical momentum: name), |I(t) - I(0)| / |I(0)| on a log axis so that
// drifts of very different sizes (implicit Euler against DIRK-CG2) show on one chart; one series per choice, same
// step times.
// axisLabel: what the values are, when they are not relative to |I(0)| (e.g. relative to the invariant's scale).
export function invariantChart(container, times, runs, name, axisLabel = `${name}: |I(t) \u2212 I(0)| / |I(0)|`) {
  // The work-precision chart's styles (same choice, same colour and dash): coinciding runs stay visible.
  const series = [{ label: 't', class: 'x-series' }].concat(runs.map((r, i) => styledLine(r.label, i)));
  const opts = {
    series,
    scales: { x: { time: false }, y: { distr: 3, log: 10, range: decades } },
    axes: [{ label: 'time t' }, logAxis(axisLabel)],
    legend: { live: true },
  };
  const plot = mount(container, opts, [times, ...runs.map((r) => r.values.map((v) => positive(Math.abs(v))))]);
  record(container, plot);
  return plot;
}

// State components against time on a linear axis (signed values: an angular velocity's components), one line each.
export function stateChart(container, times, runs, axisLabel) {
  const series = [{ label: 't', class: 'x-series' }].concat(runs.map((r, i) => styledLine(r.label, i)));
  const opts = { series, scales: { x: { time: false } }, axes: [{ label: 'time t' }, { label: axisLabel, size: 60 }],
    legend: { live: true } };
  const plot = mount(container, opts, [times, ...runs.map((r) => r.values)]);
  record(container, plot);
  return plot;
}

// Solver speed against accuracy: ||f(y_n)|| (y) against the solver's cumulative CPU time (x), both log, one
// line per run in the server's styles. set(tables) takes per run [cpu_seconds[], residual[]] so far.
export function residualTimeChart(container, labels) {
  const series = [{}].concat(labels.map((text, i) => ({ ...styledLine(text, i), paths: uPlot.paths.linear(),
    facets: [{ scale: 'x', auto: false }, { scale: 'y', auto: false }] })));
  let xr = [1e-6, 1e-3]; let yr = [1e-16, 1];
  const opts = {
    mode: 2,
    series,
    scales: { x: { time: false, distr: 3, log: 10, range: () => xr }, y: { distr: 3, log: 10, range: () => yr } },
    axes: [logAxis('solver CPU time [s] (cpu_seconds)', { size: 50 }), logAxis('\u2016f(y\u2099)\u2016')],
    legend: { live: false },
    cursor: { drag: { x: false, y: false }, points: { show: false } },
    hooks: { draw: [drawMarkers] },
  };
  const plot = mount(container, opts, [null, ...labels.map(() => [[], []])]);
  return {
    set(tables) {
      const clean = tables.map(([xs, ys]) => {
        const keep = xs.map((x, k) => positive(x) && positive(ys[k]));
        return [xs.filter((_, k) => keep[k]), ys.filter((_, k) => keep[k])];
      });
      const xsAll = clean.flatMap((t) => t[0]);
      const ysAll = clean.flatMap((t) => t[1]);
      if (xsAll.length) { xr = decades(null, Math.min(...xsAll), Math.max(...xsAll)); yr = decades(null, Math.min(...ysAll), Math.max(...ysAll)); }
      plot.setData([null, ...clean]);
      container.dataset.points = String(xsAll.length);
      container.dataset.series = String(labels.length);
      // The runs as given, zeros included (the browser tests read the time to tol off them).
      (window.__lienewtonCharts ??= {})[container.id] = { tables: tables.map(([xs, ys]) => [[...xs], [...ys]]) };
    },
  };
}
