// Stability map panel: a sweep over (method, N, h) streamed cell by cell into one interactive grid per
// method, then the server-rendered heatmap PNG. Hover or focus a cell for its numbers; click or Enter
// opens that solve in the Solve panel.
import { ApiError, postImage, stream } from '../shared/api.js';
import { el } from '../shared/dom.js';
import { imageWidth, onWidthChange } from '../shared/image_width.js';
import { actions, checkboxes, contractNumber, range, select } from '../shared/fields.js';
import { checkedValues, runner, value, wholeRange } from '../shared/form.js';
import { CONTINUATION, DIFFERENTIALS, GLOBALIZATIONS, METHODS, METRICS, PROBLEMS, STATUSES, fmtExp, fmtH, fmtRate, label, mathText } from '../shared/labels.js';
import { NO_VALUE, isOutlier, metricScale, metricValue, rampCss } from '../shared/colormap.js';
import { createGrid } from './grid.js';
import { statusBadge } from '../shared/summary.js';

const METHOD_ORDER = METHODS.map(([m]) => m);
// Narrower than this per method, the heatmap's cells and tick labels get too small: one PNG per method instead.
const MIN_PANEL = 300;

export function createStabilityPanel(root, { openSolve }) {
  const form = el('form', { class: 'controls', novalidate: true, 'aria-label': 'Sweep request' },
    select('problem', 'Problem', PROBLEMS, 'paper-linear'),
    checkboxes('methods', 'Methods', METHODS, METHOD_ORDER, ['method']),
    select('differential', 'Differential', DIFFERENTIALS, 'finite-difference'),
    select('globalization', 'Newton variant', GLOBALIZATIONS, 'none', 'The paper: none'),
    select('continuation', 'Continuation in h', CONTINUATION, 'false', 'The paper: off'),
    contractNumber('SweepRequest', 'restarts', 'Restarts', { hint: 'With continuation: seeded starts tried last' }),
    range('n', 'Dimension N', ['n_lo', 2], ['n_hi', 15], 'The paper: 2 to 15'),
    range('h', 'log\u2082 h', ['k_lo', -10], ['k_hi', 10], 'h = 2\u1d4f; the paper: \u221210 to 10'),
    contractNumber('SweepRequest', 'tol', 'Tolerance'),
    contractNumber('SweepRequest', 'max_iterations', 'Max iterations'),
    contractNumber('SweepRequest', 'seed', 'Seed'),
    select('metric', 'Colour converged cells by', METRICS, 'iterations'),
    actions());
  const live = el('p', { class: 'live', role: 'status' }, 'Press Run to sweep the grid (the paper\u2019s Figure 5.1).');
  const maps = el('div', { class: 'maps', id: 'stability-grids' });
  const legend = el('div', { class: 'legend', id: 'stability-legend' });
  const figures = el('section', { class: 'figure-tables', id: 'figure-tables' });
  const details = el('aside', { class: 'cell-details', id: 'cell-details', 'aria-live': 'polite' },
    el('p', { class: 'hint' }, 'Hover or focus a cell to see its numbers.'));
  const pictures = el('div', { class: 'heatmap-images' });
  const image = el('figure', { class: 'heatmap', hidden: true }, pictures,
    el('figcaption', {}, 'Server-rendered heatmap (PNG): x = log\u2082 h, y = N, one panel per method.'));
  const output = el('div', { class: 'output' }, live, el('div', { class: 'map-area' }, maps, details), legend, figures, image);
  root.append(form, output);

  const start = runner(form, live);
  let last = null; // { request, cells, grids }
  let imageUrls = [];

  function paint() {
    const metric = value(form, 'metric');
    const scale = metricScale(last.cells, metric);
    for (const c of last.cells) last.grids.find((g) => g.set(c, metric, scale));
    const r = last.request;
    drawLegend(legend, last.cells, scale, metric, r.methods.length * r.n.length * r.h.length);
    drawFigureTables(figures, r, last.cells);
  }

  // One PNG as wide as the panel; where that leaves a method's panel under MIN_PANEL pixels (a phone), one PNG
  // per method, stacked, each the panel's width.
  async function renderImage(signal, width = imageWidth(output)) {
    const methods = last.request.methods;
    const split = methods.length > 1 && width / methods.length < MIN_PANEL;
    const parts = split ? methods.map((m) => [m]) : [methods];
    const urls = await Promise.all(parts.map((group) => postImage('/api/v1/render/heatmap', {
      sweep: { cells: last.cells.filter((c) => group.includes(c.method)), seconds: last.seconds },
      metric: value(form, 'metric'), width }, { signal })));
    for (const url of imageUrls) URL.revokeObjectURL(url);
    imageUrls = urls;
    drawnWidth = width;
    pictures.replaceChildren(...urls.map((src, i) => el('img', { id: i ? `heatmap-img-${i + 1}` : 'heatmap-img', src,
      alt: `Server-rendered heatmap of the sweep: ${parts[i].map((m) => label(METHODS, m)).join(', ')}` })));
    image.hidden = false;
  }
  // A finished map is drawn again at the new width (a new run hides the picture until it has its own).
  let resized = null;
  let drawnWidth = 0;
  onWidthChange(output, (width) => {
    if (!last?.cells.length || image.hidden || width === drawnWidth) return;
    resized?.abort();
    resized = new AbortController();
    renderImage(resized.signal, width).catch(() => { /* the picture at the old width stays */ });
  });

  function show(cell) {
    const row = (key, term, v) => [el('dt', {}, term), el('dd', { dataset: { detail: key } }, v)];
    details.replaceChildren(el('h3', {}, 'Cell'), el('dl', { class: 'summary' },
      row('method', 'Method', label(METHODS, cell.method)), row('n', 'N', String(cell.n)), row('h', 'h', fmtH(cell.h)),
      row('status', 'Status', statusBadge(cell.status)), row('reason', 'Why', mathText(cell.reason)),
      row('iterations', 'Iterations', String(cell.iterations)), row('rate', 'Rate r', fmtRate(cell.rate)),
      row('residual', 'Final \u2016f\u2016', fmtExp(cell.residual))),
    el('button', { type: 'button', onclick: () => openCell(cell) }, 'Open in Solve'));
  }

  function openCell(cell) {
    const r = last.request;
    openSolve({ problem: r.problem, n: cell.n, h: cell.h, method: cell.method, differential: r.differential,
      tol: r.tol, max_iterations: r.max_iterations, seed: r.seed, globalization: r.globalization,
      continuation: r.continuation, restarts: r.restarts ?? 0 });
  }

  form.addEventListener('submit', async (e) => {
    e.preventDefault();
    resized?.abort();
    await start(async (signal, progress) => {
      const request = { problem: value(form, 'problem'), methods: checkedValues(form, 'methods'),
        differential: value(form, 'differential'), n: wholeRange(form, 'n_lo', 'n_hi', 'N'),
        h: wholeRange(form, 'k_lo', 'k_hi', 'k').map((k) => 2 ** k), seed: value(form, 'seed'),
        tol: value(form, 'tol'), max_iterations: value(form, 'max_iterations'),
        globalization: value(form, 'globalization'), continuation: value(form, 'continuation') === 'true' };
      if (request.continuation) request.restarts = value(form, 'restarts');
      const grids = request.methods.map((method) => createGrid({ method, ns: request.n, hs: request.h,
        onShow: show, onOpen: openCell }));
      maps.replaceChildren(...grids.map((g) => g.element));
      image.hidden = true;
      last = { request, cells: [], grids, seconds: 0 };
      const total = request.methods.length * request.n.length * request.h.length;
      progress.max = total;
      // A cancelled or timed-out sweep keeps the cells it finished, coloured on their own range.
      const result = await stream('/api/v1/sweep', request, { signal, onRecord(rec) {
        if (rec.type !== 'cell') return;
        const { type, ...cell } = rec;
        last.cells.push(cell);
        // Provisional colours on the range so far; paint() recolours on the final range.
        const metric = value(form, 'metric');
        grids.find((g) => g.set(cell, metric, metricScale(last.cells, metric)));
        progress.value = last.cells.length;
        live.textContent = `${last.cells.length} of ${total} cells solved\u2026`;
      } }).catch((err) => {
        if (last.cells.length) paint();
        throw err;
      });
      if (Array.isArray(result.cells)) last.cells = result.cells;
      last.cells.sort(cellOrder);
      last.seconds = result.seconds ?? 0;
      paint();
      live.textContent = `${last.cells.length} cells in ${(last.seconds).toFixed(2)} s. Hover a cell for its numbers.`;
      await renderImage(signal);
    });
  });

  // A new metric recolours the grid and re-renders the PNG without solving again.
  form.elements.namedItem('metric').addEventListener('change', () => {
    if (!last || !last.cells.length) return;
    paint();
    start((signal) => renderImage(signal));
  });
}

// The documented order of a sweep result: method-major, then N, then h.
function cellOrder(a, b) {
  return METHOD_ORDER.indexOf(a.method) - METHOD_ORDER.indexOf(b.method) || a.n - b.n || a.h - b.h;
}

// Every cell of the requested grid is counted once: by its status, as an outlier of the clamped rate scale,
// or as not computed (the sweep was cancelled or stopped before reaching it).
function drawLegend(box, cells, scale, metric, total) {
  const counts = {};
  const outliers = cells.filter((c) => isOutlier(c, metric)).length;
  const missing = total - cells.length;
  for (const c of cells) counts[c.status] = (counts[c.status] ?? 0) + 1;
  const noValue = cells.filter((c) => c.status === 'converged' && metricValue(c, metric) === null).length;
  const fmt = (v) => (metric === 'residual' ? `1e${v.toFixed(1)}` : metric === 'rate' ? v.toFixed(2) : String(v));
  box.replaceChildren(
    el('div', { class: 'ramp' }, el('span', {}, `converged, ${label(METRICS, metric).toLowerCase()}: ${fmt(scale.lo)}`),
      el('span', { class: 'ramp-bar', style: `background:${rampCss()}` }), el('span', {}, fmt(scale.hi))),
    ...(metric === 'rate' ? [el('p', { class: 'hint', dataset: { legend: 'outliers' } },
      `Rates outside 0\u20133 are clamped to the ends and marked with a dot (${outliers}).`)] : []),
    el('ul', { class: 'swatches' },
      el('li', { class: noValue ? '' : 'absent' }, el('span', { class: 'swatch', style: `background:${NO_VALUE}` }),
        `converged, no ${label(METRICS, metric).toLowerCase()} (${noValue})`),
      Object.entries(STATUSES).filter(([s]) => s !== 'converged').map(([s, info]) =>
      el('li', { class: counts[s] ? '' : 'absent' }, el('span', { class: 'swatch', style: `background:${info.color}` }),
        `${info.text} (${counts[s] ?? 0})`)),
      el('li', { class: missing ? '' : 'absent', dataset: { legend: 'missing' } },
        el('span', { class: 'swatch pending' }), `not reached: the run was cancelled or stopped first (${missing})`)));
}

// The paper's Figures 5.1/5.2 as numbers: per method, iterations and rate r for each N (rows) and h = 2^k
// (columns); a failed cell shows its status. The same cells as CSV for a spreadsheet.
function drawFigureTables(box, request, cells) {
  const at = new Map(cells.map((c) => [`${c.method}|${c.n}|${c.h}`, c]));
  const text = (c) => (!c ? '\u00b7' : c.status === 'converged' ? `${c.iterations} \u00b7 ${fmtRate(c.rate)}` : c.status.replace(/_/g, ' '));
  const tables = request.methods.map((method) => el('div', { class: 'table-wrap' },
    el('table', { dataset: { method } },
      el('caption', {}, `${label(METHODS, method)}: iterations \u00b7 rate r`),
      el('thead', {}, el('tr', {}, el('th', { scope: 'col' }, 'N \\ k'),
        request.h.map((h) => el('th', { scope: 'col' }, String(Math.log2(h)))))),
      el('tbody', {}, request.n.map((n) => el('tr', {}, el('th', { scope: 'row' }, String(n)),
        request.h.map((h) => el('td', {}, text(at.get(`${method}|${n}|${h}`))))))))));
  const csv = ['method,n,h,status,iterations,rate,residual'].concat(cells.map((c) =>
    [c.method, c.n, c.h, c.status, c.iterations, c.rate ?? '', c.residual ?? ''].join(','))).join('\n');
  const old = box.querySelector('a[download]')?.href;
  if (old) URL.revokeObjectURL(old);
  const link = el('a', { href: URL.createObjectURL(new Blob([csv + '\n'], { type: 'text/csv' })),
    download: 'stability-map.csv' }, 'Download these cells as CSV');
  box.replaceChildren(el('h3', {}, 'As tables (the paper\u2019s Figures 5.1 and 5.2)'),
    el('p', { class: 'hint' }, 'Rows N, columns k with h = 2\u1d4f; each cell: iterations \u00b7 rate r, or why it failed. Wide tables scroll sideways; the N column stays.'),
    link, el('div', { class: 'maps' }, tables));
}
