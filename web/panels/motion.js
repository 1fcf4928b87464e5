// Motion panel: a built-in mechanical problem integrated and shown as it moves. The server draws the bodies
// (render/motion: solids from their inertia, the path of a telling point coloured by time), played by
// motion_player.js. Beside it, the state against time (the body angular velocity) and each invariant's drift,
// from the integrate route's frames and steps.
import { postJSON } from '../shared/api.js';
import { chartMessage, invariantChart, stateChart } from '../shared/chart.js';
import { schemas } from '../shared/catalog.js';
import { el } from '../shared/dom.js';
import { actions, contractNumber, field, select } from '../shared/fields.js';
import { runner, value } from '../shared/form.js';
import { INTEGRATORS, PROBLEMS } from '../shared/labels.js';
import { motionPlayer } from '../shared/motion_player.js';
import { groupOf, programFields, problemOf } from '../shared/request.js';
import { sharePanel } from '../shared/share.js';
import { warningBadges } from '../shared/summary.js';

const MECHANICS = ['heavy-top', 'rigid-body', 'stiff-body', 'chain'];
// The charts' states: the API's cap on frames. The heavy top's w1, w3 turn with its 150 rad/s spin (a period of
// about 0.04 s): the animation's 100 frames over t = 2 would alias them into a zigzag.
const CHART_FRAMES = 1000;

// The state's angular velocity per frame: on SO(3) x R^3 (the heavy top, the stiff body, or a program on SOxR) the
// w of its matrix [[R, 0], [0, [[I, w], [0, 1]]]]; the free rigid body's w = I^-1 y^T m, from its parameters (or
// their defaults).
function angularVelocity(request, y) {
  if (groupOf(request) === 'SOxR') return [y[3][6], y[4][6], y[5][6]];
  if (request.g || request.problem !== 'rigid-body') return null;
  const defaults = schemas.RigidBody?.properties ?? {};
  const m = request.rigid_body?.momentum ?? defaults.momentum?.default ?? [0.6, 0.8, 0.5];
  const inertia = request.rigid_body?.inertia ?? defaults.inertia?.default ?? [1, 2, 3];
  return [0, 1, 2].map((k) => (y[0][k] * m[0] + y[1][k] * m[1] + y[2][k] * m[2]) / inertia[k]);
}

const INVARIANTS = [['energy', 'energy'], ['vertical_momentum', 'vertical momentum'], ['axial_spin', 'axial spin']];

// What the state chart can plot: the body angular velocity (the built-in mechanics), and every entry y(i,j) of the
// state matrix that moves (MATLAB's 1-based indices, as a program names them). { key, label, series: [{ label,
// values }] } per choice.
function stateComponents(request, integration) {
  const choices = [];
  const w = integration.frames.map((y) => angularVelocity(request, y));
  if (w.length && w.every((v) => v)) {
    choices.push({ key: 'omega', label: '\u03c9 (body angular velocity)',
      series: [0, 1, 2].map((k) => ({ label: `\u03c9${'\u2081\u2082\u2083'[k]}`, column: `omega_${k + 1}`,
        values: w.map((v) => v[k]) })) });
  }
  const [first] = integration.frames;
  for (const [i, row] of (first ?? []).entries()) {
    for (const j of row.keys()) {
      const values = integration.frames.map((y) => y[i][j]);
      const range = Math.max(...values) - Math.min(...values);
      if (!(range > 1e-12 * Math.max(1, ...values.map(Math.abs)))) continue;  // a constant entry: nothing to plot
      const label = `y(${i + 1},${j + 1})`;
      choices.push({ key: label, label, range, series: [{ label, column: `y_${i + 1}_${j + 1}`, values }] });
    }
  }
  return choices;
}

// The axis label of the chosen components.
function stateAxis(chosen) {
  const omega = chosen.some((c) => c.key === 'omega');
  if (omega && chosen.length === 1) return 'body angular velocity \u03c9 [rad/s]';
  return omega ? '\u03c9 [rad/s] and entries of y' : 'entries y(i,j) of the state';
}

export function createMotionPanel(root) {
  const form = el('form', { class: 'controls', novalidate: true, 'aria-label': 'Motion request' },
    select('problem', 'Problem', PROBLEMS.filter(([v]) => MECHANICS.includes(v)), 'heavy-top'),
    programFields(),
    select('integrator', 'Integrator', INTEGRATORS, 'rkmk-gauss2'),
    contractNumber('IntegrateRequest', 't_end', 'End time t_end', { value: 2 }),
    contractNumber('IntegrateRequest', 'n', 'N (the chain\u2019s links, your g\u2019s N)', { value: 3,
      hint: 'The chain\u2019s links, or N of your g\u2019s group; the other problems have one body' }),
    contractNumber('RenderMotionRequest', 'frame_ms', 'Milliseconds per frame', { value: 50 }),
    actions());
  const live = el('p', { class: 'live', role: 'status' }, 'Press Run to see the motion.');
  const player = motionPlayer('motion-figure', {
    caption: 'Drag the picture to turn the view; the server draws it again on release.' });
  const stateBox = el('div', { class: 'chart', id: 'motion-state' });
  const picker = el('select', { id: 'motion-components', multiple: true, size: 5 });
  let components = [];  // stateComponents of the last run
  const driftBox = el('div', { class: 'chart', id: 'motion-drift' });
  const exactNote = el('p', { class: 'hint', id: 'motion-exact', hidden: true });
  const charts = el('div', { class: 'chart-pair', hidden: true, id: 'motion-charts' },
    el('figure', {}, el('figcaption', {}, 'The state against time'),
      el('div', { class: 'field' }, el('label', { for: picker.id }, 'Plot (ctrl-click for several)'), picker), stateBox),
    el('figure', {}, el('figcaption', {}, 'Invariants\u2019 drift |I(t) \u2212 I(0)| / scale'), driftBox, exactNote));
  const start = runner(form, live);
  let last = null;  // { request, integration }

  function requestOf() {
    // No frames: the motion route's own default (100) for the animation.
    const request = { ...problemOf(form), integrator: value(form, 'integrator'), t_end: value(form, 't_end') };
    if (request.g || request.problem === 'chain') request.n = value(form, 'n');
    return request;
  }
  const share = sharePanel(form, {
    requests: () => [{ path: '/api/v1/render/motion', body: requestOf() },
      { path: '/api/v1/integrate', body: { ...requestOf(), frames: CHART_FRAMES } }],
    data: () => last && stateTable(last, chosen()),
  });
  root.append(form, el('div', { class: 'output' }, live, player.element, charts, share.element));

  const chosen = () => components.filter((c) => [...picker.selectedOptions].some((o) => o.value === c.key));
  function drawState() {
    const picked = chosen();
    if (!picked.length) {
      chartMessage(stateBox, components.length ? 'Choose what to plot.' : 'Nothing in the state moves.');
      return;
    }
    stateChart(stateBox, last.integration.frame_times, picked.flatMap((c) => c.series), stateAxis(picked));
  }
  picker.addEventListener('change', () => { drawState(); share.refresh(); });

  function drawCharts(request, integration) {
    components = stateComponents(request, integration);
    // Shown at first: omega, else the three entries that move the most.
    const shown = components.some((c) => c.key === 'omega') ? ['omega']
      : components.slice().sort((a, b) => b.range - a.range).slice(0, 3).map((c) => c.key);
    picker.replaceChildren(...components.map((c) => el('option', { value: c.key, selected: shown.includes(c.key) }, c.label)));
    drawState();
    const stepTimes = integration.steps.map((s) => s.t);
    const runs = INVARIANTS.filter(([key]) => integration.steps.some((s) => s[key] !== null && s[key] !== undefined))
      .map(([key, name]) => {
        const first = integration[`initial_${key}`] ?? integration.steps[0][key];
        const scale = integration[`${key}_scale`] || Math.abs(first) || 1;
        return { label: name, values: integration.steps.map((s) => (s[key] - first) / scale) };
      });
    // An invariant the method keeps exactly (the symmetric top's axial spin) has no point on a log axis: said,
    // not drawn as a missing line.
    const drifting = runs.filter((r) => r.values.some((v) => v !== 0));
    const exact = runs.filter((r) => !drifting.includes(r)).map((r) => r.label);
    exactNote.textContent = exact.length ? `Kept exactly (drift 0 at every step): ${exact.join(', ')}.` : '';
    exactNote.hidden = !exact.length;
    if (drifting.length) invariantChart(driftBox, stepTimes, drifting, 'drift', '|I(t) \u2212 I(0)| / scale');
    else chartMessage(driftBox, runs.length ? 'No invariant drifts.' : 'This problem reports no invariants.');
  }

  async function run() {
    const request = requestOf();
    last = null;
    share.refresh();
    live.textContent = 'Integrating and drawing\u2026';
    const startedAt = performance.now();
    await start(async (signal) => {
      const [integration] = await Promise.all([postJSON('/api/v1/integrate', { ...request, frames: CHART_FRAMES }, { signal }),
        player.load(request, { signal, frameMs: value(form, 'frame_ms') || undefined })]);
      last = { request, integration };
      charts.hidden = false;
      drawCharts(request, integration);
      // A converged run is not yet a right one: its warnings (an error beyond the solution's scale, a drifting
      // invariant, an enlarged step) stand beside the status, as in the Speed panel.
      live.replaceChildren(`${integration.status}: ${integration.steps.length} steps, ${player.frameCount} frames, `
        + `${((performance.now() - startedAt) / 1000).toFixed(2)} s from Run to picture. `,
      ...warningBadges(integration.warnings));
      share.refresh();
    });
  }
  form.addEventListener('submit', (e) => { e.preventDefault(); run(); });
  return { share, run };
}

// The CSV: t and the components plotted (y(i,j) as y_i_j).
function stateTable({ request, integration }, chosen) {
  const series = chosen.flatMap((c) => c.series);
  return { name: 'motion-state', columns: ['t', ...series.map((s) => s.column)],
    rows: integration.frame_times.map((t, i) => [t, ...series.map((s) => s.values[i])]),
    json: { request, result: integration } };
}
