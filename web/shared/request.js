// The fields every solve-like request has, built and read the same way in every panel.
import { contractNumber, number, select, spec, stepSize } from './fields.js';
import { value } from './form.js';
import { PROBLEMS } from './labels.js';

// n, tol, max_iterations and seed as the server defaults them; the rest are the dashboard's choice.
export const DEFAULTS = { problem: 'paper-linear', h: 0.5, method: 'newton-group', differential: 'exact',
  ...Object.fromEntries(['n', 'tol', 'max_iterations', 'seed'].map((name) => [name, spec('SolveRequest', name).default])) };

export function problemFields(d = DEFAULTS) {
  return [
    select('problem', 'Problem', PROBLEMS, d.problem),
    number('n', 'Dimension N (SO(N))', d.n, 'rigid-body needs N = 3'),
    stepSize(d.h),
  ];
}

export function limitFields(d = DEFAULTS) {
  return [
    contractNumber('SolveRequest', 'tol', 'Tolerance on \u2016f(y)\u2016', { value: d.tol }),
    contractNumber('SolveRequest', 'max_iterations', 'Max iterations', { value: d.max_iterations }),
    contractNumber('SolveRequest', 'seed', 'Seed of the random start point', { value: d.seed }),
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
