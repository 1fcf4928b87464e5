// Compare panel: one problem solved by several method/differential pairs, one after the other (the server
// caps concurrent streams), with every residual curve on one chart and a results table.
import { ApiError, stream } from '../shared/api.js';
import { residualChart, residualTimeChart } from '../shared/chart.js';
import { el } from '../shared/dom.js';
import { actions, choiceMatrix } from '../shared/fields.js';
import { checkedValues, runner } from '../shared/form.js';
import { runFrames } from '../shared/frame_stepper.js';
import { entries, entry } from '../shared/catalog.js';
import { DIFFERENTIALS, DIFFERENTIALS_SHORT, fmtExp, fmtRate, fmtSeconds, iterateText, label, mathText } from '../shared/labels.js';
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
  const timeBox = el('div', { class: 'chart', id: 'compare-time-chart' });
  const tableBox = el('div', { class: 'table-wrap', id: 'compare-table' });
  const frames = runFrames('compare-frames', 'Rotation frames of the iterates (N = 3)', 'Iterate n',
    'Iterates y\u2080 \u2026 y\u2099 of the chosen run as rotated frames (server-rendered PNG): y\u2099 bold, '
    + 'earlier ones fainter, z dashed.');
  root.append(form, el('div', { class: 'output' }, live,
    el('div', { class: 'chart-pair' },
      el('figure', {}, el('figcaption', {}, 'Residual against solver CPU time (speed vs accuracy)'), timeBox),
      el('figure', {}, el('figcaption', {}, 'Residual against iteration n'), chartBox)),
    el('p', { class: 'hint' }, 'Times are the solver\u2019s own CPU time (cpu_seconds of each trace record), not the '
      + 'HTTP round trip. \u201cTime to tol\u201d is the CPU time of the first iterate with \u2016f\u2016 \u2264 tol.'),
    tableBox, frames.element));
  const start = runner(form, live);

  form.addEventListener('submit', async (e) => {
    e.preventDefault();
    const picks = checkedValues(form, 'runs').map((v) => v.split('|'));
    const labels = picks.map(([m, d]) => runLabel(m, d));
    const columns = picks.map(() => []);
    const times = picks.map(() => [[], []]);
    const rows = [];
    const requests = [];
    tableBox.replaceChildren();
    frames.hide();
    await start(async (signal, progress) => {
      if (!picks.length) throw new ApiError('Tick at least one method.', { field: 'runs' });
      const chart = residualChart(chartBox, labels);
      const timeChart = residualTimeChart(timeBox, labels);
      const { tol } = readCommon(form);
      progress.max = picks.length;
      for (const [i, [method, differential]] of picks.entries()) {
        const request = { ...readCommon(form), method, differential, include_iterates: false };
        live.textContent = `Running ${labels[i]} (${i + 1} of ${picks.length})\u2026`;
        const result = await stream('/api/v1/solve', request, { signal, onRecord(rec) {
          if (rec.type !== 'iteration') return;
          columns[i].push(rec.residual);
          times[i][0].push(rec.cpu_seconds);
          times[i][1].push(rec.residual);
          chart.set(columns);
          timeChart.set(times);
        } });
        chart.set(columns);
        timeChart.set(times);
        progress.value = i + 1;
        rows.push([labels[i], result, timeToTol(times[i], tol)]);
        requests.push(request);
        tableBox.replaceChildren(resultsTable(rows));
      }
      live.textContent = `Compared ${picks.length} runs.`;
      // Every N = 3 run's iterates as frames: the server re-runs the chosen solve to draw iterates 0..n.
      if (requests[0].n === 3) {
        frames.show(requests.map((request, i) => ({ label: labels[i], request, count: columns[i].length,
          describe: (n) => iterateText(n, columns[i][n]) })));
      }
    });
  });
}

// CPU seconds of the first iterate whose residual is at most tol, or null when none is.
function timeToTol([cpu, residual], tol) {
  const k = residual.findIndex((r) => typeof r === 'number' && r <= tol);
  return k < 0 ? null : cpu[k];
}

function resultsTable(rows) {
  // The reason last: on a phone its long text pushes what follows out of view.
  const head = ['Method', 'Status', 'Iterations', 'Rate r', 'Final \u2016f\u2016', 'Time to tol (CPU)', 'Solver CPU time',
    'Why'];
  return el('table', {},
    el('thead', {}, el('tr', {}, head.map((h) => el('th', { scope: 'col' }, h)))),
    el('tbody', {}, rows.map(([name, r, ttol]) => el('tr', {},
      el('th', { scope: 'row' }, name), el('td', {}, statusBadge(r.status)),
      el('td', {}, String(r.iterations)), el('td', {}, fmtRate(r.rate)), el('td', {}, fmtExp(r.residual)),
      el('td', { 'data-col': 'time-to-tol' }, ttol === null ? 'not reached' : fmtSeconds(ttol)),
      el('td', { 'data-col': 'cpu-seconds' }, fmtSeconds(r.cpu_seconds)), el('td', { class: 'why' }, mathText(r.reason))))));
}
