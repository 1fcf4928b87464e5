// Share and export, the same on every panel: the panel's settings in the page's URL (?name=value#panel, only
// what differs from the form's defaults), the requests Run sends as curl commands or as JSON, and the data the
// charts show as CSV and JSON files.
import { el } from './dom.js';
import { showError } from './form.js';

// Every named control's values: a text box or select one value, a tick group the ticked values (maybe none).
function snapshot(form) {
  const out = new Map();
  for (const c of form.elements) {
    if (!c.name || c.type === 'submit' || c.type === 'button' || c.tagName === 'FIELDSET') continue;
    const values = out.get(c.name) ?? [];
    if (c.type !== 'checkbox') values.push(c.value);
    else if (c.checked) values.push(c.value);
    out.set(c.name, values);
  }
  return out;
}

const same = (a, b) => a.length === b.length && a.every((v, i) => v === b[i]);

// The settings that differ from defaults as URL parameters; a tick group with nothing ticked is one empty value.
function paramsOf(form, defaults) {
  const q = new URLSearchParams();
  for (const [name, values] of snapshot(form)) {
    if (same(values, defaults.get(name) ?? [])) continue;
    if (!values.length) q.append(name, '');
    for (const v of values) q.append(name, v);
  }
  return q;
}

// Sets the form from URL parameters; names the form does not have are ignored. Fires input and change so that
// linked widgets (the h slider, the "What is this?" texts) follow.
function applyParams(form, q) {
  for (const name of new Set(q.keys())) {
    const values = q.getAll(name);
    for (const c of form.querySelectorAll(`[name="${CSS.escape(name)}"]`)) {
      if (c.type === 'checkbox') c.checked = values.includes(c.value);
      else c.value = values[0];
      const fold = c.closest('details.folded');
      if (fold) fold.open = true;
      c.dispatchEvent(new Event('input', { bubbles: true }));
      c.dispatchEvent(new Event('change', { bubbles: true }));
    }
  }
}

// A shell word: single quotes, each ' inside written as '\''.
const quote = (s) => `'${s.replace(/'/g, "'\\''")}'`;

export function curlOf({ path, body }) {
  return `curl -s ${location.origin}${path} -H 'Content-Type: application/json' -d ${quote(JSON.stringify(body))}`;
}

// One request: its body (what `lienewton <command>` reads on stdin too); several: each with its route.
export function requestJson(requests) {
  return JSON.stringify(requests.length === 1 ? requests[0].body : requests, null, 2);
}

// RFC 4180 CSV: a field with a comma, quote or line break is quoted; null is empty.
export function toCsv(columns, rows) {
  const cell = (v) => {
    const s = v === null || v === undefined ? '' : String(v);
    return /[",\n]/.test(s) ? `"${s.replace(/"/g, '""')}"` : s;
  };
  return [columns, ...rows].map((r) => r.map(cell).join(',')).join('\n') + '\n';
}

export function download(name, type, text) {
  const url = URL.createObjectURL(new Blob([text], { type }));
  const a = el('a', { href: url, download: name, hidden: true });
  document.body.append(a);
  a.click();
  a.remove();
  setTimeout(() => URL.revokeObjectURL(url), 1000);
}

// The share bar of a panel. requests(): the [{path, body}] Run sends for the form as it is (throws an ApiError
// naming the field when the form cannot make one); data(): { name, columns, rows, json } of the last run, or
// null before one. The panel calls refresh() after each run.
export function sharePanel(form, { requests, data }) {
  const defaults = snapshot(form);
  const shown = el('pre', { class: 'share-text', hidden: true, tabindex: 0 });
  const note = el('p', { class: 'hint share-note', 'aria-live': 'polite' });
  const copy = async (kind, text) => {
    shown.textContent = text;
    shown.hidden = false;
    shown.dataset.kind = kind;
    try {
      await navigator.clipboard.writeText(text);
      note.textContent = 'Copied to the clipboard:';
    } catch {
      note.textContent = 'Select and copy:';  // no clipboard outside https and localhost
    }
  };
  const fromForm = (kind, format) => () => {
    let list;
    try { list = requests(); } catch (err) { showError(form, err); return; }
    copy(kind, format(list));
  };
  const save = (ext) => () => {
    const d = data();
    if (!d) return;
    if (ext === 'csv') download(`${d.name}.csv`, 'text/csv', toCsv(d.columns, d.rows));
    else download(`${d.name}.json`, 'application/json', `${JSON.stringify(d.json, null, 1)}\n`);
  };
  const button = (text, role, onclick, disabled = false) => el('button', { type: 'button', dataset: { share: role }, onclick, disabled }, text);
  const csv = button('Download CSV', 'csv', save('csv'), true);
  const json = button('Download JSON', 'json', save('json'), true);
  const element = el('div', { class: 'share', role: 'group', 'aria-label': 'Share and export' },
    el('div', { class: 'share-buttons' },
      button('Copy as curl', 'curl', fromForm('curl', (list) => list.map(curlOf).join('\n'))),
      button('Copy request JSON', 'request', fromForm('request', requestJson)), csv, json),
    note, shown);
  return {
    element,
    params: () => paramsOf(form, defaults),
    apply: (q) => applyParams(form, q),
    refresh() {
      const ready = Boolean(data());
      csv.disabled = !ready;
      json.disabled = !ready;
    },
  };
}
