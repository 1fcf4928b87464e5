// Compare panel: one problem solved by several method/differential pairs, one after the other (the server
// caps concurrent streams), with every residual curve on one chart and a results table.
import { ApiError, postJSON, stream } from '../shared/api.js';
import { residualChart, residualTimeChart } from '../shared/chart.js';
import { el } from '../shared/dom.js';
import { actions, choiceMatrix, folded } from '../shared/fields.js';
import { checkedValues, runner } from '../shared/form.js';
import { drawsBodies, runMotions } from '../shared/motion_player.js';
import { entries, entry } from '../shared/catalog.js';
import { DIFFERENTIALS, DIFFERENTIALS_SHORT, fmtExp, fmtRate, fmtSeconds, iterateText, label, mathText } from '../shared/labels.js';
import { limitFields, problemFields, readCommon } from '../shared/request.js';
import { sharePanel } from '../shared/share.js';
import { RATE_WORDS, statusBadge } from '../shared/summary.js';
import { REPEATS, median, spreadText, withinNoise } from '../shared/repeats.js';

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
    folded('More options: tolerance, iterations, seed', limitFields()),
    actions());
  const live = el('p', { class: 'live', role: 'status' }, 'Tick the methods to compare and press Run.');
  const chartBox = el('div', { class: 'chart', id: 'compare-chart' });
  const timeBox = el('div', { class: 'chart', id: 'compare-time-chart' });
  const timeCaption = el('figcaption', {}, 'Residual against solver CPU time, iteration by iteration');
  const tableBox = el('div', { class: 'table-wrap', id: 'compare-table' });
  const motions = runMotions('compare-motion', 'The iterates as bodies', { at: 'last',
    caption: 'The iterates y\u2080 \u2026 y\u2099 of the chosen run (drag to turn the view); the path of a body point is coloured by n.' });
  // The solves Run sends, one per ticked method and differential.
  function requestsOf() {
    const picks = checkedValues(form, 'runs').map((v) => v.split('|'));
    if (!picks.length) throw new ApiError('Tick at least one method.', { field: 'runs' });
    return picks.map(([method, differential]) => ({ path: '/api/v1/solve',
      body: { ...readCommon(form), method, differential, include_iterates: false } }));
  }
  let last = null;  // [{ label, request, result, trace }] of the last run
  const share = sharePanel(form, {
    requests: requestsOf,
    data: () => last && { name: 'compare-traces', columns: ['run', 'method', 'differential', ...TRACE_COLUMNS],
      rows: last.flatMap((r) => r.trace.map((t) => [r.label, r.request.method, r.request.differential,
        ...TRACE_COLUMNS.map((c) => t[c] ?? null)])),
      json: last },
  });
  root.append(form, el('div', { class: 'output' }, live,
    el('div', { class: 'chart-pair' },
      el('figure', {}, timeCaption, timeBox),
      el('figure', {}, el('figcaption', {}, 'Residual against iteration n'), chartBox)),
    el('p', { class: 'hint' }, 'Times are the solver\u2019s own CPU time (cpu_seconds of each trace record), not the '
      + 'HTTP round trip. \u201cTime to tol\u201d is the CPU time of the first iterate with \u2016f\u2016 \u2264 tol, on the trace scaled to its median. '
      + RATE_WORDS),
    tableBox, motions.element, share.element));
  const start = runner(form, live);

  form.addEventListener('submit', async (e) => {
    e.preventDefault();
    const picks = checkedValues(form, 'runs').map((v) => v.split('|'));
    const labels = picks.map(([m, d]) => runLabel(m, d));
    const columns = picks.map(() => []);
    const times = picks.map(() => [[], []]);
    const rows = [];
    const requests = [];
    const runs = [];
    tableBox.replaceChildren();
    motions.hide();
    last = null;
    share.refresh();
    timeCaption.textContent = 'Residual against solver CPU time, iteration by iteration (one run; the median follows)';
    await start(async (signal, progress) => {
      const sends = requestsOf();
      const chart = residualChart(chartBox, labels);
      const timeChart = residualTimeChart(timeBox, labels);
      const { tol } = readCommon(form);
      progress.max = picks.length;
      for (const [i, [method, differential]] of picks.entries()) {
        const request = sends[i].body;
        const trace = [];
        live.textContent = `Running ${labels[i]} (${i + 1} of ${picks.length})\u2026`;
        const result = await stream('/api/v1/solve', request, { signal, onRecord(rec) {
          if (rec.type !== 'iteration') return;
          trace.push(rec);
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
        runs.push({ label: labels[i], request, result, trace });
        tableBox.replaceChildren(resultsTable(rows));
      }
      last = runs;
      live.textContent = `Compared ${picks.length} runs.`;
      // One run's CPU time is noise at the microsecond scale: each run again REPEATS times, median and range.
      for (const [i, { request }] of runs.entries()) {
        live.textContent = `Timing ${labels[i]} again (${REPEATS} runs)\u2026`;
        const cpu = [];
        for (let k = 0; k < REPEATS; k += 1) cpu.push((await postJSON('/api/v1/solve', request, { signal })).cpu_seconds);
        cpu.sort((a, b) => a - b);
        runs[i].cpu_repeats = cpu;
        rows[i].push(cpu);
      }
      // The chart first drew each run's one noisy timing; now each trace's times are scaled so that it ends at its
      // run's median, and the time to tol read off the scaled trace: the chart and the table tell one story.
      const scaled = times.map(([xs, ys], i) => {
        const f = xs.length && xs.at(-1) > 0 ? median(runs[i].cpu_repeats) / xs.at(-1) : 1;
        return [xs.map((x) => x * f), ys];
      });
      timeChart.set(scaled);
      timeCaption.textContent = `Residual against solver CPU time, each run\u2019s iterates scaled to its median of ${REPEATS} runs`;
      for (const [i, row] of rows.entries()) row[2] = timeToTol(scaled[i], tol);
      tableBox.replaceChildren(resultsTable(rows), noiseNote(rows));
      live.textContent = `Compared ${picks.length} runs, each timed ${REPEATS} times more.`;
      // Each run's iterates as bodies, once the timings are done (drawing beside them would load the server they
      // time): the server re-runs the chosen solve to draw them.
      if (drawsBodies(requests[0])) await motions.show(requests.map((request, i) => ({ label: labels[i], request: { ...request, kind: 'solve' },
        describe: (k, n) => `${iterateText(n, columns[i][n])} (frame ${k})` })));
    });
    share.refresh();
  });
  return { share };
}

// Which runs' CPU times overlap (min..max of the repeats): their order is noise, not a finding.
function noiseNote(rows) {
  const timed = rows.filter((r) => r[3]);
  const pairs = [];
  for (let i = 0; i < timed.length; i += 1) {
    for (let j = i + 1; j < timed.length; j += 1) {
      const [a, b] = [timed[i][3], timed[j][3]];
      if (withinNoise(a, b)) pairs.push(`${timed[i][0]} and ${timed[j][0]}`);
    }
  }
  return el('p', { class: 'hint', id: 'compare-noise' }, pairs.length
    ? `Within the noise (their ranges of ${REPEATS} runs overlap): ${pairs.join('; ')}.`
    : `No two runs\u2019 ranges of ${REPEATS} CPU times overlap.`);
}

// The trace record's fields, in the order of the CSV's columns.
const TRACE_COLUMNS = ['iteration', 'residual', 'step', 'cpu_seconds', 'seconds'];

// CPU seconds of the first iterate whose residual is at most tol, or null when none is.
function timeToTol([cpu, residual], tol) {
  const k = residual.findIndex((r) => typeof r === 'number' && r <= tol);
  return k < 0 ? null : cpu[k];
}

function resultsTable(rows) {
  // The reason last: on a phone its long text pushes what follows out of view.
  const head = ['Method', 'Status', 'Iterations', 'Rate r', 'Final \u2016f\u2016', 'Time to tol (CPU)', 'Solver CPU time',
    `CPU time, median of ${REPEATS} (range)`, 'Why'];
  return el('table', {},
    el('thead', {}, el('tr', {}, head.map((h) => el('th', { scope: 'col' }, h)))),
    el('tbody', {}, rows.map(([name, r, ttol, cpu]) => el('tr', {},
      el('th', { scope: 'row' }, name), el('td', {}, statusBadge(r.status)),
      el('td', {}, String(r.iterations)), el('td', {}, fmtRate(r.rate)), el('td', {}, fmtExp(r.residual)),
      el('td', { 'data-col': 'time-to-tol' }, ttol === null ? 'not reached' : fmtSeconds(ttol)),
      el('td', { 'data-col': 'cpu-seconds' }, fmtSeconds(r.cpu_seconds)),
      el('td', { 'data-col': 'cpu-median' }, cpu ? spreadText(cpu) : '\u2026'),
      el('td', { class: 'why' }, mathText(r.reason))))));
}
