// The parameters of a user's g(y) as a small table: a name and a value in MATLAB notation per row ("0.5",
// "[1 0 0; 0 2 0; 0 0 3]", "[0.6; 0.8; 0.5]"). The request's JSON object lives in one hidden field named
// parameters, which the page's URL keeps (shared/share.js) and the request reads (shared/request.js); the
// table writes it as it is edited and is drawn again from it when it is set from outside.
import { el } from './dom.js';

// A value in MATLAB notation as the request's JSON: a number, or an array of rows. Text that is not a
// matrix of finite numbers with rows of equal length comes back as it was typed, so that the server names the
// parameter and says what it expects.
export function parseMatrix(text) {
  const raw = text.trim();
  const bracketed = raw.startsWith('[') && raw.endsWith(']');
  const body = bracketed ? raw.slice(1, -1) : raw;
  const rows = body.split(/[;\n]/).map((r) => r.trim()).filter(Boolean)
    .map((r) => r.split(/[\s,]+/).map((x) => (x === '' ? NaN : Number(x))));
  const valid = rows.length > 0 && rows.every((r) => r.length === rows[0].length && r.every(Number.isFinite));
  if (!valid) return raw;
  return !bracketed && rows.length === 1 && rows[0].length === 1 ? rows[0][0] : rows;
}

// The request's value in MATLAB notation: a number as it is, a row as [a b c], rows joined by "; ".
export function matrixText(value) {
  if (typeof value === 'number') return String(value);
  if (!Array.isArray(value)) return String(value);
  const rows = value.every(Array.isArray) ? value : [value];
  return `[${rows.map((r) => r.join(' ')).join('; ')}]`;
}

export function parameterTable() {
  const hidden = el('input', { type: 'hidden', name: 'parameters', value: '' });
  const body = el('tbody');
  const status = el('small', { class: 'hint' });
  let writing = false;  // the table is setting the hidden field: do not draw it again under the cursor

  const write = () => {
    const entries = [...body.rows].map((tr) => tr.querySelectorAll('input'))
      .filter(([name]) => name.value.trim() !== '')
      .map(([name, value]) => [name.value.trim(), parseMatrix(value.value)]);
    hidden.value = entries.length ? JSON.stringify(Object.fromEntries(entries)) : '';
    writing = true;
    hidden.dispatchEvent(new Event('input', { bubbles: true }));
    hidden.dispatchEvent(new Event('change', { bubbles: true }));
    writing = false;
  };

  const row = (name = '', value = '') => {
    const nameInput = el('input', { type: 'text', value: name, autocomplete: 'off', spellcheck: 'false',
      class: 'code', 'aria-label': 'Parameter name' });
    const valueInput = el('input', { type: 'text', value, autocomplete: 'off', spellcheck: 'false', class: 'code',
      'aria-label': 'Parameter value (MATLAB notation)' });
    const remove = el('button', { type: 'button', class: 'remove', 'aria-label': 'Remove this parameter' }, '\u00d7');
    const tr = el('tr', {}, el('td', {}, nameInput), el('td', {}, valueInput), el('td', {}, remove));
    remove.addEventListener('click', () => {
      tr.remove();
      write();
    });
    for (const input of [nameInput, valueInput]) input.addEventListener('input', write);
    return tr;
  };

  // Drawn from the hidden field when something else sets it: a shared URL, "Edit the problem as a program",
  // a run opened from another panel.
  const draw = () => {
    if (writing) return;
    status.textContent = '';
    const text = hidden.value.trim();
    let object = {};
    if (text) {
      try {
        object = JSON.parse(text);
      } catch {
        status.textContent = `Could not read the parameters ${text}: they are sent as written.`;
      }
    }
    const entries = object && typeof object === 'object' && !Array.isArray(object) ? Object.entries(object) : [];
    body.replaceChildren(...entries.map(([name, value]) => row(name, matrixText(value))));
  };
  hidden.addEventListener('input', draw);
  hidden.addEventListener('change', draw);

  const add = el('button', { type: 'button' }, 'Add a parameter');
  add.addEventListener('click', () => {
    const tr = row();
    body.append(tr);
    tr.querySelector('input').focus();
  });
  const table = el('table', { class: 'parameters' },
    el('thead', {}, el('tr', {}, el('th', { scope: 'col' }, 'Name'), el('th', { scope: 'col' }, 'Value'),
      el('td', {}))),
    body);
  return el('fieldset', { class: 'field', dataset: { field: 'parameters' } },
    el('legend', {}, 'Parameters of g'),
    hidden, table, add,
    el('small', { class: 'hint' }, 'Named numbers and matrices the program reads, in MATLAB notation: J = [1 0 0; 0 2 0; 0 0 3]'),
    status,
    el('p', { class: 'field-error', 'aria-live': 'polite' }));
}
