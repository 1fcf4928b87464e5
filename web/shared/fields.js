// Builders for the form fields the panels share. Every field is wrapped in .field[data-field=<API name>]
// with an error slot, so a server error naming that field lands right under it.
import { schemas } from './catalog.js';
import { el, uid } from './dom.js';
import { EXPLAINED, explainer, explainerList } from './explain.js';
import { fillSelect } from './form.js';

export function field(name, labelText, control, hint) {
  const id = control.id || (control.id = uid(name));
  const errId = `${id}-error`;
  const hintId = hint ? `${id}-hint` : null;
  control.setAttribute('aria-describedby', [errId, hintId].filter(Boolean).join(' '));
  return el('div', { class: 'field', dataset: { field: name } },
    el('label', { for: id }, labelText),
    control,
    hint ? el('small', { class: 'hint', id: hintId }, hint) : null,
    el('p', { class: 'field-error', id: errId, 'aria-live': 'polite' }));
}

// Problem, method and differential selects carry a "What is this?" disclosure for their current value.
export function select(name, labelText, options, value, hint) {
  const s = el('select', { name });
  fillSelect(s, options, value);
  const wrapper = field(name, labelText, s, hint);
  if (EXPLAINED.includes(name)) wrapper.querySelector('.field-error').before(explainer(s));
  return wrapper;
}

export function number(name, labelText, value, hint) {
  const input = el('input', { name, type: 'text', inputmode: 'decimal', value: String(value),
    autocomplete: 'off', spellcheck: 'false', dataset: { type: 'number' } });
  return field(name, labelText, input, hint);
}

// A field of a request schema as /openapi.json states it: type, bounds, enum, default and description (an
// array's element bounds, with the array's description).
export function spec(schema, name) {
  const p = schemas[schema]?.properties?.[name];
  if (!p) throw new Error(`/openapi.json describes no ${schema}.${name}`);
  return p.type === 'array' ? { ...p.items, description: p.description } : p;
}

// A field's bounds as a hint: "0 to 10000", "over 0, up to 100", "at most 512", "at least 1".
export function rangeText(p) {
  const lo = p.minimum === undefined ? '' : `${p.exclusiveMinimum ? 'over' : 'at least'} ${p.minimum}`;
  if (p.maximum === undefined) return lo;
  if (!lo) return `at most ${p.maximum}`;
  return p.exclusiveMinimum ? `${lo}, up to ${p.maximum}` : `${p.minimum} to ${p.maximum}`;
}

// A number box for a field of the request contract: the schema's default unless value is given, the schema's
// bounds after the hint, the schema's description as the box's title.
export function contractNumber(schema, name, labelText, { value, hint } = {}) {
  const p = spec(schema, name);
  const wrapper = number(name, labelText, value ?? p.default, [hint, rangeText(p)].filter(Boolean).join(', '));
  wrapper.querySelector('input').title = p.description ?? '';
  return wrapper;
}

// h with a log2 slider (2^-10 .. 2^10) bound to a numeric box; the box is what gets sent.
export function stepSize(value) {
  const box = el('input', { name: 'h', type: 'text', inputmode: 'decimal', value: String(value),
    autocomplete: 'off', spellcheck: 'false', dataset: { type: 'number' } });
  const slider = el('input', { type: 'range', min: -10, max: 10, step: 0.25, value: Math.log2(value),
    'aria-label': 'log2 of h', class: 'log-slider' });
  const readout = el('output', { class: 'slider-readout' });
  const syncReadout = () => { readout.textContent = `log\u2082 h = ${slider.value}`; };
  slider.addEventListener('input', () => {
    box.value = String(Number((2 ** Number(slider.value)).toPrecision(6)));
    syncReadout();
  });
  box.addEventListener('input', () => {
    const h = Number(box.value);
    if (Number.isFinite(h) && h > 0) slider.value = String(Math.log2(h));
    syncReadout();
  });
  syncReadout();
  const wrapper = field('h', 'Step size h', box);
  wrapper.querySelector('label').after(el('div', { class: 'slider-row' }, slider, readout));
  return wrapper;
}

// explained: enum names whose values the boxes are (e.g. ['method']), explained in a disclosure.
export function checkboxes(name, legend, options, checked, explained = []) {
  return el('fieldset', { class: 'field checks', dataset: { field: name } },
    el('legend', {}, legend),
    options.map(([v, text]) => el('label', { class: 'check' },
      el('input', { type: 'checkbox', name, value: v, checked: checked.includes(v) }), ' ', text)),
    explained.length ? explainerList(explained) : null,
    el('p', { class: 'field-error', 'aria-live': 'polite' }));
}

// Two numbers that form one API field (e.g. the N range of a sweep).
export function range(name, legend, [loName, lo], [hiName, hi], hint) {
  const box = (n, v, text) => el('label', { class: 'range-end' }, text,
    el('input', { name: n, type: 'text', inputmode: 'decimal', value: String(v), autocomplete: 'off', dataset: { type: 'number' } }));
  return el('fieldset', { class: 'field range', dataset: { field: name } },
    el('legend', {}, legend),
    el('div', { class: 'range-row' }, box(loName, lo, 'from '), box(hiName, hi, 'to ')),
    hint ? el('small', { class: 'hint' }, hint) : null,
    el('p', { class: 'field-error', 'aria-live': 'polite' }));
}

// Fields most runs leave alone, folded under a summary so that the first screen holds the problem, the method
// and Run. A fold opens by itself when a field in it gets an error or a value from the page's URL.
export function folded(summary, ...fields) {
  return el('details', { class: 'folded', dataset: { fold: summary } }, el('summary', {}, summary), fields.flat(Infinity));
}

export function actions() {
  return el('div', { class: 'actions' },
    el('button', { type: 'submit', class: 'primary', dataset: { role: 'run' } }, 'Run'),
    el('button', { type: 'button', dataset: { role: 'cancel' }, disabled: true, title: 'Cancel (Esc)',
      'aria-keyshortcuts': 'Escape' }, 'Cancel'),
    el('progress', { hidden: true, 'aria-label': 'progress' }),
    el('p', { class: 'form-error', role: 'alert' }));
}

// A table of checkboxes: one row per method (or integrator + method), one column per differential.
// Rows marked single (fixed point: no differential) get one box sending `${row}|exact`.
// Each box is labelled in full for screen readers; values are `${row}|${column}`.
// explained: the enums the rows and columns are made of, explained in a disclosure under the table.
export function choiceMatrix(name, legend, rows, columns, checked, describe, explained = ['method', 'differential']) {
  const box = (v, text) => el('input', { type: 'checkbox', name, value: v, checked: checked.includes(v), 'aria-label': text });
  const body = rows.map(({ key, text, single }) => el('tr', {},
    el('th', { scope: 'row' }, text),
    single
      ? el('td', { colspan: columns.length, class: 'center' },
        el('label', {}, box(`${key}|exact`, describe(key, null)), ' no differential'))
      : columns.map(([c]) => el('td', { class: 'center' }, box(`${key}|${c}`, describe(key, c))))));
  return el('fieldset', { class: 'field choices', dataset: { field: name } },
    el('legend', {}, legend),
    el('div', { class: 'table-wrap' }, el('table', {},
      el('thead', {}, el('tr', {}, el('th', {}, ''), columns.map(([, t]) => el('th', { scope: 'col' }, t)))),
      el('tbody', {}, body))),
    explainerList(explained),
    el('p', { class: 'field-error', 'aria-live': 'polite' }));
}
