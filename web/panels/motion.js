// Motion panel: a built-in mechanical problem integrated and shown as it moves. The server draws the bodies
// (render/motion: solids from their inertia, the path of a telling point coloured by time) as an animated WebP;
// the page decodes its frames (ImageDecoder) so that Play/Pause and the time slider step through them, and a drag
// on the picture turns the camera (the server draws the new view on release). Beside it, the state against time
// (the body angular velocity) and each invariant's drift, from the integrate route's frames and steps.
import { postBlob, postJSON } from '../shared/api.js';
import { invariantChart, stateChart } from '../shared/chart.js';
import { schemas } from '../shared/catalog.js';
import { el } from '../shared/dom.js';
import { actions, contractNumber, field, select } from '../shared/fields.js';
import { runner, value } from '../shared/form.js';
import { INTEGRATORS, PROBLEMS } from '../shared/labels.js';
import { sharePanel } from '../shared/share.js';

const MECHANICS = ['heavy-top', 'rigid-body', 'stiff-body', 'chain'];
const SIZE = 512;
// The charts' states: the API's cap on frames. The heavy top's w1, w3 turn with its 150 rad/s spin (a period of
// about 0.04 s): the animation's 100 frames over t = 2 would alias them into a zigzag.
const CHART_FRAMES = 1000;

// The state's angular velocity per frame: the heavy top's and the stiff body's w in their SO(3) x R^3 matrix
// [[R, 0], [0, [[I, w], [0, 1]]]]; the free rigid body's w = I^-1 y^T m, from its parameters (or their defaults).
function angularVelocity(problem, request, y) {
  if (problem === 'heavy-top' || problem === 'stiff-body') return [y[3][6], y[4][6], y[5][6]];
  if (problem !== 'rigid-body') return null;
  const defaults = schemas.RigidBody?.properties ?? {};
  const m = request.rigid_body?.momentum ?? defaults.momentum?.default ?? [0.6, 0.8, 0.5];
  const inertia = request.rigid_body?.inertia ?? defaults.inertia?.default ?? [1, 2, 3];
  return [0, 1, 2].map((k) => (y[0][k] * m[0] + y[1][k] * m[1] + y[2][k] * m[2]) / inertia[k]);
}

const INVARIANTS = [['energy', 'energy'], ['vertical_momentum', 'vertical momentum'], ['axial_spin', 'axial spin']];

export function createMotionPanel(root) {
  const form = el('form', { class: 'controls', novalidate: true, 'aria-label': 'Motion request' },
    select('problem', 'Problem', PROBLEMS.filter(([v]) => MECHANICS.includes(v)), 'heavy-top'),
    select('integrator', 'Integrator', INTEGRATORS, 'rkmk-gauss2'),
    contractNumber('IntegrateRequest', 't_end', 'End time t_end', { value: 2 }),
    contractNumber('IntegrateRequest', 'n', 'Bodies (chain)', { value: 3, hint: 'The chain\u2019s links; other problems have one body' }),
    contractNumber('RenderMotionRequest', 'frame_ms', 'Milliseconds per frame', { value: 50 }),
    actions());
  const live = el('p', { class: 'live', role: 'status' }, 'Press Run to see the motion.');
  const canvas = el('canvas', { id: 'motion-canvas', width: SIZE, height: SIZE, tabindex: 0,
    'aria-label': 'The motion; drag to turn the view' });
  const play = el('button', { type: 'button', id: 'motion-play', disabled: true }, 'Play');
  const slider = el('input', { type: 'range', id: 'motion-slider', min: 0, max: 0, step: 1, value: 0, disabled: true,
    'aria-label': 'Time' });
  const readout = el('output', { id: 'motion-readout', for: 'motion-slider', class: 'frame-readout' });
  const note = el('figcaption', {}, 'Drag the picture to turn the view; the server draws it again on release.');
  const figure = el('figure', { class: 'frames motion', id: 'motion-figure', hidden: true },
    el('div', { class: 'frame-slider' }, play, slider), readout, canvas, note);
  const stateBox = el('div', { class: 'chart', id: 'motion-state' });
  const driftBox = el('div', { class: 'chart', id: 'motion-drift' });
  const charts = el('div', { class: 'result-row', hidden: true, id: 'motion-charts' },
    el('figure', {}, el('figcaption', {}, 'Body angular velocity \u03c9(t)'), stateBox),
    el('figure', {}, el('figcaption', {}, 'Invariants\u2019 drift |I(t) \u2212 I(0)| / scale'), driftBox));
  const start = runner(form, live);
  let last = null;  // { request, integration }
  const view = { azimuth_deg: 35, elevation_deg: 20 };
  let frames = [];  // ImageBitmaps of the animation, or none (the <img> fallback plays it)
  let timer = null;

  function requestOf() {
    const problem = value(form, 'problem');
    const request = { problem, integrator: value(form, 'integrator'), t_end: value(form, 't_end'), frames: 100 };
    if (problem === 'chain') request.n = value(form, 'n');
    return request;
  }
  const share = sharePanel(form, {
    requests: () => [{ path: '/api/v1/render/motion', body: { ...requestOf(), ...view } },
      { path: '/api/v1/integrate', body: { ...requestOf(), frames: CHART_FRAMES } }],
    data: () => last && stateTable(last),
  });
  root.append(form, el('div', { class: 'output' }, live, figure, charts, share.element));

  function show(k) {
    slider.value = String(k);
    // The frame's time is drawn in the picture: the server picks the frames evenly along its own steps.
    const words = `frame ${k} of ${frames.length - 1}`;
    readout.textContent = words;
    slider.setAttribute('aria-valuetext', words);
    figure.dataset.frame = String(k);
    if (frames[k]) canvas.getContext('2d').drawImage(frames[k], 0, 0, canvas.width, canvas.height);
  }
  function pause() {
    clearInterval(timer);
    timer = null;
    play.textContent = 'Play';
    figure.dataset.playing = 'false';
  }
  play.addEventListener('click', () => {
    if (timer) return pause();
    play.textContent = 'Pause';
    figure.dataset.playing = 'true';
    timer = setInterval(() => show((Number(slider.value) + 1) % frames.length), value(form, 'frame_ms') || 50);
  });
  slider.addEventListener('input', () => { pause(); show(Number(slider.value)); });

  // Decodes every frame of the animation; without ImageDecoder (older browsers) the picture plays by itself.
  async function load(signal) {
    const blob = await postBlob('/api/v1/render/motion', { ...requestOf(), ...view, width: SIZE, height: SIZE,
      frame_ms: value(form, 'frame_ms') }, 'image/webp', { signal });
    pause();
    frames = [];
    if (typeof ImageDecoder === 'undefined') {
      const img = el('img', { src: URL.createObjectURL(blob), alt: 'The motion, animated', width: SIZE, height: SIZE });
      canvas.replaceWith(img);
      return;
    }
    const decoder = new ImageDecoder({ data: blob.stream(), type: 'image/webp' });
    // A streamed file's frame count grows as its bytes arrive: it is final once the whole file is read.
    await decoder.completed;
    const count = decoder.tracks.selectedTrack.frameCount;
    for (let i = 0; i < count; ++i) {
      const { image } = await decoder.decode({ frameIndex: i });
      frames.push(await createImageBitmap(image));
      image.close();  // a decoded VideoFrame holds its memory until closed, not until collected
    }
    decoder.close();
    slider.max = String(frames.length - 1);
    slider.disabled = false;
    play.disabled = false;
    figure.dataset.frames = String(frames.length);
  }

  // Drag: 0.4 degrees per pixel, the elevation kept within +-89; the new view is drawn on release.
  let drag = null;
  canvas.addEventListener('pointerdown', (e) => { drag = { x: e.clientX, y: e.clientY, ...view }; canvas.setPointerCapture(e.pointerId); });
  canvas.addEventListener('pointermove', (e) => {
    if (!drag) return;
    view.azimuth_deg = Math.round((drag.azimuth_deg - 0.4 * (e.clientX - drag.x)) % 360);
    view.elevation_deg = Math.round(Math.max(-89, Math.min(89, drag.elevation_deg + 0.4 * (e.clientY - drag.y))));
    note.textContent = `View: azimuth ${view.azimuth_deg}\u00b0, elevation ${view.elevation_deg}\u00b0 (release to draw)`;
  });
  canvas.addEventListener('pointerup', async () => {
    if (!drag) return;
    const moved = drag.azimuth_deg !== view.azimuth_deg || drag.elevation_deg !== view.elevation_deg;
    drag = null;
    if (!moved || !last) return;
    const k = Number(slider.value);
    await start(async (signal) => { await load(signal); show(Math.min(k, frames.length - 1)); });
    note.textContent = `View: azimuth ${view.azimuth_deg}\u00b0, elevation ${view.elevation_deg}\u00b0`;
    figure.dataset.azimuth = String(view.azimuth_deg);
  });

  function drawCharts(request, integration) {
    const w = integration.frames.map((y) => angularVelocity(request.problem, request, y));
    if (w.every((v) => v)) {
      stateChart(stateBox, integration.frame_times, [0, 1, 2].map((k) => ({ label: `\u03c9${'\u2081\u2082\u2083'[k]}`,
        values: w.map((v) => v[k]) })), 'body angular velocity \u03c9 [rad/s]');
    } else stateBox.replaceChildren(el('p', { class: 'hint' }, 'This problem\u2019s state has no angular velocity to plot.'));
    const stepTimes = integration.steps.map((s) => s.t);
    const runs = INVARIANTS.filter(([key]) => integration.steps.some((s) => s[key] !== null && s[key] !== undefined))
      .map(([key, name]) => {
        const first = integration[`initial_${key}`] ?? integration.steps[0][key];
        const scale = integration[`${key}_scale`] || Math.abs(first) || 1;
        return { label: name, values: integration.steps.map((s) => (s[key] - first) / scale) };
      });
    if (runs.length) invariantChart(driftBox, stepTimes, runs, 'drift', '|I(t) \u2212 I(0)| / scale');
    else driftBox.replaceChildren(el('p', { class: 'hint' }, 'This problem reports no invariants.'));
  }

  async function run() {
    const request = requestOf();
    last = null;
    share.refresh();
    delete figure.dataset.frames;  // until this run's animation is decoded
    live.textContent = 'Integrating and drawing\u2026';
    const startedAt = performance.now();
    await start(async (signal) => {
      const [integration] = await Promise.all([postJSON('/api/v1/integrate', { ...request, frames: CHART_FRAMES }, { signal }), load(signal)]);
      last = { request, integration };
      figure.hidden = false;
      charts.hidden = false;
      show(0);
      drawCharts(request, integration);
      live.textContent = `${integration.status}: ${integration.steps.length} steps, ${frames.length} frames, `
        + `${((performance.now() - startedAt) / 1000).toFixed(2)} s from Run to picture.`;
      share.refresh();
    });
  }
  form.addEventListener('submit', (e) => { e.preventDefault(); run(); });
  return { share, run };
}

function stateTable({ request, integration }) {
  const w = integration.frames.map((y) => angularVelocity(request.problem, request, y));
  const columns = ['t', 'omega_1', 'omega_2', 'omega_3'];
  return { name: 'motion-state', columns,
    rows: integration.frame_times.map((t, i) => [t, ...(w[i] ?? [null, null, null])]),
    json: { request, result: integration } };
}
