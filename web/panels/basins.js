// Basin map panel: where each method converges from. The starts y0 = z exp(a B1 + b B2) cover a square of
// (a, b); the map streams in row by row (NDJSON) into one canvas per method, each pixel in its root's hue
// shaded by iterations (light = few) or in its failure class' colour, as the server's PNG draws it. Hover a
// pixel for its numbers; click it (or Enter) to open that start as a solve, with y0 filled in.
import { postImage, postJSON, postSvg, stream } from '../shared/api.js';
import { catalog } from '../shared/catalog.js';
import { el } from '../shared/dom.js';
import { imageWidth } from '../shared/image_width.js';
import { actions, checkboxes, contractNumber, folded, select, spec } from '../shared/fields.js';
import { checkedValues, runner, value } from '../shared/form.js';
import { DIFFERENTIALS, METHODS, STATUSES, fmtExp, label } from '../shared/labels.js';
import { DEFAULTS, fieldValues, problemFields, problemOf } from '../shared/request.js';
import { download, sharePanel } from '../shared/share.js';
import { statusBadge } from '../shared/summary.js';
import { SWEEP_SECONDS, duration, paceText, planBadge, planText, prober, tooLongText } from '../shared/plan.js';

const MIN_PANEL = 200;  // pixels per method's panel in the server PNG, with room for its title
const MAX_SIZE = spec('BasinRequest', 'size').maximum;
// The largest size this server's output cap allows for k methods (size^2 x k pixels, each a few numbers).
const { max_values: MAX_VALUES, basin_pixel_values: PIXEL_VALUES } = catalog.output_limits;
const maxSize = (k) => Math.min(MAX_SIZE, Math.floor(Math.sqrt(MAX_VALUES / (PIXEL_VALUES * k))));

// The side of the map the plan's probe solves.
const PROBE_SIZE = 32;

const ROOTS = catalog.colors.basin_roots;
const DARKEST = catalog.colors.basin_darkest;

export function createBasinsPanel(root, { openSolve }) {
  const form = el('form', { class: 'controls', novalidate: true, 'aria-label': 'Basin map request' },
    problemFields({ ...DEFAULTS, h: 4 }),
    checkboxes('methods', 'Methods', METHODS, METHODS.map(([m]) => m), ['method']),
    select('differential', 'Differential', DIFFERENTIALS, 'exact'),
    contractNumber('BasinRequest', 'size', 'Pixels per side', { value: 96, hint: 'The grid is size \u00d7 size starts' }),
    folded('More options: square, tolerance, seed',
      contractNumber('BasinRequest', 'r', 'Half-width r of the square',
        { value: Number(spec('BasinRequest', 'r').default.toFixed(6)), hint: 'a, b in [\u2212r, r]; default \u03c0' }),
      contractNumber('BasinRequest', 'tol', 'Tolerance on \u2016f(y)\u2016'),
      contractNumber('BasinRequest', 'max_iterations', 'Max iterations'),
      contractNumber('BasinRequest', 'seed', 'Seed of z')),
    actions());
  const live = el('p', { class: 'live', role: 'status' },
    'Press Run to map from which starts y\u2080 = z exp(a B\u2081 + b B\u2082) each method converges.');
  const maps = el('div', { class: 'maps basin-maps', id: 'basin-maps' });
  const legend = el('div', { class: 'legend', id: 'basin-legend' });
  const details = el('aside', { class: 'cell-details', id: 'basin-details', 'aria-live': 'polite' },
    el('p', { class: 'hint' }, 'Hover or tap a pixel to see where its start went; click to open it in Solve.'));
  const image = el('figure', { class: 'heatmap', hidden: true },
    el('div', { class: 'scroll-x' }, el('img', { id: 'basin-img', alt: 'Server-rendered basin map, one panel per method' })),
    el('figcaption', {}, 'Server-rendered basin map (PNG): a to the right, b upward, one panel per method. ',
      el('button', { type: 'button', dataset: { share: 'svg' }, onclick: () => postSvg('/api/v1/render/basins', last.request)
        .then((text) => download('basin-map.svg', 'image/svg+xml', text))
        .catch((err) => { live.textContent = `Failed: ${err.message}`; }) }, 'Download SVG')));
  let last = null; // { request, rows, roots, result, panels }
  const requestOf = () => ({ ...problemOf(form), n: value(form, 'n'), h: value(form, 'h'),
    methods: checkedValues(form, 'methods'), differential: value(form, 'differential'), size: value(form, 'size'),
    r: value(form, 'r'), tol: value(form, 'tol'), max_iterations: value(form, 'max_iterations'),
    seed: value(form, 'seed') });
  const share = sharePanel(form, {
    requests: () => [{ path: '/api/v1/basins', body: requestOf() }],
    data: () => last?.result && { name: 'basin-map', columns: PIXEL_COLUMNS, rows: pixelRows(last),
      json: { request: last.request, grid: { a: last.axis, z: last.z, b1: last.b1, b2: last.b2 }, rows: last.rows,
        roots: last.result.roots, methods: last.result.methods } },
  });
  // The key right under the canvases (above them on a phone), not after the pixel's card.
  const output = el('div', { class: 'output' }, live,
    el('div', { class: 'map-area' }, el('div', { class: 'map-column' }, maps, legend), details),
    share.element, el('details', { class: 'view', id: 'basins-png' },
      el('summary', {}, 'As the server\u2019s PNG (for a slide or a paper)'), image));
  root.append(form, output);
  const start = runner(form, live);

  // The plan, before Run: a PROBE_SIZE map of the same square, methods and problem; its time per start, times
  // size^2 starts, is the estimate (cost is spread over the square, so a coarse map samples it fairly). The
  // size hint says what this server allows for the ticked methods: its output cap and its time limit.
  const sizeHint = form.querySelector('.field[data-field="size"] .hint');
  const probe = prober();
  const badge = planBadge(form);
  let planned = null;  // { key, perStart } or { key, timedOut }
  let planTimer = null;
  async function plan() {
    if (form.getAttribute('aria-busy') === 'true' || root.closest('[hidden]')) return;
    const request = requestOf();
    const k = Math.max(1, request.methods.length);
    const cap = maxSize(k);
    const hint = `The grid is size \u00d7 size starts; at most ${cap} with ${k} method${k > 1 ? 's' : ''} (the server\u2019s output cap)`;
    sizeHint.textContent = hint;
    badge.clear();
    if (!request.methods.length || !Number.isInteger(request.size) || request.size < 1) return;
    const { size, ...rest } = request;
    const key = JSON.stringify(rest);
    if (planned?.key !== key) {
      const sample = { ...rest, size: Math.min(size, PROBE_SIZE) };
      const answer = await probe((signal) => postJSON('/api/v1/basins', sample, { signal })).catch(() => null);
      if (!answer) return;
      planned = answer.timedOut ? { key, timedOut: true, byServer: answer.byServer, probeSize: sample.size }
        : { key, perStart: answer.seconds / (sample.size * sample.size), probeSize: sample.size };
    }
    const starts = size * size * k;
    const probeWords = `${planned.probeSize} \u00d7 ${planned.probeSize} probe`;
    if (planned.timedOut) {
      live.textContent = tooLongText({ count: starts, unit: 'starts', probe: probeWords, byServer: planned.byServer });
      badge.say({ count: starts, unit: 'starts', seconds: null });
      return;
    }
    const seconds = planned.perStart * size * size;
    // The largest size that fits in the server's time limit at the probe's pace (and its output cap).
    const inTime = Math.min(cap, Math.floor(Math.sqrt(SWEEP_SECONDS / Math.max(planned.perStart, 1e-9))));
    sizeHint.textContent = `${hint}; at ${size}: ${duration(seconds)}` +
      (inTime < cap ? `; at most about ${inTime} in the server\u2019s ${SWEEP_SECONDS} s limit` : '');
    live.textContent = `${planText({ count: starts, unit: 'starts', seconds, probe: probeWords })} Press Run.`;
    live.dataset.estimate = String(seconds);
    badge.say({ count: starts, unit: 'starts', seconds });
    Object.assign(planned, { seconds, size });
  }
  const replan = () => {
    clearTimeout(planTimer);
    planTimer = setTimeout(plan, 300);
  };
  form.addEventListener('input', replan);
  form.addEventListener('change', replan);
  new IntersectionObserver((seen) => { if (seen.some((x) => x.isIntersecting)) replan(); }).observe(form);
  let imageUrl = null;

  function pixelColor(px, lo, hi) {
    if (px.status !== 'converged') return STATUSES[px.status]?.color ?? '#777';
    const [r, g, b] = parseRgb(ROOTS[px.root % ROOTS.length]);
    const t = hi > lo ? Math.min(1, Math.max(0, (px.iterations - lo) / (hi - lo))) : 0;
    const k = 1 - DARKEST * t;
    return `rgb(${Math.round(r * k)},${Math.round(g * k)},${Math.round(b * k)})`;
  }

  // Paints one row of every panel; rows are drawn bottom-up (b grows upward).
  function paintRow(row, lo, hi) {
    const size = last.request.size;
    last.panels.forEach((panel, m) => {
      const ctx = panel.canvas.getContext('2d');
      const pixels = pixelsOf(row, m);
      for (let c = 0; c < size; c += 1) {
        ctx.fillStyle = pixelColor(pixels[c], lo, hi);
        ctx.fillRect(c, size - 1 - row.row, 1, 1);
      }
    });
  }

  const pixelsOf = (row, m) => {
    const p = row.methods[m];
    return p.status.map((status, c) => ({ status, root: p.root[c], iterations: p.iterations[c] }));
  };

  function iterationRange() {
    let lo = Infinity;
    let hi = 0;
    for (const row of last.rows) for (const p of row.methods) p.status.forEach((s, c) => {
      if (s !== 'converged') return;
      lo = Math.min(lo, p.iterations[c]);
      hi = Math.max(hi, p.iterations[c]);
    });
    return Number.isFinite(lo) ? [lo, hi] : [0, 0];
  }

  function repaint() {
    const [lo, hi] = iterationRange();
    for (const row of last.rows) paintRow(row, lo, hi);
    drawLegend(legend, last, lo, hi);
  }

  // The pixel under a pointer event (or the keyboard cursor) -> { row, column, a, b }.
  function pixelAt(canvas, x, y) {
    const size = last.request.size;
    const rect = canvas.getBoundingClientRect();
    const column = Math.min(size - 1, Math.max(0, Math.floor(((x - rect.left) / rect.width) * size)));
    const row = size - 1 - Math.min(size - 1, Math.max(0, Math.floor(((y - rect.top) / rect.height) * size)));
    return { row, column };
  }

  function describe(m, { row, column }) {
    const r = last.rows.find((x) => x.row === row);
    const axis = last.axis;
    const a = axis[column];
    const b = axis[row];
    const rows = [];
    const item = (key, term, v) => rows.push(el('dt', {}, term), el('dd', { dataset: { detail: key } }, v));
    item('start', 'Start', `a = ${a.toFixed(4)}, b = ${b.toFixed(4)}`);
    if (r) {
      const px = pixelsOf(r, m)[column];
      item('method', 'Method', label(METHODS, last.request.methods[m]));
      item('status', 'Status', statusBadge(px.status));
      item('root', 'Root', px.root === null || px.root === undefined ? '\u2014' : `root ${px.root}`);
      item('iterations', 'Iterations', String(px.iterations));
    } else {
      item('status', 'Status', 'not computed yet');
    }
    details.replaceChildren(el('h3', {}, 'Start'), el('dl', { class: 'summary' }, rows),
      el('button', { type: 'button', disabled: !last.z, onclick: () => open(m, { row, column }) }, 'Open in Solve'));
  }

  function open(m, { row, column }) {
    const q = last.request;
    const y0 = startPoint(last.z, last.b1, last.b2, last.axis[column], last.axis[row]);
    openSolve({ ...fieldValues(q), n: q.n, h: q.h, method: q.methods[m], differential: q.differential,
      tol: q.tol, max_iterations: q.max_iterations, seed: q.seed, y0: JSON.stringify(y0) });
  }

  function makePanel(method, m, size) {
    const canvas = el('canvas', { width: size, height: size, class: 'basin-canvas', tabindex: 0, role: 'img',
      dataset: { method }, 'aria-label': `Basin map, ${label(METHODS, method)}: arrows move, Enter opens the start in Solve` });
    const cursor = { row: Math.floor(size / 2), column: Math.floor(size / 2) };
    canvas.addEventListener('mousemove', (e) => describe(m, pixelAt(canvas, e.clientX, e.clientY)));
    canvas.addEventListener('click', (e) => {
      const p = pixelAt(canvas, e.clientX, e.clientY);
      Object.assign(cursor, p);
      describe(m, p);
      if (e.pointerType !== 'touch' && last.z) open(m, p);
    });
    canvas.addEventListener('focus', () => describe(m, cursor));
    canvas.addEventListener('keydown', (e) => {
      const steps = { ArrowUp: [1, 0], ArrowDown: [-1, 0], ArrowLeft: [0, -1], ArrowRight: [0, 1] };
      if (steps[e.key]) {
        e.preventDefault();
        cursor.row = Math.min(size - 1, Math.max(0, cursor.row + steps[e.key][0]));
        cursor.column = Math.min(size - 1, Math.max(0, cursor.column + steps[e.key][1]));
        describe(m, cursor);
      } else if (e.key === 'Enter' && last.z) {
        e.preventDefault();
        open(m, cursor);
      }
    });
    const figure = el('figure', { class: 'map basin-map' }, el('figcaption', {}, label(METHODS, method)), canvas,
      el('p', { class: 'axis-title' }, 'a \u2192 (b \u2191)'));
    return { canvas, figure };
  }

  async function renderImage(signal) {
    const q = last.request;
    // As wide as the panel (the map is computed again on the server, so a resize does not redraw it), but at
    // least MIN_PANEL pixels per method: on a phone the picture scrolls sideways rather than shrink its panels
    // (one picture, so that each root keeps one colour across the methods).
    const width = Math.max(imageWidth(output), MIN_PANEL * q.methods.length + 60);
    const url = await postImage('/api/v1/render/basins', { ...q, width, height: 0 }, { signal });
    if (imageUrl) URL.revokeObjectURL(imageUrl);
    imageUrl = url;
    image.querySelector('img').src = url;
    image.hidden = false;
  }

  form.addEventListener('submit', async (e) => {
    e.preventDefault();
    clearTimeout(planTimer);  // a plan made now would overwrite the run's status line
    probe.cancel();
    if (last) last.result = null;
    share.refresh();
    await start(async (signal, progress) => {
      const request = requestOf();
      const size = Number.isInteger(request.size) && request.size > 0 && request.size <= MAX_SIZE ? request.size : 1;
      const panels = request.methods.map((m, i) => makePanel(m, i, size));
      maps.replaceChildren(...panels.map((p) => p.figure));
      image.hidden = true;
      last = { request, rows: [], roots: [], panels, axis: [], z: null, b1: null, b2: null };
      progress.max = size;
      const began = performance.now();
      const result = await stream('/api/v1/basins', request, { signal, onRecord(rec) {
        if (rec.type === 'grid') {
          Object.assign(last, { axis: rec.a, z: rec.z, b1: rec.b1, b2: rec.b2 });
          return;
        }
        if (rec.type !== 'row') return;
        last.rows.push(rec);
        last.roots.push(...rec.new_roots);
        paintRow(rec, 1, request.max_iterations); // provisional shading; repaint() uses the final range
        progress.value = last.rows.length;
        live.textContent = `${paceText(last.rows.length * size * request.methods.length, size * size * request.methods.length,
          'starts', began).replace('\u2026', '')}, ${last.roots.length} roots so far\u2026`;
      } }).catch((err) => {
        if (last.rows.length) repaint();
        throw err;
      });
      last.result = result;
      repaint();
      const estimate = planned?.seconds && planned.size === size && planned.key === JSON.stringify({ ...request, size: undefined }) ? ` (estimated: ${duration(planned.seconds)})` : '';
      live.textContent = `${size} \u00d7 ${size} starts per method in ${(result.seconds ?? 0).toFixed(2)} s${estimate}, ` +
        `${result.roots.length} roots. Hover a pixel for its numbers.`;
      share.refresh();
      await renderImage(signal);
    });
  });
  return { share };
}

// One CSV row per start and method: where it is on the square, and what became of it.
const PIXEL_COLUMNS = ['method', 'row', 'column', 'a', 'b', 'status', 'root', 'iterations'];
function pixelRows({ request, rows, axis }) {
  return request.methods.flatMap((method, m) => rows.flatMap((r) => r.methods[m].status.map((status, c) =>
    [method, r.row, c, axis[c], axis[r.row], status, r.methods[m].root[c], r.methods[m].iterations[c]])));
}

function parseRgb(css) {
  const m = /rgb\((\d+),\s*(\d+),\s*(\d+)\)/.exec(css) ?? /#(..)(..)(..)/.exec(css);
  if (!m) return [128, 128, 128];
  return css.startsWith('#') ? m.slice(1, 4).map((h) => parseInt(h, 16)) : m.slice(1, 4).map(Number);
}

// Per method: share converged, basins, mean iterations; then the roots and the failure classes that occur.
function drawLegend(box, last, lo, hi) {
  const summary = last.result?.methods ?? [];
  const counts = {};
  for (const row of last.rows) for (const p of row.methods) for (const s of p.status) counts[s] = (counts[s] ?? 0) + 1;
  box.replaceChildren(
    summary.length ? el('table', { class: 'basin-summary' },
      el('thead', {}, el('tr', {}, ['Method', 'Converged', 'Basins', 'Mean iterations'].map((h) => el('th', { scope: 'col' }, h)))),
      el('tbody', {}, summary.map((s) => el('tr', { dataset: { method: s.method } },
        el('th', { scope: 'row' }, label(METHODS, s.method)), el('td', {}, `${(100 * s.converged_fraction).toFixed(1)}%`),
        el('td', {}, String(s.basins)), el('td', {}, s.mean_iterations === null ? '\u2014' : s.mean_iterations.toFixed(2)))))) : null,
    el('p', { class: 'hint' }, `Shade: iterations to converge, light ${lo} \u2026 dark ${hi}.`),
    el('ul', { class: 'swatches' },
      last.roots.slice(0, 24).map((r) => el('li', { dataset: { root: String(r.id) } },
        el('span', { class: 'swatch', style: `background:${ROOTS[r.id % ROOTS.length]}` }),
        `root ${r.id}: \u2016log z\u207b\u00b9y\u2016 = ${fmtExp(r.distance_from_z)}`)),
      last.roots.length > 24 ? el('li', {}, `+${last.roots.length - 24} more roots`) : null,
      Object.entries(STATUSES).filter(([s]) => s !== 'converged' && counts[s]).map(([s, info]) =>
        el('li', { dataset: { status: s } }, el('span', { class: 'swatch', style: `background:${info.color}` }),
          `${info.text} (${counts[s]})`))));
}

// y0 = z exp(a B1 + b B2) on SO(N): B in coordinates of the basis E_ij - E_ji (i < j, row-major), exp by
// scaling and squaring of a Taylor series (accurate to rounding for these small N).
export function startPoint(z, b1, b2, a, b) {
  const n = z.length;
  const w = Array.from({ length: n }, () => new Array(n).fill(0));
  let k = 0;
  for (let i = 0; i < n; i += 1) {
    for (let j = i + 1; j < n; j += 1, k += 1) {
      const c = a * b1[k] + b * b2[k];
      w[i][j] = c;
      w[j][i] = -c;
    }
  }
  return matmul(z, expm(w));
}

function matmul(x, y) {
  return x.map((row) => y[0].map((_, j) => row.reduce((s, v, k) => s + v * y[k][j], 0)));
}

function expm(w) {
  const n = w.length;
  const norm = Math.max(...w.map((row) => row.reduce((s, v) => s + Math.abs(v), 0)));
  const squarings = Math.max(0, Math.ceil(Math.log2(norm / 0.25)));
  const x = w.map((row) => row.map((v) => v / 2 ** squarings));
  let term = x.map((row, i) => row.map((_, j) => (i === j ? 1 : 0)));
  let sum = term.map((row) => row.slice());
  for (let p = 1; p <= 18; p += 1) {
    term = matmul(term, x).map((row) => row.map((v) => v / p));
    sum = sum.map((row, i) => row.map((v, j) => v + term[i][j]));
  }
  for (let s = 0; s < squarings; s += 1) sum = matmul(sum, sum);
  return n ? sum : [];
}
