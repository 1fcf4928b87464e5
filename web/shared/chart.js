// Thin wrappers around uPlot (vendored in vendor/, see vendor/README.md). Each chart follows its
// container's width, and records how many points and series it draws in data-points / data-series so
// that the browser tests check what is actually plotted.
import uPlot from '../vendor/uPlot.esm.js';
import { SERIES_COLORS, fmtExp, fmtSeconds } from './labels.js';

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

function logAxis(label, extra = {}) {
  return { label, values: logAxisValues, size: 60, space: 24, gap: 4, ...extra };
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

// Replaces the container's chart. The old one is destroyed: a detached uPlot that still resizes
// recomputes its axes with no data, and its log-axis tick loop then never ends.
function mount(container, opts, data) {
  const old = mounted.get(container);
  if (old) {
    old.observer.disconnect();
    old.plot.destroy();
  }
  container.replaceChildren();
  const width = () => Math.max(280, container.clientWidth);
  const plot = new uPlot({ ...opts, width: width(), height: opts.height ?? 300 }, data, container);
  const observer = new ResizeObserver(() => {
    if (container.clientWidth > 0) plot.setSize({ width: width(), height: plot.height });
  });
  observer.observe(container);
  mounted.set(container, { plot, observer });
  return plot;
}

function record(container, plot) {
  container.dataset.points = String(plot.data[0].length);
  container.dataset.series = String(plot.series.length - 1);
}

// One coloured series; the legend shows values in the same format as the tables.
function line(label, i, extra = {}) {
  return { label, stroke: SERIES_COLORS[i % SERIES_COLORS.length], width: 2, value: (u, v) => fmtExp(v), ...extra };
}

// Residual ||f(y_n)|| against n on a log axis, one series per run; xs are iteration numbers.
export function residualChart(container, labels) {
  const series = [{ label: 'n' }].concat(labels.map((text, i) => line(text, i, { points: { show: true, size: 6 } })));
  const opts = {
    series,
    scales: { x: { time: false }, y: { distr: 3, log: 10, range: decades } },
    axes: [{ label: 'iteration n' }, logAxis('\u2016f(y\u2099)\u2016')],
    legend: { live: true },
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
    },
  };
}

// Work-precision: CPU seconds (x) against global error (y), both log, one series per choice. Points only:
// CPU times of short runs are noisy, and a line in CPU order would zigzag.
export function workPrecisionChart(container, runs) {
  const tables = runs.map((r) => {
    const pts = r.points.filter((p) => positive(p.cpu_seconds) && positive(p.error))
      .sort((a, b) => a.cpu_seconds - b.cpu_seconds);
    return [pts.map((p) => p.cpu_seconds), pts.map((p) => p.error)];
  });
  const data = tables.length ? uPlot.join(tables) : [[]];
  const series = [{ label: 'CPU time', value: (u, v) => fmtSeconds(v) }].concat(runs.map((r, i) =>
    line(r.label, i, { points: { show: true, size: 8, fill: SERIES_COLORS[i % SERIES_COLORS.length] }, paths: () => null })));
  const opts = {
    series,
    scales: { x: { time: false, distr: 3, log: 10, range: decades }, y: { distr: 3, log: 10, range: decades } },
    axes: [logAxis('CPU time [s]', { size: 50 }), logAxis('global error at t_end')],
    legend: { live: true },
    height: 340,
  };
  const plot = mount(container, opts, data);
  record(container, plot);
  return plot;
}

// Rigid-body energy error over time, |E(t) - E(t1)| / E(t1) on a log axis so that drifts of very different
// sizes (implicit Euler against DIRK-CG2) show on one chart; one series per choice, same step times.
export function energyChart(container, times, runs) {
  const series = [{ label: 't' }].concat(runs.map((r, i) => line(r.label, i, { points: { show: true, size: 5 } })));
  const opts = {
    series,
    scales: { x: { time: false }, y: { distr: 3, log: 10, range: decades } },
    axes: [{ label: 'time t' }, logAxis('|E(t) \u2212 E(t\u2081)| / E(t\u2081)')],
    legend: { live: true },
  };
  const plot = mount(container, opts, [times, ...runs.map((r) => r.values.map((v) => positive(Math.abs(v))))]);
  record(container, plot);
  return plot;
}
