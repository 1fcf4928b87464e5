// The heatmap colours, the same as the server's renderer (render/colormap.cpp, heatmap_scene.cpp) so that
// the interactive grid and the PNG read alike: viridis for a converged cell's metric, one flat colour per
// failure class, grey where a converged cell has no value for the metric (e.g. no rate).
export const NO_VALUE = 'rgb(200,200,200)';

// Degree-6 polynomial fit of matplotlib's viridis, the same coefficients as the renderer.
const VIRIDIS = [
  [0.2777273272234177, 0.005407344544966578, 0.3340998053353061],
  [0.1050930431085774, 1.404613529898575, 1.384590162594685],
  [-0.3308618287255563, 0.214847559468213, 0.09509516302823659],
  [-4.634230498983486, -5.799100973351585, -19.33244095627987],
  [6.228269936347081, 14.17993336680509, 56.69055260068105],
  [4.776384997670288, -13.74514537774601, -65.35303263337234],
  [-5.435455855934631, 4.645852612178535, 26.3124352495832],
];

export function viridis(t) {
  const x = Number.isNaN(t) ? 0 : Math.min(1, Math.max(0, t));
  const rgb = [0, 1, 2].map((k) => {
    let v = VIRIDIS[6][k];
    for (let i = 5; i >= 0; i -= 1) v = v * x + VIRIDIS[i][k];
    return Math.round(Math.min(1, Math.max(0, v)) * 255);
  });
  return `rgb(${rgb.join(',')})`;
}

export function metricValue(cell, metric) {
  if (cell.status !== 'converged') return null;
  if (metric === 'iterations') return cell.iterations;
  if (metric === 'rate') return Number.isFinite(cell.rate) ? cell.rate : null;
  return Number.isFinite(cell.residual) ? Math.log10(Math.max(Math.abs(cell.residual), 1e-18)) : null;
}

// Range of the metric over the converged cells; a single value is widened by one either side.
export function metricScale(cells, metric) {
  const values = cells.map((c) => metricValue(c, metric)).filter((v) => v !== null);
  if (!values.length) return { lo: 0, hi: 1 };
  const lo = Math.min(...values);
  const hi = Math.max(...values);
  return lo === hi ? { lo: lo - 1, hi: hi + 1 } : { lo, hi };
}

export function cellColor(cell, metric, scale, statusColors) {
  if (cell.status !== 'converged') return statusColors[cell.status]?.color ?? NO_VALUE;
  const v = metricValue(cell, metric);
  return v === null ? NO_VALUE : viridis((v - scale.lo) / (scale.hi - scale.lo));
}

export function rampCss() {
  return `linear-gradient(to right, ${[0, 0.25, 0.5, 0.75, 1].map(viridis).join(', ')})`;
}
