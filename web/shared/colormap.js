// The heatmap colours, the same as the server's renderer (render/colormap.cpp, heatmap_scene.cpp) so that
// the interactive grid and the PNG read alike (the grid's range is fixed before its sweep, the PNG's is its
// cells' range; each has its colour bar): viridis for a converged cell's metric, one flat colour per
// failure class, grey where a converged cell has no value for the metric (e.g. no rate). All of them come
// from the server's catalog.
import { catalog } from './catalog.js';

export const NO_VALUE = catalog.colors.no_value;

// The renderer's viridis sampled at 256 evenly spaced t; linear interpolation in between.
const STOPS = catalog.colors.viridis;

export function viridis(t) {
  const x = (Number.isNaN(t) ? 0 : Math.min(1, Math.max(0, t))) * (STOPS.length - 1);
  const i = Math.min(Math.floor(x), STOPS.length - 2);
  const f = x - i;
  const rgb = [0, 1, 2].map((k) => Math.round(STOPS[i][k] + f * (STOPS[i + 1][k] - STOPS[i][k])));
  return `rgb(${rgb.join(',')})`;
}

export function metricValue(cell, metric) {
  if (cell.status !== 'converged') return null;
  if (metric === 'iterations') return cell.iterations;
  if (metric === 'rate') return Number.isFinite(cell.rate) ? cell.rate : null;
  return Number.isFinite(cell.residual) ? Math.log10(Math.max(Math.abs(cell.residual), 1e-18)) : null;
}

// Rates are coloured on a fixed 0..3 (linear r = 1, quadratic r = 2, (3.8)-(3.9)): a few wild rates of
// nearly stagnant runs would otherwise squeeze every meaningful cell into one colour. Cells outside are
// clamped to the ends and flagged as outliers.
export const RATE_RANGE = { lo: 0, hi: 3 };

export function isOutlier(cell, metric) {
  const v = metricValue(cell, metric);
  return metric === 'rate' && v !== null && (v < RATE_RANGE.lo || v > RATE_RANGE.hi);
}

// The scale fixed before a sweep starts, so that no cell changes colour while it runs: from the smallest value
// its probe met (the cells of a few of its rows) to the largest the request allows (max_iterations iterations,
// a residual of tol); rates on their fixed 0..3.
export function fixedScale(metric, request, probeCells) {
  if (metric === 'rate') return RATE_RANGE;
  const hi = metric === 'iterations' ? request.max_iterations : Math.log10(Math.max(request.tol, 1e-18));
  const seen = probeCells.map((c) => metricValue(c, metric)).filter((v) => v !== null && v < hi);
  return { lo: seen.length ? Math.min(...seen) : hi - 1, hi };
}

export function cellColor(cell, metric, scale, statusColors) {
  if (cell.status !== 'converged') return statusColors[cell.status]?.color ?? NO_VALUE;
  const v = metricValue(cell, metric);
  return v === null ? NO_VALUE : viridis((v - scale.lo) / (scale.hi - scale.lo));
}

export function rampCss() {
  return `linear-gradient(to right, ${[0, 0.25, 0.5, 0.75, 1].map(viridis).join(', ')})`;
}
