// Names and colours shared by every panel: API values -> words a reader understands, plus number formats.

export const PROBLEMS = [
  ['paper-linear', 'paper-linear (\u00a75, linear g)'],
  ['paper-sine', 'paper-sine (\u00a75, sine g)'],
  ['rigid-body', 'rigid-body (free rigid body)'],
];

export const METHODS = [
  ['fixed-point', 'Fixed point (1.2)'],
  ['newton-group', 'Newton V1, group (3.5)'],
  ['newton-algebra', 'Newton V2, algebra (3.20)'],
];

export const DIFFERENTIALS = [
  ['finite-difference', 'Finite differences'],
  ['dexpinv-0', 'dexp\u207b\u00b9 to order 0'],
  ['dexpinv-1', 'dexp\u207b\u00b9 to order 1'],
  ['exact', 'Exact dexp\u207b\u00b9'],
];

// Column heads of the method x differential tick tables, which must fit a narrow form.
export const DIFFERENTIALS_SHORT = [
  ['finite-difference', 'FD'],
  ['dexpinv-0', 'order 0'],
  ['dexpinv-1', 'order 1'],
  ['exact', 'exact'],
];

export const INTEGRATORS = [
  ['implicit-euler', 'Implicit Euler'],
  ['dirk-cg2', 'DIRK Crouch\u2013Grossman 2'],
];

export const METRICS = [
  ['iterations', 'Iterations'],
  ['rate', 'Convergence rate r'],
  ['residual', 'Final residual'],
];

// Failure colours: the renderer's (render/colormap.cpp), chosen outside viridis, which colours converged cells.
export const STATUSES = {
  converged: { color: '#1b7837', text: 'converged: \u2016f(y)\u2016 \u2264 tol' },
  max_iterations: { color: 'rgb(215,48,39)', text: 'max iterations reached above tol' },
  diverged: { color: 'rgb(40,40,40)', text: 'diverged: residual or step blew up' },
  non_finite: { color: 'rgb(231,41,138)', text: 'non-finite: NaN or Inf appeared' },
  left_log_domain: { color: 'rgb(253,141,60)', text: 'left the log domain (angle reached \u03c0)' },
  singular_differential: { color: 'rgb(140,86,75)', text: 'singular Newton system' },
  stagnated: { color: 'rgb(158,218,229)', text: 'stagnated at the rounding floor' },
  off_branch: { color: 'rgb(247,182,210)', text: 'solved, but h g(y) beyond angle \u03c0 (off branch)' },
  cancelled: { color: 'rgb(120,120,120)', text: 'cancelled, not computed' },
};

export const SERIES_COLORS = ['#0072b2', '#d55e00', '#009e73', '#cc79a7', '#e69f00', '#56b4e9', '#000000',
  '#8c564b', '#7f7f7f', '#bcbd22'];

export function label(list, value) {
  const hit = list.find(([v]) => v === value);
  return hit ? hit[1] : value;
}

// Exponential with 3 decimals: readable and still parseable by Number().
export function fmtExp(x) {
  if (x === null || x === undefined) return '\u2014';
  if (!Number.isFinite(x)) return String(x);
  return x === 0 ? '0' : x.toExponential(3);
}

export function fmtRate(r) {
  return r === null || r === undefined ? '\u2014' : r.toFixed(3);
}

export function fmtSeconds(s) {
  if (s === null || s === undefined) return '\u2014';
  if (s < 1e-3) return `${(s * 1e6).toFixed(1)} \u00b5s`;
  if (s < 1) return `${(s * 1e3).toFixed(2)} ms`;
  return `${s.toFixed(2)} s`;
}

// h values of the grids are powers of two: show both forms.
export function fmtH(h) {
  const k = Math.log2(h);
  const exact = Number.isInteger(k) ? ` (2^${k})` : '';
  return `${Number(h.toPrecision(6))}${exact}`;
}
