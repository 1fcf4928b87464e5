// Speed vs accuracy panel: a work-precision chart (log CPU time against log global error), one series per
// ticked integrator/method/differential, and for a problem with invariants (rigid-body: energy; heavy-top: energy and
// vertical angular momentum, as the server's catalog lists them) each invariant's drift over time per choice.
import { ApiError, postJSON } from '../shared/api.js';
import { invariantChart, workPrecisionChart } from '../shared/chart.js';
import { el } from '../shared/dom.js';
import { actions, choiceMatrix, contractNumber, folded, number, range, select } from '../shared/fields.js';
import { checkedValues, runner, value, wholeRange } from '../shared/form.js';
import { runMotions } from '../shared/motion_player.js';
import { entries, entry } from '../shared/catalog.js';
import { DIFFERENTIALS, DIFFERENTIALS_SHORT, INTEGRATORS, PROBLEMS, fmtExp, fmtSeconds, label } from '../shared/labels.js';
import { programFields, problemOf } from '../shared/request.js';
import { sharePanel } from '../shared/share.js';
import { statusBadge, warningBadges } from '../shared/summary.js';
import { REPEATS, median, withinNoise } from '../shared/repeats.js';


const DEFAULT_TICKS = ['implicit-euler|newton-group|exact', 'implicit-euler|fixed-point|exact',
  'dirk-cg2|newton-group|exact', 'dirk-cg2|newton-algebra|dexpinv-1'];

function choiceLabel({ integrator, method, differential }) {
  if (entry('integrator', integrator).solves_stages === false) return label(INTEGRATORS, integrator);  // explicit: no method
  const m = entry('method', method);
  const d = m.uses_differential ? ` \u00b7 ${label(DIFFERENTIALS, differential)}` : '';
  return `${label(INTEGRATORS, integrator)} \u00b7 ${m.short}${d}`;
}

// The legend entry: the choice and its fitted order p (slope of log error vs log h), or "no order" (the fit's
// reason is in the note under the chart).
function seriesLabel(s) {
  const p = s.fitted_order;
  return `${choiceLabel(s.choice)}${p === null || p === undefined ? ' (no order)' : ` (p \u2248 ${p.toFixed(2)})`}`;
}

// Per series without an order, why: the server's fit_reason.
function fitText(series) {
  const none = series.filter((s) => s.fitted_order === null || s.fitted_order === undefined);
  if (!none.length) return 'Every order is fitted over points in the asymptotic regime; grey markers are left out of the fit.';
  return `Grey markers are left out of the fit (hover one for why). ${none.map((s) => `${choiceLabel(s.choice)}: `
    + `${s.fit_reason}`).join('; ')}.`;
}

const ROWS = entries('integrator').flatMap((i) => entries('method').map((m) => ({ key: `${i.value}|${m.value}`,
  text: `${i.short}, ${m.short}`, single: !m.uses_differential })));

function describe(row, differential) {
  const [integrator, method] = row.split('|');
  return choiceLabel({ integrator, method, differential });
}

export function createSpeedPanel(root) {
  const form = el('form', { class: 'controls', novalidate: true, 'aria-label': 'Work-precision request' },
    select('problem', 'Problem', PROBLEMS, 'rigid-body'),
    programFields(),
    range('h', 'log\u2082 h of the step sizes', ['k_lo', ''], ['k_hi', ''],
      'h = 2\u1d4f for each whole k; both empty: six steps from the problem\u2019s time scale'),
    folded('More options: N, t_end, invariants plot, tolerance, seed',
      contractNumber('WorkPrecisionRequest', 'n', 'Dimension N'),
      contractNumber('WorkPrecisionRequest', 't_end', 'End time t_end'),
      number('energy_h', 'Step size h of the invariants plot', '',
        'Problems with invariants: rigid-body, heavy-top; empty: the largest h fitted in the work-precision run'),
      contractNumber('WorkPrecisionRequest', 'tol', 'Tolerance'),
      contractNumber('WorkPrecisionRequest', 'max_iterations', 'Max iterations'),
      contractNumber('WorkPrecisionRequest', 'seed', 'Seed')),
    actions());
  form.insertBefore(choiceMatrix('choices', 'Integrator, solver and differential', ROWS, DIFFERENTIALS_SHORT, DEFAULT_TICKS,
    describe, ['integrator', 'method', 'differential']), form.querySelector('.field[data-field="h"]'));
  const live = el('p', { class: 'live', role: 'status' }, 'Tick the choices to compare and press Run.');
  const wpBox = el('div', { class: 'chart', id: 'work-precision-chart' });
  // One chart per invariant the catalog knows (energy-chart, vertical_momentum-chart), shown for the problems
  // that report it.
  const invariantBoxes = Object.fromEntries(entries('invariant').map((i) => [i.value,
    el('div', { class: 'chart', id: `${i.value}-chart` })]));
  const wpHover = el('p', { class: 'hint', id: 'work-precision-hover', 'aria-live': 'polite' });
  const noiseNote = el('p', { class: 'hint', id: 'work-precision-noise' });
  const fitNote = el('p', { class: 'hint', id: 'work-precision-fit' });
  // Per invariant: its chart and the sentence naming curves drawn over each other.
  const coincideNotes = Object.fromEntries(entries('invariant').map((i) => [i.value,
    el('p', { class: 'hint', id: `${i.value}-coincide` })]));
  const invariantFigs = Object.fromEntries(entries('invariant').map((i) => [i.value,
    el('section', { class: 'energy', hidden: true }, el('h3', {}, `${i.label}: error over time`),
      el('p', { class: 'hint' }, i.description), invariantBoxes[i.value], coincideNotes[i.value])]));
  const tableBox = el('div', { class: 'table-wrap', id: 'energy-table' });
  const trajectory = runMotions('trajectory-motion', 'The motion of the chosen run',
    { caption: 'The states y(t) of the chosen run as bodies (drag to turn the view); the path is coloured by t.' });
  // The invariants the request's problem reports (none for a program g).
  const invariantsOf = (common) => (common.g ? [] : entry('problem', common.problem).invariants ?? []);
  // The work-precision request, then for a problem with invariants one integration per choice (their plots).
  function requestsOf() {
    const choices = checkedValues(form, 'choices').map((v) => {
      const [integrator, method, differential] = v.split('|');
      return { integrator, method, differential };
    });
    if (!choices.length) throw new ApiError('Tick at least one choice.', { field: 'choices' });
    const common = { ...problemOf(form), n: value(form, 'n'), t_end: value(form, 't_end'),
      tol: value(form, 'tol'), max_iterations: value(form, 'max_iterations'), seed: value(form, 'seed') };
    // Both ends empty: the server's step sizes from the problem's time scale.
    const auto = value(form, 'k_lo') === '' && value(form, 'k_hi') === '';
    const h = auto ? undefined : wholeRange(form, 'k_lo', 'k_hi', 'k').reverse().map((k) => 2 ** k);
    // An empty box: the step the last run chose (energyStep), so that the shared curl commands repeat it.
    const energyH = value(form, 'energy_h') === '' ? energyStep : value(form, 'energy_h');
    const energy = !invariantsOf(common).length ? [] : choices.map((choice) => ({ path: '/api/v1/integrate',
      body: { ...common, ...choice, h: energyH } }));
    return [{ path: '/api/v1/work-precision', body: { ...common, choices, ...(h ? { h } : {}) } }, ...energy];
  }
  let last = null;  // { wp, runs } of the last run
  let energyStep;    // the invariants' runs' h when its box is empty: chosen from the last work-precision run
  const share = sharePanel(form, {
    requests: requestsOf,
    data: () => last && { name: 'work-precision', columns: POINT_COLUMNS,
      rows: last.wp.series.flatMap((s) => s.points.map((p) => [s.choice.integrator, s.choice.method, s.choice.differential,
        ...POINT_COLUMNS.slice(3).map((k) => p[k] ?? null)])),
      json: { work_precision: last.wp, energy_runs: last.runs.map(({ request, result }) => ({ request, result })) } },
  });
  root.append(form, el('div', { class: 'output' }, live, el('h3', {}, 'Work precision'),
    el('p', { class: 'hint' }, 'One line per choice through its step sizes h, each marker labelled with its h; '
      + `x is the global error at t_end, y the solver\u2019s own CPU time (cpu_seconds), the median of ${REPEATS} runs `
      + '(hover a marker for its range), as in the server\u2019s work-precision PNG. p is the fitted order (slope of log error against log h). Click a legend entry to hide '
      + 'or show its line.'),
    wpBox, wpHover, fitNote, noiseNote, share.element, ...Object.values(invariantFigs), tableBox, trajectory.element));
  const start = runner(form, live);

  form.addEventListener('submit', async (e) => {
    e.preventDefault();
    Object.values(invariantFigs).forEach((fig) => { fig.hidden = true; });
    noiseNote.textContent = '';
    fitNote.textContent = '';
    tableBox.replaceChildren();
    trajectory.hide();
    last = null;
    share.refresh();
    await start(async (signal, progress) => {
      energyStep = undefined;  // chosen again from this run's fit
      const [wpRequest, ...energyRequests] = requestsOf();
      const { choices } = wpRequest.body;
      const sizes = wpRequest.body.h ? `${wpRequest.body.h.length} step sizes` : 'the problem\u2019s step sizes';
      live.textContent = `Timing ${choices.length} choices at ${sizes}\u2026`;
      // The same request REPEATS times: each point's CPU time is the median of its runs, with their range.
      const repeats = [];
      for (let k = 0; k < REPEATS; k += 1) {
        repeats.push(await postJSON(wpRequest.path, wpRequest.body, { signal }));
        live.textContent = `Timing ${choices.length} choices at ${sizes}: run ${k + 1} of ${REPEATS} done\u2026`;
      }
      const wp = medianOf(repeats);
      const timed = `work precision ${REPEATS} times in ${fmtSeconds(repeats.reduce((a, r) => a + r.seconds, 0))}`;
      workPrecisionChart(wpBox, wp.series.map((s) => ({ label: seriesLabel(s), points: s.points })), wpHover);
      noiseNote.textContent = noiseText(wp.series);
      fitNote.textContent = fitText(wp.series);
      // The invariants' runs at the largest h any order is fitted from (else the smallest h run).
      const fitted = wp.series.flatMap((s) => s.points.filter((p) => p.in_fit).map((p) => p.h));
      energyStep = fitted.length ? Math.max(...fitted) : Math.min(...wp.series.flatMap((s) => s.points.map((p) => p.h)));
      energyRequests.forEach((r) => { r.body.h ??= energyStep; });
      last = { wp, runs: [] };
      if (!energyRequests.length) {
        live.textContent = `Done: ${timed}.`;
        return;
      }
      progress.max = energyRequests.length;
      const runs = [];
      for (const [i, { path, body: request }] of energyRequests.entries()) {
        const choice = choices[i];
        live.textContent = `Integrating ${choiceLabel(choice)} (${i + 1} of ${choices.length})\u2026`;
        const result = await postJSON(path, request, { signal }).catch((err) => {
          if (err.field === 'h') err.field = 'energy_h';
          throw err;
        });
        runs.push({ choice, request, result });
        progress.value = i + 1;
      }
      last.runs = runs;
      const invariants = invariantsOf(energyRequests[0].body);
      for (const name of invariants) {
        coincideNotes[name].textContent = drawInvariant(invariantBoxes[name], runs, name);
        invariantFigs[name].hidden = false;
      }
      tableBox.replaceChildren(integrateTable(runs, invariants));
      await trajectory.show(runs.map(({ choice, request, result }) => trajectoryRun(choiceLabel(choice), result,
        { ...request, kind: 'integrate' }, invariants)));
      live.textContent = `Done: ${timed}, ${runs.length} invariant runs.`;
    });
    share.refresh();
  });
  return { share };
}

// One CSV row per point of the work-precision diagram: its choice, h, and what it cost and reached.
const POINT_COLUMNS = ['integrator', 'method', 'differential', 'h', 'global_error', 'cpu_seconds', 'iterations'];

// One run for the motion player: its render request and, per frame at time t, the step of the integration that
// ended at t (the same steps: the render re-runs the request) with its invariants' errors.
function trajectoryRun(label, result, request, invariants) {
  return { label, request, describe(frame, t) {
    const k = t === 0 ? 0 : result.steps.findIndex((s) => s.t === t) + 1;
    const when = `t = ${Number(t.toPrecision(6))} (frame ${frame})`;
    if (k === 0 && t !== 0) return when;
    const errors = invariants.map((name) => {
      const value = k ? result.steps[k - 1][name] : result[`initial_${name}`];
      const short = entry('invariant', name).short;
      return `${short} \u2212 ${short}(0) = ${fmtExp(value - result[`initial_${name}`])}`;
    });
    return `step ${k}, ${when}: ${errors.join(', ')}`;
  } };
}

// The first repeat with each point's cpu_seconds replaced by the median of the repeats, and their ascending
// list as cpu_runs (errors and iterations do not depend on the run).
function medianOf(repeats) {
  const [first] = repeats;
  return { ...first, series: first.series.map((s, i) => ({ ...s, points: s.points.map((p, j) => {
    const runs = repeats.map((r) => r.series[i].points[j].cpu_seconds).sort((a, b) => a - b);
    return { ...p, cpu_seconds: median(runs), cpu_runs: runs };
  }) })) };
}

// Which choices' CPU times are within the noise of each other (their ranges overlap) at the same h.
function noiseText(series) {
  const pairs = [];
  for (let i = 0; i < series.length; i += 1) {
    for (let j = i + 1; j < series.length; j += 1) {
      const at = series[i].points.filter((p) => {
        const q = series[j].points.find((x) => x.h === p.h);
        return q?.cpu_runs && p.cpu_runs && withinNoise(p.cpu_runs, q.cpu_runs);
      });
      if (at.length) pairs.push(`${choiceLabel(series[i].choice)} and ${choiceLabel(series[j].choice)} at ` +
        `${at.length} of ${series[i].points.length} step sizes`);
    }
  }
  return pairs.length
    ? `Within the noise (their ranges of ${REPEATS} CPU times overlap, so their order there is not a finding): ${pairs.join('; ')}.`
    : `No two choices\u2019 ranges of ${REPEATS} CPU times overlap at the same h.`;
}

// An invariant relative to its value at t = 0, so that drift is visible whatever its size; runs that stopped
// early are padded with gaps. Curves that coincide (one hides the other) say so in the legend; the returned
// sentence names them.
function drawInvariant(box, runs, name) {
  const longest = runs.reduce((a, r) => (r.result.steps.length > a.length ? r.result.steps : a), []);
  const times = longest.map((s) => s.t);
  const curves = runs.map(({ choice, result }) => {
    const i0 = result[`initial_${name}`];
    const scale = i0 ? Math.abs(i0) : 1;
    return { label: choiceLabel(choice),
      values: times.map((_, k) => (k < result.steps.length ? (result.steps[k][name] - i0) / scale : null)) };
  });
  const same = curves.map((c, i) => curves.findIndex((d, j) => j < i && coincides(c.values, d.values)));
  invariantChart(box, times, curves.map((c, i) => (same[i] < 0 ? c
    : { ...c, label: `${c.label} (same curve as ${curves[same[i]].label})` })), entry('invariant', name).short);
  const hidden = same.flatMap((j, i) => (j < 0 ? [] : [`${curves[i].label} coincides with ${curves[j].label}`]));
  return hidden.length ? `${hidden.join('; ')}: drawn over each other (relative difference below ${COINCIDE.toExponential(0)}).` : '';
}

// Two curves coincide when every value differs by at most this, relative: one line covers the other.
const COINCIDE = 1e-6;
function coincides(a, b) {
  return a.every((v, k) => (v === null || b[k] === null ? v === b[k]
    : Math.abs(v - b[k]) <= COINCIDE * Math.max(Math.abs(v), Math.abs(b[k]))));
}

// A global error within 10x of the reference's estimated error bounds the run's error, it does not measure it.
function globalError(r) {
  if (!r.global_error_at_reference) return fmtExp(r.global_error);
  return el('span', { title: `within 10\u00d7 of the reference's estimated error ${fmtExp(r.reference_error)}` },
    `\u2264 ${fmtExp(r.global_error)} (reference)`);
}

function integrateTable(runs, invariants) {
  const head = ['Choice', 'Status', 'Global error', ...invariants.map((name) => `${entry('invariant', name).label} drift`),
    '\u2016y\u1d40y \u2212 I\u2016', 'Solver CPU time'];
  return el('table', {},
    el('thead', {}, el('tr', {}, head.map((h) => el('th', { scope: 'col' }, h)))),
    el('tbody', {}, runs.map(({ choice, result: r }) => el('tr', {},
      el('th', { scope: 'row' }, choiceLabel(choice)), el('td', {}, statusBadge(r.status), ...warningBadges(r.warnings)),
      el('td', {}, globalError(r)), ...invariants.map((name) => el('td', {}, fmtExp(r[`${name}_drift`]))),
      el('td', {}, fmtExp(r.orthogonality_error)), el('td', {}, fmtSeconds(r.cpu_seconds))))));
}
