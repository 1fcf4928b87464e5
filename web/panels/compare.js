// Compare panel: one problem solved by several method/differential pairs, one after the other (the server
// caps concurrent streams), with every residual curve on one chart and a results table.
import { ApiError, stream } from '../shared/api.js';
import { residualChart } from '../shared/chart.js';
import { el } from '../shared/dom.js';
import { actions, choiceMatrix } from '../shared/fields.js';
import { checkedValues, runner } from '../shared/form.js';
import { entries, entry } from '../shared/catalog.js';
import { DIFFERENTIALS, DIFFERENTIALS_SHORT, fmtExp, fmtRate, fmtSeconds, label } from '../shared/labels.js';
import { limitFields, problemFields, readCommon } from '../shared/request.js';
import { statusBadge } from '../shared/summary.js';

// One row per method; a method that forms no differential gets a single tick.
const ROWS = entries('method').map((m) => ({ key: m.value, text: m.short, single: !m.uses_differential }));

function runLabel(method, differential) {
  const m = entry('method', method);
  return m.uses_differential ? `${m.short} \u00b7 ${label(DIFFERENTIALS, differential)}` : m.short;
}

export function createComparePanel(root) {
  const form = el('form', { class: 'controls', novalidate: true, 'aria-label': 'Compare request' },
    problemFields(),
    choiceMatrix('runs', 'Methods and differentials', ROWS, DIFFERENTIALS_SHORT,
      ['fixed-point|exact', 'newton-group|exact', 'newton-algebra|exact', 'newton-group|finite-difference'], runLabel),
    limitFields(),
    actions());
  const live = el('p', { class: 'live', role: 'status' }, 'Tick the methods to compare and press Run.');
  const chartBox = el('div', { class: 'chart', id: 'compare-chart' });
  const tableBox = el('div', { class: 'table-wrap', id: 'compare-table' });
  root.append(form, el('div', { class: 'output' }, live, chartBox, tableBox));
  const start = runner(form, live);

  form.addEventListener('submit', async (e) => {
    e.preventDefault();
    const picks = checkedValues(form, 'runs').map((v) => v.split('|'));
    const labels = picks.map(([m, d]) => runLabel(m, d));
    const columns = picks.map(() => []);
    const rows = [];
    tableBox.replaceChildren();
    await start(async (signal, progress) => {
      if (!picks.length) throw new ApiError('Tick at least one method.', { field: 'runs' });
      const chart = residualChart(chartBox, labels);
      progress.max = picks.length;
      for (const [i, [method, differential]] of picks.entries()) {
        const request = { ...readCommon(form), method, differential, include_iterates: false };
        live.textContent = `Running ${labels[i]} (${i + 1} of ${picks.length})\u2026`;
        const result = await stream('/api/v1/solve', request, { signal, onRecord(rec) {
          if (rec.type !== 'iteration') return;
          columns[i].push(rec.residual);
          chart.set(columns);
        } });
        chart.set(columns);
        progress.value = i + 1;
        rows.push([labels[i], result]);
        tableBox.replaceChildren(resultsTable(rows));
      }
      live.textContent = `Compared ${picks.length} runs.`;
    });
  });
}

function resultsTable(rows) {
  const head = ['Method', 'Status', 'Why', 'Iterations', 'Rate r', 'Final \u2016f\u2016', 'Time'];
  return el('table', {},
    el('thead', {}, el('tr', {}, head.map((h) => el('th', { scope: 'col' }, h)))),
    el('tbody', {}, rows.map(([name, r]) => el('tr', {},
      el('th', { scope: 'row' }, name), el('td', {}, statusBadge(r.status)), el('td', { class: 'why' }, r.reason ?? ''),
      el('td', {}, String(r.iterations)), el('td', {}, fmtRate(r.rate)), el('td', {}, fmtExp(r.residual)),
      el('td', {}, fmtSeconds(r.seconds))))));
}
