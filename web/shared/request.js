// The fields every solve-like request has, built and read the same way in every panel.
import { el } from './dom.js';
import { contractNumber, field, folded, number, select, spec, stepSize } from './fields.js';
import { value } from './form.js';
import { entry } from './catalog.js';
import { PROBLEMS } from './labels.js';
import { parameterTable } from './parameters.js';
import { codeEditor } from './code_editor.js';

// n, tol, max_iterations and seed as the server defaults them; the rest are the dashboard's choice.
export const DEFAULTS = { problem: 'paper-linear', h: 0.5, method: 'newton-group', differential: 'exact',
  ...Object.fromEntries(['n', 'tol', 'max_iterations', 'seed'].map((name) => [name, spec('SolveRequest', name).default])) };

// The built-ins as a user writes them (MATLAB notation, the paper's section 5), with their parameters.
export const PROGRAMS = {
  'paper-linear': ['g = diag(diag(y,1),1) - diag(diag(y,1),-1)', ''],
  'paper-sine': ["u = sin(y)*(2*y - 5*y^2);\ng = u - u'", ''],
  'rigid-body': ["w = J \\ (y' * m);\ng = [0 -w(3) w(2); w(3) 0 -w(1); -w(2) w(1) 0]",
    '{"J": [[1,0,0],[0,2,0],[0,0,3]], "m": [[0.6],[0.8],[0.5]]}'],
  // On SO(3)xR^3: y = diag(R, [[I, w], [0, 1]]), g = diag(hat(w), [[0, w'], [0, 0]]) (docs/requests.md).
  'heavy-top': ["R = y(1:3,1:3); w = y(4:6,7);\n"
    + "dw = (cross(J .* w, w) + m * cross(chi, R' * gamma)) ./ J;\n"
    + 'W = [0 -w(3) w(2); w(3) 0 -w(1); -w(2) w(1) 0];\n'
    + 'g = [W zeros(3,4); zeros(4,3) [zeros(3) dw; zeros(1,4)]]',
  '{"J": [[15.234375],[0.46875],[15.234375]], "m": 15, "chi": [[0],[1],[0]], "gamma": [[0],[0],[-9.81]]}', 'SOxR'],
  'stiff-body': ["R = y(1:3,1:3); w = y(4:6,7); S = (R - R') / 2;\n"
    + 'a = (cross(J .* w, w) - k * [S(3,2); S(1,3); S(2,1)] - c * w + f .* [sin(2*t); cos(t); 1]) ./ J;\n'
    + 'W = [0 -w(3) w(2); w(3) 0 -w(1); -w(2) w(1) 0];\n'
    + 'g = [W zeros(3,4); zeros(4,3) [zeros(3) a; zeros(1,4)]]',
  '{"J": [[1],[2],[3]], "k": 10000, "c": 10000, "f": [[0.5],[0.3],[0.2]]}', 'SOxR'],
};

// The groups a program may be written on, as the server registers them (SExR^k: k = N bodies).
const GROUPS = spec('SolveRequest', 'group').anyOf?.find((a) => a.enum)?.enum ?? ['SO'];

// "Your g(y)": a program sent as g instead of the problem, its parameters in a small table; the button fills
// both with the chosen problem written as a program. Like every field, both travel in the page's URL.
export function programFields() {
  const g = el('textarea', { name: 'g', rows: 4, spellcheck: 'false', autocomplete: 'off', class: 'code', wrap: 'off' });
  const parameters = parameterTable();
  const group = select('group', 'Group of your g', GROUPS.map((v) => [v, v]), 'SO',
    'SO: SO(N); SE, SOxR, SExR: N = 3; SExR^k: k = N bodies (docs/requests.md, groups and their matrices)');
  const fillButton = el('button', { type: 'button' }, 'Edit the problem as a program');
  fillButton.addEventListener('click', () => {
    const problem = fillButton.form.elements.namedItem('problem').value;
    const hidden = parameters.querySelector('input[name="parameters"]');
    const groupSelect = group.querySelector('select');
    let on;
    [g.value, hidden.value, on = 'SO'] = PROGRAMS[problem] ?? ['', ''];
    groupSelect.value = on;
    // As if typed: the page's URL keeps the program (shared/share.js), the table shows the parameters.
    for (const control of [g, hidden, groupSelect]) control.dispatchEvent(new Event('input', { bubbles: true }));
  });
  const gField = field('g', 'Your g(y) in MATLAB notation (empty: the built-in above)', g,
    "MATLAB notation over y and t (the time when integrating, 0 otherwise), e.g. u = sin(y)*(2*y - 5*y^2); g = u - u'. Errors name the line and column");
  const anchor = g.nextSibling;
  const editor = codeEditor(g);
  gField.insertBefore(editor.element, anchor);
  gField.addEventListener('program-error', (e) => editor.mark(e.detail.line, e.detail.column));
  return folded('Your own g(y)', group, gField, fillButton, parameters);
}

export function problemFields(d = DEFAULTS) {
  return [
    select('problem', 'Problem', PROBLEMS, d.problem),
    number('n', 'Dimension N (SO(N))', d.n, 'rigid-body needs N = 3'),
    stepSize(d.h),
    programFields(),
  ];
}

// The request's field: {problem} (with its group when the server's catalog names one: heavy-top and stiff-body on
// SOxR), or {g, parameters} when the form has a program. Parameters that are not JSON are sent as typed, so the server
// names the field.
export function problemOf(form) {
  const g = form.elements.namedItem('g')?.value.trim();
  if (!g) {
    const problem = value(form, 'problem');
    const { group } = entry('problem', problem);
    return group ? { problem, group } : { problem };
  }
  const group = form.elements.namedItem('group')?.value;
  const on = group && group !== 'SO' ? { g, group } : { g };  // SO is the server's default
  const text = form.elements.namedItem('parameters')?.value.trim();
  if (!text) return on;
  try {
    return { ...on, parameters: JSON.parse(text) };
  } catch {
    return { ...on, parameters: text };
  }
}

// The group a sent request is on: its program's (SO when it names none, the server's default), or its built-in
// problem's as the catalog names it (heavy-top: SOxR; the paper's problems: SO).
export function groupOf(request) {
  return request.g ? request.group ?? 'SO' : entry('problem', request.problem).group ?? 'SO';
}

export function limitFields(d = DEFAULTS) {
  return [
    contractNumber('SolveRequest', 'tol', 'Tolerance on \u2016f(y)\u2016', { value: d.tol }),
    contractNumber('SolveRequest', 'max_iterations', 'Max iterations', { value: d.max_iterations }),
    contractNumber('SolveRequest', 'seed', 'Seed of the random start point', { value: d.seed }),
  ];
}

// A sent request's field as form values, for opening one of its runs in another panel: the problem, or the
// program and its parameters.
export function fieldValues(request) {
  return request.g ? { g: request.g, group: request.group ?? 'SO', parameters: request.parameters ? JSON.stringify(request.parameters) : '' }
    : { problem: request.problem, g: '', parameters: '' };
}

export function readCommon(form) {
  const out = problemOf(form);
  for (const name of ['n', 'h', 'tol', 'max_iterations', 'seed']) out[name] = value(form, name);
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
