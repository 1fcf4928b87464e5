// Names and colours shared by every panel: API values -> words a reader understands (from the server's
// catalog), plus number formats.
import { catalog, choices, entries } from './catalog.js';

export const PROBLEMS = choices('problem');
export const METHODS = choices('method');
export const DIFFERENTIALS = choices('differential');
// Column heads of the method x differential tick tables, which must fit a narrow form.
export const DIFFERENTIALS_SHORT = choices('differential', 'short');
export const INTEGRATORS = choices('integrator');
export const METRICS = choices('heatmap_metric');
export const GLOBALIZATIONS = choices('globalization');
// The boolean continuation as a select: the paper's direct solve at h, or following z's branch of roots from h = 0.
export const CONTINUATION = [['false', 'Off (solve at h directly)'], ['true', 'On (follow z\u2019s root from h = 0)']];

// Per status: the colour of its badge and heatmap cells (the renderer's failure colours, outside viridis) and
// a one-line description.
export const STATUSES = Object.fromEntries(entries('status').map((s) => [s.value, { color: s.color, text: s.description }]));

// Colour x dash x marker per series, distinct for 24 series: the renderer's own table, so PNGs match.
export const SERIES_STYLES = catalog.series_styles;

export function label(list, value) {
  const hit = list.find(([v]) => v === value);
  return hit ? hit[1] : value;
}

// The server's reasons are ASCII (||f||, pi, !=, z^-1, y_3, 1/2 ||f||^2) for curl users; the page shows them
// in mathematical notation.
const SUBSCRIPTS = '\u2080\u2081\u2082\u2083\u2084\u2085\u2086\u2087\u2088\u2089';
export function mathText(text) {
  return String(text ?? '')
    .replace(/\|\|/g, '\u2016')
    .replace(/\bpi\b/g, '\u03c0')
    .replace(/!=/g, '\u2260')
    .replace(/<=/g, '\u2264')
    .replace(/>=/g, '\u2265')
    .replace(/\^-1/g, '\u207b\u00b9')
    .replace(/\^2/g, '\u00b2')
    .replace(/\^T/g, '\u1d40')
    .replace(/\b1\/2 /g, '\u00bd ')
    .replace(/\b([yv])_(\d+)/g, (_, v, d) => v + subscript(d))
    .replace(/f~/g, 'f\u0303');
}

export function subscript(n) {
  return String(n).replace(/\d/g, (d) => SUBSCRIPTS[Number(d)]);
}

// A frame slider's words for iterate n of a solve.
export function iterateText(n, residual) {
  return `n = ${n}: \u2016f(y${subscript(n)})\u2016 = ${fmtExp(residual)}`;
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
  const exact = Number.isInteger(k) ? ` (2${superscript(k)})` : '';
  return `${Number(h.toPrecision(6))}${exact}`;
}

// 2^-3 as 2⁻³: whole numbers in superscript digits.
const SUPERSCRIPTS = '\u2070\u00b9\u00b2\u00b3\u2074\u2075\u2076\u2077\u2078\u2079';
export function superscript(k) {
  return String(k).replace('-', '\u207b').replace(/\d/g, (d) => SUPERSCRIPTS[Number(d)]);
}
