// Speed vs accuracy panel: a work-precision chart (log CPU time against log global error), one series per
// ticked integrator/method/differential, and for the rigid body the energy over time of each choice.
import { ApiError, postJSON } from '../shared/api.js';
import { energyChart, workPrecisionChart } from '../shared/chart.js';
import { el } from '../shared/dom.js';
import { actions, choiceMatrix, contractNumber, number, range, select } from '../shared/fields.js';
import { checkedValues, runner, value, wholeRange } from '../shared/form.js';
import { runFrames } from '../shared/frame_stepper.js';
import { entries, entry } from '../shared/catalog.js';
import { DIFFERENTIALS, DIFFERENTIALS_SHORT, INTEGRATORS, PROBLEMS, fmtExp, fmtSeconds, label } from '../shared/labels.js';
import { statusBadge } from '../shared/summary.js';

// Frames of the trajectory: every step up to the API's cap of 1000, then evenly spaced (the server says which
// steps in frame_steps).
const FRAMES = 1000;

const DEFAULT_TICKS = ['implicit-euler|newton-group|exact', 'implicit-euler|fixed-point|exact',
  'dirk-cg2|newton-group|exact', 'dirk-cg2|newton-algebra|dexpinv-1'];

function choiceLabel({ integrator, method, differential }) {
  const m = entry('method', method);
  const d = m.uses_differential ? ` \u00b7 ${label(DIFFERENTIALS, differential)}` : '';
  return `${label(INTEGRATORS, integrator)} \u00b7 ${m.short}${d}`;
}

// The legend entry: the choice and its fitted order p (slope of log error vs log h).
function seriesLabel(s) {
  const p = s.fitted_order;
  return `${choiceLabel(s.choice)}${p === null || p === undefined ? '' : ` (p \u2248 ${p.toFixed(2)})`}`;
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
    contractNumber('WorkPrecisionRequest', 'n', 'Dimension N'),
    contractNumber('WorkPrecisionRequest', 't_end', 'End time t_end'),
    range('h', 'log\u2082 h of the step sizes', ['k_lo', -7], ['k_hi', -2], 'h = 2\u1d4f for each whole k'),
    number('energy_h', 'Step size h of the energy plot', 0.0625, 'Rigid body only'),
    contractNumber('WorkPrecisionRequest', 'tol', 'Tolerance'),
    contractNumber('WorkPrecisionRequest', 'max_iterations', 'Max iterations'),
    contractNumber('WorkPrecisionRequest', 'seed', 'Seed'),
    actions());
  form.insertBefore(choiceMatrix('choices', 'Integrator, solver and differential', ROWS, DIFFERENTIALS_SHORT, DEFAULT_TICKS,
    describe, ['integrator', 'method', 'differential']), form.querySelector('.field[data-field="h"]'));
  const live = el('p', { class: 'live', role: 'status' }, 'Tick the choices to compare and press Run.');
  const wpBox = el('div', { class: 'chart', id: 'work-precision-chart' });
  const energyBox = el('div', { class: 'chart', id: 'energy-chart' });
  const wpHover = el('p', { class: 'hint', id: 'work-precision-hover', 'aria-live': 'polite' });
  const energyFig = el('section', { class: 'energy', hidden: true },
    el('h3', {}, 'Rigid body: energy error over time'), energyBox);
  const tableBox = el('div', { class: 'table-wrap', id: 'energy-table' });
  const trajectory = runFrames('trajectory-frames', 'Rigid body: the trajectory as rotation frames', 'Time step',
    'States y(t\u2080) \u2026 y(t\u2096) of the chosen run as rotated frames (server-rendered PNG): y(t\u2096) bold, '
    + 'earlier ones fainter, y(0) dashed.');
  root.append(form, el('div', { class: 'output' }, live, el('h3', {}, 'Work precision'),
    el('p', { class: 'hint' }, 'One line per choice through its step sizes h (largest h at the left end); '
      + 'x is the solver\u2019s own CPU time (cpu_seconds), y the global error at t_end. p is the fitted order '
      + '(slope of log error against log h). Click a legend entry to hide or show its line.'),
    wpBox, wpHover, energyFig, tableBox, trajectory.element));
  const start = runner(form, live);

  form.addEventListener('submit', async (e) => {
    e.preventDefault();
    const choices = checkedValues(form, 'choices').map((v) => {
      const [integrator, method, differential] = v.split('|');
      return { integrator, method, differential };
    });
    const common = { problem: value(form, 'problem'), n: value(form, 'n'), t_end: value(form, 't_end'),
      tol: value(form, 'tol'), max_iterations: value(form, 'max_iterations'), seed: value(form, 'seed') };
    energyFig.hidden = true;
    tableBox.replaceChildren();
    trajectory.hide();
    await start(async (signal, progress) => {
      if (!choices.length) throw new ApiError('Tick at least one choice.', { field: 'choices' });
      const h = wholeRange(form, 'k_lo', 'k_hi', 'k').reverse().map((k) => 2 ** k);
      live.textContent = `Timing ${choices.length} choices at ${h.length} step sizes\u2026`;
      const wp = await postJSON('/api/v1/work-precision', { ...common, choices, h }, { signal });
      workPrecisionChart(wpBox, wp.series.map((s) => ({ label: seriesLabel(s), points: s.points })), wpHover);
      live.textContent = `Work precision done in ${fmtSeconds(wp.seconds)}.`;
      if (common.problem !== 'rigid-body') return;
      progress.max = choices.length;
      const runs = [];
      for (const [i, choice] of choices.entries()) {
        live.textContent = `Integrating ${choiceLabel(choice)} (${i + 1} of ${choices.length})\u2026`;
        const request = { ...common, ...choice, h: value(form, 'energy_h'), frames: FRAMES };
        const result = await postJSON('/api/v1/integrate', request, { signal }).catch((err) => {
          if (err.field === 'h') err.field = 'energy_h';
          throw err;
        });
        runs.push({ choice, request, result });
        progress.value = i + 1;
      }
      drawEnergy(energyBox, runs);
      energyFig.hidden = false;
      tableBox.replaceChildren(integrateTable(runs));
      trajectory.show(runs.map(({ choice, request, result }) => trajectoryRun(choiceLabel(choice), result,
        { ...request, kind: 'integrate' })));
      live.textContent = `Done: work precision in ${fmtSeconds(wp.seconds)}, ${runs.length} energy runs.`;
    });
  });
}

// One run for the trajectory's stepper: the render request (the same frames as the integration, which ran with
// FRAMES) and per slider position the step and time the server reports for that frame (frame_steps,
// frame_times) and its energy error.
function trajectoryRun(label, result, request) {
  const steps = result.frame_steps;
  return { label, request, count: steps.length, describe(i) {
    const k = steps[i];
    const energy = k ? result.steps[k - 1].energy : result.initial_energy;
    return `step ${k}, t = ${Number(result.frame_times[i].toPrecision(6))}: E \u2212 E(0) = ${fmtExp(energy - result.initial_energy)}`;
  } };
}

// Energy relative to E(0), so that drift is visible whatever E's size; runs that stopped
// early are padded with gaps.
function drawEnergy(box, runs) {
  const longest = runs.reduce((a, r) => (r.result.steps.length > a.length ? r.result.steps : a), []);
  const times = longest.map((s) => s.t);
  energyChart(box, times, runs.map(({ choice, result }) => {
    const e0 = result.initial_energy;
    return { label: choiceLabel(choice),
      values: times.map((_, k) => (k < result.steps.length && e0 ? (result.steps[k].energy - e0) / e0 : null)) };
  }));
}

function integrateTable(runs) {
  const head = ['Choice', 'Status', 'Global error', 'Energy drift', '\u2016y\u1d40y \u2212 I\u2016', 'Solver CPU time'];
  return el('table', {},
    el('thead', {}, el('tr', {}, head.map((h) => el('th', { scope: 'col' }, h)))),
    el('tbody', {}, runs.map(({ choice, result: r }) => el('tr', {},
      el('th', { scope: 'row' }, choiceLabel(choice)), el('td', {}, statusBadge(r.status)),
      el('td', {}, fmtExp(r.global_error)), el('td', {}, fmtExp(r.energy_drift)),
      el('td', {}, fmtExp(r.orthogonality_error)), el('td', {}, fmtSeconds(r.cpu_seconds))))));
}
