// Stability map panel: a sweep over (method, N, h) streamed cell by cell into one interactive grid per
// method, then the server-rendered heatmap PNG. Hover or focus a cell for its numbers; click or Enter
// opens that solve in the Solve panel.
import { postImage, postJSON, postSvg, stream } from '../shared/api.js';
import { catalog, entry } from '../shared/catalog.js';
import { el } from '../shared/dom.js';
import { imageWidth, onWidthChange } from '../shared/image_width.js';
import { actions, checkboxes, contractNumber, folded, range, select } from '../shared/fields.js';
import { checkedValues, runner, value, wholeRange } from '../shared/form.js';
import { CONTINUATION, DIFFERENTIALS, GLOBALIZATIONS, METHODS, METRICS, PROBLEMS, STATUSES, fmtExp, fmtH, fmtRate, label, mathText, superscript } from '../shared/labels.js';
import { fieldValues, programFields, problemOf } from '../shared/request.js';
import { NO_VALUE, fixedScale, isOutlier, metricValue, rampCss } from '../shared/colormap.js';
import { createGrid } from './grid.js';
import { download, sharePanel } from '../shared/share.js';
import { statusBadge } from '../shared/summary.js';
import { duration, paceText, planBadge, planText, probePoints, prober, sweepEstimate, tooLongText } from '../shared/plan.js';

const METHOD_ORDER = METHODS.map(([m]) => m);
// The largest grid this server accepts (its --max-grid).
const MAX_CELLS = catalog.output_limits.max_grid_cells;
// Narrower than this per method, the heatmap's cells and tick labels get too small: one PNG per method instead.
const MIN_PANEL = 300;

export function createStabilityPanel(root, { openSolve }) {
  const form = el('form', { class: 'controls', novalidate: true, 'aria-label': 'Sweep request' },
    select('problem', 'Problem', PROBLEMS, 'paper-linear'),
    programFields(),
    checkboxes('methods', 'Methods', METHODS, METHOD_ORDER, ['method']),
    select('differential', 'Differential', DIFFERENTIALS, 'finite-difference'),
    range('n', 'Dimension N', ['n_lo', 2], ['n_hi', 15], 'The paper: 2 to 15'),
    range('h', 'log\u2082 h', ['k_lo', -10], ['k_hi', 10], 'h = 2\u1d4f; the paper: \u221210 to 10'),
    select('metric', 'Colour converged cells by', METRICS, 'iterations'),
    folded('More options: Newton variant, continuation, tolerance, seed',
      select('globalization', 'Newton variant', GLOBALIZATIONS, 'none', 'The paper: none'),
      select('continuation', 'Continuation in h', CONTINUATION, 'false', 'The paper: off'),
      contractNumber('SweepRequest', 'multistart', 'Multistart', { hint: 'Seeded starts tried when no root was found' }),
      contractNumber('SweepRequest', 'tol', 'Tolerance'),
      contractNumber('SweepRequest', 'max_iterations', 'Max iterations'),
      contractNumber('SweepRequest', 'seed', 'Seed')),
    actions());
  const live = el('p', { class: 'live', role: 'status' }, 'Press Run to sweep the grid (the paper\u2019s Figure 5.1).');
  const maps = el('div', { class: 'maps', id: 'stability-grids' });
  // What the grids show, named as the server's PNG title names it.
  const caption = el('p', { class: 'map-caption', id: 'stability-caption' });
  const legend = el('div', { class: 'legend', id: 'stability-legend' });
  // The grids show each cell; the same cells as tables and as the server's PNG are one click away, folded.
  const figures = el('div', { class: 'figure-tables', id: 'figure-tables' });
  const details = el('aside', { class: 'cell-details', id: 'cell-details', 'aria-live': 'polite' },
    el('p', { class: 'hint' }, 'Hover or focus a cell to see its numbers.'));
  const pictures = el('div', { class: 'heatmap-images' });
  const pngCaption = el('span', {}, 'Server-rendered heatmap (PNG): x = log\u2082 h, y = N, one panel per method. ');
  // The same picture as SVG (vectors, for a paper), all methods side by side.
  const svgButton = el('button', { type: 'button', dataset: { share: 'svg' }, onclick: () => postSvg('/api/v1/render/heatmap',
    { ...last.request, sweep: { cells: last.cells, seconds: last.seconds }, metric: value(form, 'metric') })
    .then((text) => download('stability-map.svg', 'image/svg+xml', text)).catch((err) => { live.textContent = `Failed: ${err.message}`; }) },
  'Download SVG');
  const image = el('figure', { class: 'heatmap', hidden: true }, pictures,
    el('figcaption', {}, pngCaption, svgButton));
  const tablesFold = el('details', { class: 'view', id: 'stability-tables', hidden: true },
    el('summary', {}, 'As tables (the paper\u2019s Figures 5.1 and 5.2)'), figures);
  const imageFold = el('details', { class: 'view', id: 'stability-png' },
    el('summary', {}, 'As the server\u2019s PNG (for a slide or a paper)'), image);
  let last = null; // { request, cells, grids }
  const share = sharePanel(form, {
    requests: () => [{ path: '/api/v1/sweep', body: requestOf() }],
    data: () => last?.done && { name: 'stability-map', columns: CELL_COLUMNS,
      rows: last.cells.map((c) => CELL_COLUMNS.map((k) => c[k] ?? null)), json: { request: last.request, cells: last.cells } },
  });
  // The key sits right under the grids (beside them the cell's card), so that on a phone it is in view with them.
  const output = el('div', { class: 'output' }, live, caption,
    el('div', { class: 'map-area' }, el('div', { class: 'map-column' }, maps, legend), details),
    share.element, tablesFold, imageFold);
  root.append(form, output);

  const start = runner(form, live);

  // The plan, before Run: a probe sweeps 3 h (smallest, middle, largest) of the grid for each method at 3 N
  // (likewise), one request per N; their times give the estimate (plan.js) and their cells' metric values the
  // colour scale, fixed before the run.
  const probe = prober();
  const badge = planBadge(form);
  let planned = null;  // { key, cells, estimate } of the current form, or { key, timedOut }
  let planTimer = null;
  const keyOf = (request) => JSON.stringify(request);
  async function plan(running) {
    if (!running && (form.getAttribute('aria-busy') === 'true' || root.closest('[hidden]'))) return null;
    let request;
    try {
      request = requestOf();
    } catch { return null; }  // a bad range: Run names it
    const key = keyOf(request);
    const total = request.methods.length * request.n.length * request.h.length;
    badge.clear();
    if (!total) return null;
    if (total > MAX_CELLS) {
      live.textContent = `${total} cells: more than this server\u2019s limit of ${MAX_CELLS}; make the grid smaller.`;
      return null;
    }
    const ns = probePoints(request.n);
    const sample = { ...request, h: probePoints(request.h) };
    const probeWords = `probe of ${sample.methods.length * ns.length * sample.h.length} of its cells`;
    if (planned?.key !== key) {
      live.textContent = `${total} cells to solve; timing a few of them\u2026`;
      let answer;
      try {
        answer = await probe(async (signal) => {
          const probes = [];
          for (const n of ns) probes.push({ n, answer: await postJSON('/api/v1/sweep', { ...sample, n: [n] }, { signal }) });
          return probes;
        }, running);
      } catch {
        if (!running) live.textContent = `${total} cells to solve. Press Run.`;  // Run names the field at fault
        return null;
      }
      if (!answer) return null;  // a newer plan took over
      planned = answer.timedOut ? { key, timedOut: true, byServer: answer.byServer, cells: [] }
        : { key, cells: answer.flatMap((p) => p.answer.cells), estimate: sweepEstimate(request, answer) };
    }
    live.textContent = planned.timedOut
      ? tooLongText({ count: total, unit: 'cells', probe: probeWords, byServer: planned.byServer })
      : `${planText({ count: total, unit: 'cells', seconds: planned.estimate.seconds, probe: probeWords })}` +
        (running ? '' : ' Press Run.');
    live.dataset.estimate = planned.timedOut ? '' : String(planned.estimate.seconds);
    badge.say({ count: total, unit: 'cells', seconds: planned.timedOut ? null : planned.estimate.seconds });
    return planned;
  }
  const replan = (e) => {
    if (e?.target.name === 'metric') return;
    clearTimeout(planTimer);
    planTimer = setTimeout(plan, 300);
  };
  form.addEventListener('input', replan);
  form.addEventListener('change', replan);
  // A panel opened later plans when it is shown.
  new IntersectionObserver((seen) => { if (seen.some((x) => x.isIntersecting)) replan(); }).observe(form);

  function requestOf() {
    const problem = problemOf(form);
    // rigid-body, heavy-top and stiff-body are written for one n: the map sweeps h alone there.
    const onlyN = problem.problem ? entry('problem', problem.problem).n : undefined;
    const request = { ...problem, methods: checkedValues(form, 'methods'),
      differential: value(form, 'differential'), n: onlyN ? [onlyN] : wholeRange(form, 'n_lo', 'n_hi', 'N'),
      h: wholeRange(form, 'k_lo', 'k_hi', 'k').map((k) => 2 ** k), seed: value(form, 'seed'),
      tol: value(form, 'tol'), max_iterations: value(form, 'max_iterations'),
      globalization: value(form, 'globalization'), continuation: value(form, 'continuation') === 'true' };
    const multistart = value(form, 'multistart');
    if (multistart !== '') request.multistart = multistart;  // empty: the server's default
    return request;
  }
  let imageUrls = [];

  // The grids, legend and caption on the scale fixed for the metric before the run (the probe's cells).
  function paint() {
    const metric = value(form, 'metric');
    const scale = fixedScale(metric, last.request, last.probeCells);
    for (const c of last.cells) last.grids.find((g) => g.set(c, metric, scale));
    const r = last.request;
    drawLegend(legend, last.cells, scale, metric, r.methods.length * r.n.length * r.h.length);
    caption.textContent = captionOf(r, last.cells.length, metric);
    pngCaption.textContent = `Server-rendered heatmap (PNG) of ${problemText(r)}: x = log\u2082 h, y = N, one panel per method. `;
    drawFigureTables(figures, r, last.cells);
  }

  // One PNG as wide as the panel; where that leaves a method's panel under MIN_PANEL pixels (a phone), one PNG
  // per method, stacked, each the panel's width.
  async function renderImage(signal, width = imageWidth(output)) {
    const methods = last.request.methods;
    const split = methods.length > 1 && width / methods.length < MIN_PANEL;
    const parts = split ? methods.map((m) => [m]) : [methods];
    // The cells drawn, not run again, with their request beside them for the title (problem, group, solver). One
    // picture at a time: the server runs only half of its long requests for one client at once (429 beyond), and
    // a phone's one picture per method, beside a sweep or a redraw still open in another tab, would pass that.
    const urls = [];
    for (const group of parts) {
      urls.push(await postImage('/api/v1/render/heatmap', { ...last.request, methods: group,
        sweep: { cells: last.cells.filter((c) => group.includes(c.method)), seconds: last.seconds },
        metric: value(form, 'metric'), width }, { signal }));
    }
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

  function show(cell, reveal = false) {
    const row = (key, term, v) => [el('dt', {}, term), el('dd', { dataset: { detail: key } }, v)];
    details.replaceChildren(el('h3', {}, 'Cell'), el('dl', { class: 'summary' },
      row('method', 'Method', label(METHODS, cell.method)), row('n', 'N', String(cell.n)), row('h', 'h', fmtH(cell.h)),
      row('status', 'Status', statusBadge(cell.status)), row('reason', 'Why', mathText(cell.reason)),
      row('iterations', 'Iterations', String(cell.iterations)), row('rate', 'Rate r', fmtRate(cell.rate)),
      row('residual', 'Final \u2016f\u2016', fmtExp(cell.residual))),
    el('button', { type: 'button', onclick: () => openCell(cell) }, 'Open in Solve'));
    // On a phone the card is under the grids: a tapped cell brings it into view (not on hover, which would jump).
    if (reveal) details.scrollIntoView({ block: 'nearest' });
  }

  function openCell(cell) {
    const r = last.request;
    openSolve({ ...fieldValues(r), n: cell.n, h: cell.h, method: cell.method, differential: r.differential,
      tol: r.tol, max_iterations: r.max_iterations, seed: r.seed, globalization: r.globalization,
      continuation: r.continuation, multistart: r.multistart ?? 0 });
  }

  form.addEventListener('submit', async (e) => {
    e.preventDefault();
    clearTimeout(planTimer);  // the run plans itself, first
    resized?.abort();
    if (last) last.done = false;
    share.refresh();
    await start(async (signal, progress) => {
      const request = requestOf();
      // The colour scale is fixed before the sweep starts (from the probe, probed now if Run came first).
      const metric = value(form, 'metric');
      const probed = (await plan(signal)) ?? { cells: [] };
      const scale = fixedScale(metric, request, probed.cells);
      const grids = request.methods.map((method) => createGrid({ method, ns: request.n, hs: request.h,
        onShow: show, onOpen: openCell }));
      maps.replaceChildren(...grids.map((g) => g.element));
      image.hidden = true;
      last = { request, cells: [], grids, seconds: 0, done: false, probeCells: probed.cells };
      const total = request.methods.length * request.n.length * request.h.length;
      caption.textContent = captionOf(request, 0, metric);
      drawLegend(legend, [], scale, metric, total);
      progress.max = total;
      const began = performance.now();
      let legendFrame = 0;
      // A cancelled or timed-out sweep keeps the cells it finished, on the scale fixed before it started.
      const result = await stream('/api/v1/sweep', request, { signal, onRecord(rec) {
        if (rec.type !== 'cell') return;
        const { type, ...cell } = rec;
        last.cells.push(cell);
        // Coloured on the scale fixed before the run; a value beyond it is drawn at its end.
        grids.find((g) => g.set(cell, metric, scale));
        progress.value = last.cells.length;
        // The legend's counts and the caption once per frame, not per cell.
        legendFrame ||= requestAnimationFrame(() => {
          legendFrame = 0;
          drawLegend(legend, last.cells, scale, metric, total);
          caption.textContent = captionOf(request, last.cells.length, metric);
        });
        live.textContent = paceText(last.cells.length, total, 'cells', began);
      } }).catch((err) => {
        if (last.cells.length) paint();
        throw err;
      });
      if (Array.isArray(result.cells)) last.cells = result.cells;
      last.cells.sort(cellOrder);
      last.seconds = result.seconds ?? 0;
      last.done = true;
      tablesFold.hidden = false;
      paint();  // on the same fixed scale: no cell changes colour when the map is complete
      const estimate = probed.estimate ? ` (estimated: ${duration(probed.estimate.seconds)})` : '';
      live.textContent = `${last.cells.length} cells in ${(last.seconds).toFixed(2)} s${estimate}. Hover a cell for its numbers.`;
      share.refresh();
      await renderImage(signal);
    });
  });

  // A new metric recolours the grid and re-renders the PNG without solving again.
  form.elements.namedItem('metric').addEventListener('change', () => {
    if (!last || !last.cells.length) return;
    paint();
    start((signal) => renderImage(signal));
  });
  return { share };
}

// The problem's label, or "your g(y) = ..." for a program.
function problemText(r) {
  return r.g ? `your g(y) = ${r.g.replace(/\s+/g, ' ').slice(0, 60)}` : label(PROBLEMS, r.problem);
}

// "paper-linear (§5, linear g) on SO(N) · N = 2…15 · h = 2⁻¹⁰…2¹⁰ · Finite differences · tol 1e-10 ·
// colour: iterations (12 of 882 cells)"
function captionOf(r, done, metric) {
  const k = r.h.map((h) => superscript(Math.log2(h)));
  const total = r.methods.length * r.n.length * r.h.length;
  return `${problemText(r)} \u00b7 N = ${r.n[0]}\u2026${r.n.at(-1)} \u00b7 h = 2${k[0]}\u20262${k.at(-1)} \u00b7 ` +
    `${label(DIFFERENTIALS, r.differential)} \u00b7 tol ${r.tol} \u00b7 colour: ${label(METRICS, metric).toLowerCase()} ` +
    `(${done} of ${total} cells)`;
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
  const beyond = metric === 'rate' ? 0 : cells.filter((c) => {
    const v = metricValue(c, metric);
    return v !== null && (v < scale.lo || v > scale.hi);
  }).length;
  const missing = total - cells.length;
  for (const c of cells) counts[c.status] = (counts[c.status] ?? 0) + 1;
  const noValue = cells.filter((c) => c.status === 'converged' && metricValue(c, metric) === null).length;
  const fmt = (v) => (metric === 'residual' ? `1e${v.toFixed(1)}` : metric === 'rate' ? v.toFixed(2) : String(v));
  box.replaceChildren(
    el('div', { class: 'ramp' }, el('span', {}, `converged, ${label(METRICS, metric).toLowerCase()}: ${fmt(scale.lo)}`),
      el('span', { class: 'ramp-bar', style: `background:${rampCss()}` }), el('span', {}, fmt(scale.hi)),
      el('span', { class: 'hint' }, `(${SCALE_WORDS[metric]})`)),
    ...(metric === 'rate' ? [el('p', { class: 'hint', dataset: { legend: 'outliers' } },
      `Rates outside 0\u20133 are clamped to the ends and marked with a dot (${outliers}).`)] : []),
    ...(beyond ? [el('p', { class: 'hint', dataset: { legend: 'beyond' } },
      `Beyond the scale fixed before the run, drawn at its ends (${beyond}).`)] : []),
    // Only what the grids show: a key of every status, most of them "(0)", reads as a list of things to look for.
    el('ul', { class: 'swatches' },
      noValue ? el('li', { dataset: { legend: 'no-value' } }, el('span', { class: 'swatch', style: `background:${NO_VALUE}` }),
        `converged, no ${label(METRICS, metric).toLowerCase()} (${noValue})`) : null,
      Object.entries(STATUSES).filter(([s]) => s !== 'converged' && counts[s]).map(([s, info]) =>
        el('li', { dataset: { status: s } }, el('span', { class: 'swatch', style: `background:${info.color}` }),
          `${info.text} (${counts[s]})`)),
      missing ? el('li', { dataset: { legend: 'missing' } },
        el('span', { class: 'swatch pending' }), `not reached yet, or the run was cancelled or stopped first (${missing})`) : null));
}

// Where the legend's colour scale comes from (colormap.js, fixedScale).
const SCALE_WORDS = { iterations: 'fixed before the run: the probe\u2019s fewest to max_iterations',
  residual: 'fixed before the run: the probe\u2019s smallest to tol', rate: 'fixed: linear r = 1, quadratic r = 2' };

// A cell's fields, in the order of the CSV's columns.
const CELL_COLUMNS = ['method', 'n', 'h', 'status', 'iterations', 'rate', 'residual'];

// The paper's Figures 5.1/5.2 as numbers: per method, iterations and rate r for each N (rows) and h = 2^k
// (columns); a failed cell shows its status.
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
  box.replaceChildren(
    el('p', { class: 'hint' }, 'Rows N, columns k with h = 2\u1d4f; each cell: iterations \u00b7 rate r, or why it failed. Wide tables scroll sideways; the N column stays.'),
    el('div', { class: 'maps' }, tables));
}
