// The fields every solve-like request has, built and read the same way in every panel.
import { number, select, stepSize } from './fields.js';
import { value } from './form.js';
import { PROBLEMS } from './labels.js';

export const DEFAULTS = { problem: 'paper-linear', n: 3, h: 0.5, method: 'newton-group', differential: 'exact',
  tol: 1e-13, max_iterations: 100, seed: 1 };

export function problemFields(d = DEFAULTS) {
  return [
    select('problem', 'Problem', PROBLEMS, d.problem),
    number('n', 'Dimension N (SO(N))', d.n, 'rigid-body needs N = 3'),
    stepSize(d.h),
  ];
}

export function limitFields(d = DEFAULTS) {
  return [
    number('tol', 'Tolerance on \u2016f(y)\u2016', d.tol),
    number('max_iterations', 'Max iterations', d.max_iterations),
    number('seed', 'Seed of the random start point', d.seed),
  ];
}

export function readCommon(form) {
  const out = {};
  for (const name of ['problem', 'n', 'h', 'tol', 'max_iterations', 'seed']) out[name] = value(form, name);
  return out;
}

// Sets form controls from a request (e.g. a stability-map cell opened in Solve); fires input so that
// linked widgets such as the h slider follow.
export function fill(form, request) {
  for (const [name, v] of Object.entries(request)) {
    const control = form.elements.namedItem(name);
    if (!control || control instanceof RadioNodeList) continue;
    control.value = String(v);
    control.dispatchEvent(new Event('input', { bubbles: true }));
  }
}
