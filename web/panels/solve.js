// Solve panel: one solve, streamed iteration by iteration into a log-residual chart, then the result, the
// iterates as a motion of bodies (motion_player.js: Newton snapping in, the fixed point wandering) and the full
// trace as a table.
import { stream } from '../shared/api.js';
import { residualChart } from '../shared/chart.js';
import { el } from '../shared/dom.js';
import { actions, contractNumber, field, folded, select } from '../shared/fields.js';
import { runner, value } from '../shared/form.js';
import { CONTINUATION, DIFFERENTIALS, GLOBALIZATIONS, METHODS, fmtExp, fmtSeconds, iterateText } from '../shared/labels.js';
import { drawsBodies, motionPlayer } from '../shared/motion_player.js';
import { DEFAULTS, fill, limitFields, problemFields, readCommon } from '../shared/request.js';
import { sharePanel } from '../shared/share.js';
import { resultList } from '../shared/summary.js';

export function createSolvePanel(root) {
  const form = el('form', { class: 'controls', novalidate: true, 'aria-label': 'Solve request' },
    problemFields(),
    select('method', 'Method', METHODS, DEFAULTS.method),
    select('differential', 'Differential', DIFFERENTIALS, DEFAULTS.differential,
      'Ignored by the fixed-point method'),
    folded('More options: Newton variant, continuation, tolerance, start',
      select('globalization', 'Newton variant', GLOBALIZATIONS, 'none', 'Newton methods only'),
      select('continuation', 'Continuation in h', CONTINUATION, 'false', 'On: follows z\u2019s branch of roots from h = 0; path points stream'),
      contractNumber('SolveRequest', 'multistart', 'Multistart', { hint: 'Seeded starts tried when no root was found' }),
      limitFields(),
      field('y0', 'Start guess y\u2080 (JSON rows; empty: y\u2080 = z)', el('textarea', { name: 'y0', rows: 3,
        spellcheck: 'false', autocomplete: 'off' }), 'Filled when a basin map pixel is opened here')),
    actions());
  const live = el('p', { class: 'live', role: 'status' }, 'Press Run to solve y = z exp(h g(y)).');
  const chartBox = el('div', { class: 'chart', id: 'solve-chart' });
  const summary = el('div', { class: 'result', id: 'solve-result' });
  const motion = motionPlayer('solve-motion', { at: 'last',
    caption: 'The iterates y\u2080 \u2026 y\u2099 as bodies (drag to turn the view); the path of a body point is coloured by n.' });
  const motionNote = el('p', { class: 'hint', id: 'solve-motion-note', hidden: true });
  const table = el('details', { class: 'trace', hidden: true }, el('summary', {}, 'Trace table'), el('div', { class: 'table-wrap' }));

  const newChart = () => residualChart(chartBox, ['\u2016f(y\u2099)\u2016']);
  let chart = null; // none before the first run: the box shows a placeholder
  const start = runner(form, live);
  let last = null;  // { request, records, result } of the last run

  function requestOf() {
    const request = { ...readCommon(form), method: value(form, 'method'),
      differential: value(form, 'differential'), globalization: value(form, 'globalization'),
      continuation: value(form, 'continuation') === 'true', include_iterates: false };
    const multistart = value(form, 'multistart');
    if (multistart !== '') request.multistart = multistart;  // empty: the server's default
    const y0 = value(form, 'y0');
    if (y0) request.y0 = parseOr(y0);
    return request;
  }
  const share = sharePanel(form, {
    requests: () => [{ path: '/api/v1/solve', body: requestOf() }],
    data: () => last && { name: 'solve-trace', columns: TRACE_COLUMNS,
      rows: last.records.map((r) => TRACE_COLUMNS.map((c) => r[c] ?? null)),
      json: { request: last.request, result: last.result, trace: last.records } },
  });
  root.append(form, el('div', { class: 'output' }, live, chartBox, el('div', { class: 'result-row' }, summary, el('div', {}, motion.element, motionNote)), table,
    share.element));

  async function run() {
    const request = requestOf();
    const records = [];
    last = null;
    share.refresh();
    let queued = false;
    const draw = () => { queued = false; chart.set([records.map((r) => r.residual)]); };
    summary.replaceChildren();
    motion.hide();
    motionNote.hidden = true;
    table.hidden = true;
    chart = newChart(); // fresh axes, not the previous run's range
    live.textContent = 'Solving\u2026';
    await start(async (signal, progress) => {
      if (Number.isFinite(request.max_iterations)) progress.max = request.max_iterations;
      const result = await stream('/api/v1/solve', request, { signal, onRecord(rec) {
        if (rec.type === 'path_point') {
          live.textContent = `Continuation: path point at h = ${rec.stage_h.toPrecision(4)}`;
          return;
        }
        if (rec.type !== 'iteration') return;
        records.push(rec);
        progress.value = rec.iteration;
        live.textContent = `Iteration ${rec.iteration}: \u2016f\u2016 = ${fmtExp(rec.residual)}`;
        if (!queued) { queued = true; requestAnimationFrame(draw); }
      } });
      draw();
      last = { request, records, result };
      live.textContent = `Done: ${records.length} iterates streamed.`;
      summary.replaceChildren(resultList(result));
      table.querySelector('.table-wrap').replaceChildren(traceTable(records));
      table.hidden = false;
      // Every solve with bodies, whatever its method or status: the server re-runs it to draw its iterates.
      if (!drawsBodies(request)) return;
      try {
        await motion.load({ ...request, kind: 'solve' }, { signal,
          describe: (k, n) => `${iterateText(n, records[n]?.residual)} (frame ${k})` });
      } catch (e) {
        if (e.name === 'AbortError') throw e;
        motionNote.textContent = `No motion of the iterates: ${e.message}`;
        motionNote.hidden = false;
      }
    });
    share.refresh();
  }

  form.addEventListener('submit', (e) => { e.preventDefault(); run(); });
  return {
    share,
    // A request without y0 (a stability-map cell) starts at z again.
    open(request) {
      form.elements.namedItem('y0').value = '';
      fill(form, request);
      run();
    },
  };
}

// JSON text as a value; text that is not JSON goes to the server as it is, which names the field.
function parseOr(text) {
  try { return JSON.parse(text); } catch { return text; }
}

// The trace record's fields, in the order of the CSV's columns.
const TRACE_COLUMNS = ['iteration', 'residual', 'step', 'angle', 'distance_to_pi', 'orthogonality_error', 'seconds', 'cpu_seconds'];

function traceTable(records) {
  const head = ['n', '\u2016f(y\u2099)\u2016', 'step \u2016u\u2016', 'angle', '\u03c0 \u2212 angle', '\u2016y\u1d40y \u2212 I\u2016', 'time'];
  return el('table', {},
    el('thead', {}, el('tr', {}, head.map((h) => el('th', { scope: 'col' }, h)))),
    el('tbody', {}, records.map((r) => el('tr', {},
      el('td', {}, String(r.iteration)), el('td', {}, fmtExp(r.residual)), el('td', {}, fmtExp(r.step)),
      el('td', {}, r.angle?.toFixed(6) ?? '\u2014'), el('td', {}, fmtExp(r.distance_to_pi)),
      el('td', {}, fmtExp(r.orthogonality_error)), el('td', {}, fmtSeconds(r.seconds))))));
}
