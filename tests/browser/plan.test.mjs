// Plans for long work and honest timings, end to end against the real server:
//   node tests/browser/plan.test.mjs <server-binary> <web-root> <screenshot-dir>
// The stability map and the basin map estimate their cost before Run from a probe, show their pace while they
// run, fix the stability colours before the sweep starts; size hints and warnings know the limits of the
// server they talk to (a second server is started with small limits, so that reaching them is cheap); Speed
// times its work-precision request several times and shows medians; coinciding curves and the figures say so.
import assert from 'node:assert/strict';
import { after, before, test } from 'node:test';
import { launchChromium, openPage, startServer, stopAll, testArguments, watchdog } from './harness.mjs';

const { binary, webRoot, shots } = testArguments('plan.test.mjs');
watchdog(150_000);

// 30 000 numbers: a basin map of 3 methods may be 57 x 57 (3 numbers per pixel). The limited server also stops
// a sweep or map after 1 s; the capped one has only the output cap, so that the basin plan's probe and the
// 57 x 57 map finish on a slow (sanitizer) build too, whose timings the 1 s limit would otherwise decide.
const CAPPED = ['--max-output-values', '30000'];
const LIMITED = [...CAPPED, '--sweep-timeout', '1'];
let browser; let page; let plain; let limited; let capped;
const errors = [];

before(async () => {
  [plain, limited, capped] = await Promise.all([startServer(binary, webRoot),
    startServer(binary, webRoot, { flags: LIMITED }), startServer(binary, webRoot, { flags: CAPPED })]);
  browser = await launchChromium();
  page = await openPage(browser, { width: 1280, height: 860 }, errors, { console: false });
  // The limited server stops a sweep or map after 1 s with a 504, which the panel reports ("this takes minutes");
  // on a slow (sanitizer) build a probe can meet it, and Chromium logs every non-2xx answer as an error anyway.
  const deadline = (m) => /status of 504/.test(m.text()) && /\/api\/v1\/(sweep|basins)\b/.test(m.location().url ?? '');
  page.on('console', (m) => m.type() === 'error' && !deadline(m) && errors.push(m.text()));
});
after(stopAll);

async function open(server, id, params = {}) {
  await page.goto('about:blank');
  await page.goto(`${server.base}/?${new URLSearchParams(params)}#${id}`);
  await page.locator('#server-state[data-ok="true"]').waitFor();
  return page.locator(`#${id}`);
}
const live = (panel) => panel.locator('.live');
// Every text the status line shows from now on, in order.
const recordLive = (id) => page.evaluate((panel) => {
  const line = document.querySelector(`#${panel} .live`);
  window.__said = [line.textContent];
  new MutationObserver(() => window.__said.push(line.textContent)).observe(line, { childList: true, characterData: true, subtree: true });
}, id);

test('stability map: cells and seconds before Run, pace while running, colours fixed before the sweep', async () => {
  const panel = await open(plain, 'stability', { n_lo: 2, n_hi: 6, k_lo: -2, k_hi: 2 });
  const methods = await panel.locator('input[name="methods"]:checked').count();
  const cells = methods * 5 * 5;  // probed: 3 N x 3 h of them
  await live(panel).filter({ hasText: 'estimated' }).waitFor();
  assert.match(await live(panel).innerText(), new RegExp(`^${cells} cells to solve, (under a second|about \\d+ s) ` +
    `\\(estimated from a probe of ${methods * 9} of its cells\\)\\. Press Run\\.$`));
  const estimate = Number(await live(panel).getAttribute('data-estimate'));
  // In short beside Run, on the first screen.
  assert.match(await panel.locator('.actions .plan').innerText(), new RegExp(`^${cells} cells \u00b7 (under a second|about \\d+ s)$`));
  assert.ok(estimate > 0 && estimate < 60, String(estimate));
  await page.evaluate(() => {
    window.__colours = {};
    new MutationObserver((changes) => {
      for (const c of changes) {
        const cell = c.target;
        if (!cell.classList?.contains('cell') || !cell.style.background) continue;
        const key = `${cell.dataset.method}|${cell.dataset.n}|${cell.dataset.h}`;
        (window.__colours[key] ??= new Set()).add(cell.style.background);
      }
    }).observe(document.querySelector('#stability-grids'), { attributes: true, subtree: true, attributeFilter: ['style'] });
  });
  await recordLive('stability');
  const clicked = Date.now();
  await panel.getByRole('button', { name: 'Run' }).click();
  await live(panel).filter({ hasText: ' cells in ' }).waitFor();
  const wall = (Date.now() - clicked) / 1e3;
  const colours = await page.evaluate(() => Object.values(window.__colours).map((s) => s.size));
  assert.equal(colours.length, cells, 'every cell coloured');
  assert.ok(colours.every((n) => n === 1), `a cell changed colour during or after the run: ${colours}`);
  // The legend's scale: from the probe's fewest iterations to max_iterations, fixed before the first cell.
  assert.match(await panel.locator('#stability-legend .ramp').innerText(), /iterations: \d+\s*100\s*\(fixed before the run/);
  const said = await page.evaluate(() => window.__said);
  assert.ok(said.some((t) => /^\d+ of \d+ cells solved, [\d.]+ cells\/s, (under a second|about \d+ s) left/.test(t)), said.join(' | '));
  const done = await live(panel).innerText();
  assert.match(done, new RegExp(`^${cells} cells in [\\d.]+ s \\(estimated: (under a second|about \\d+ s)\\)\\.`));
  console.log(`stability ${cells} cells: estimated ${estimate.toFixed(2)} s, ${done.match(/in ([\d.]+) s/)[1]} s on the server, ` +
    `${wall.toFixed(2)} s click to result`);
  // The figures name the problem, as the server's PNG does.
  const problem = await panel.getByLabel('Problem').evaluate((s) => s.selectedOptions[0].textContent);
  assert.ok((await panel.locator('#stability-caption').innerText()).startsWith(`${problem} \u00b7 N = 2\u20266`));
  await panel.locator('#stability-png > summary').click();
  await page.waitForFunction(() => document.querySelector('#heatmap-img')?.naturalWidth > 0);
  assert.ok((await panel.locator('.heatmap figcaption').innerText()).includes(`heatmap (PNG) of ${problem}:`));
});

test('stability map: the plan warns beyond the server\'s time limit and its grid limit, and above a minute', async () => {
  const panel = await open(limited, 'stability', { n_lo: 2, n_hi: 20 });
  await live(panel).filter({ hasText: /\u26a0/ }).waitFor();
  // The probe's estimate passes the limit, or the probe itself did (the server stopped it), or it took over 3 s.
  assert.match(await live(panel).innerText(), /(Over|already ran over) the server\u2019s limit of 1 s: .*\(504\)|took over 3 s/);
  assert.match(await panel.locator('.actions .plan').innerText(), /^1197 cells \u00b7 .* \u26a0$/);
  await panel.locator('input[name="k_hi"]').fill('100');
  await live(panel).filter({ hasText: 'limit of 5000' }).waitFor();
  // Above a minute (within the server's limit): the same sentence, from the plan's own rule.
  await open(plain, 'stability');
  const said = await page.evaluate(async () => {
    const { planText } = await import('/shared/plan.js');
    return [59, 61].map((seconds) => planText({ count: 10, unit: 'cells', seconds, probe: 'probe' }));
  });
  assert.doesNotMatch(said[0], /\u26a0/);
  assert.match(said[1], /\u26a0 Over a minute/);
});

test('basins: the size hint is this server\'s real limit for the ticked methods; estimate, pace', async () => {
  const panel = await open(capped, 'basins', { size: 24 });
  const hint = panel.locator('.field[data-field="size"] .hint');
  await hint.filter({ hasText: 'at most 57 with 3 methods' }).waitFor();
  // The hint's number is the limit: one more is refused, that size is served.
  const sizeOk = async (size) => (await fetch(`${capped.base}/api/v1/basins`, { method: 'POST',
    headers: { 'Content-Type': 'application/json' }, body: JSON.stringify({ size, max_iterations: 1 }) })).status;
  assert.equal(await sizeOk(58), 413);
  assert.equal(await sizeOk(57), 200);
  await live(panel).filter({ hasText: 'estimated from a 24 \u00d7 24 probe' }).waitFor();
  assert.match(await live(panel).innerText(), /^1728 starts to solve, (under a second|about \d+ s) /);
  assert.match(await hint.innerText(), /; at 24: (under a second|about \d+ s)/);
  await panel.locator('input[name="methods"]').first().uncheck();
  await hint.filter({ hasText: 'at most 70 with 2 methods' }).waitFor();
  await live(panel).filter({ hasText: /^1152 starts to solve, .*estimated/ }).waitFor();  // the plan of this form
  await recordLive('basins');
  await panel.getByRole('button', { name: 'Run' }).click();
  await live(panel).filter({ hasText: 'starts per method in' }).waitFor();
  const said = await page.evaluate(() => window.__said);
  assert.ok(said.some((t) => /^\d+ of 1152 starts solved, [\d.]+ starts\/s, .* left, \d+ roots so far/.test(t)), said.join(' | '));
  assert.match(await live(panel).innerText(), /^24 \u00d7 24 starts per method in [\d.]+ s \(estimated: (under a second|about \d+ s)\)/);
});

test('speed: each point is the median of repeated runs, pairs within the noise are named, coinciding curves flagged', async () => {
  const panel = await open(plain, 'speed', { k_lo: -5, k_hi: -3 });
  const answers = [];
  const integrations = [];
  page.on('response', async (r) => {
    if (r.url().endsWith('/api/v1/work-precision')) answers.push(await r.json());
    if (r.url().endsWith('/api/v1/integrate')) integrations.push(await r.json());
  });
  const clicked = Date.now();
  await panel.getByRole('button', { name: 'Run' }).click();
  await live(panel).filter({ hasText: /^Done: .* invariant runs\.$/ }).waitFor();
  console.log(`speed k -5..-3: ${((Date.now() - clicked) / 1e3).toFixed(2)} s click to result`);
  for (let i = 0; i < 100 && answers.length < 5; i += 1) await new Promise((r) => setTimeout(r, 20));  // bodies read
  const repeats = answers.length;
  assert.equal(repeats, 5);
  const med = (xs) => xs.sort((a, b) => a - b)[xs.length >> 1];
  const cpu = answers[0].series.map((s, i) => s.points.map((p, j) => med(answers.map((a) => a.series[i].points[j].cpu_seconds)))
    .map((v, j) => [s.points[j].h, v]).sort((a, b) => b[0] - a[0]).map(([, v]) => v));
  const plotted = await page.evaluate(() => window.__lienewtonCharts['work-precision-chart'].cpu);
  assert.deepEqual(plotted, cpu);
  // The noise sentence names exactly the pairs whose ranges overlap at some h.
  const range = (i, j) => answers.map((a) => a.series[i].points[j].cpu_seconds).sort((a, b) => a - b);
  const series = answers[0].series;
  let overlapping = 0;
  for (let i = 0; i < series.length; i += 1) {
    for (let j = i + 1; j < series.length; j += 1) {
      if (series[i].points.some((_, k) => {
        const [a, b] = [range(i, k), range(j, k)];
        return a[0] <= b.at(-1) && b[0] <= a.at(-1);
      })) overlapping += 1;
    }
  }
  const note = await panel.locator('#work-precision-noise').innerText();
  assert.equal(overlapping ? note.split('; ').length : 0, overlapping, note);
  if (!overlapping) assert.match(note, /^No two choices/);
  // Energy curves: a curve drawn under another says so in the legend and under the chart.
  const curves = integrations.map((r) => r.steps.map((s) => (s.energy - r.initial_energy) / r.initial_energy));
  const same = curves.map((c, i) => curves.findIndex((d, j) => j < i && c.every((v, k) =>
    Math.abs(v - d[k]) <= 1e-6 * Math.max(Math.abs(v), Math.abs(d[k])))));
  const legend = await panel.locator('#energy-chart .u-legend .u-series .u-label').allInnerTexts();
  const flagged = legend.filter((t) => t.includes('(same curve as'));
  assert.equal(flagged.length, same.filter((j) => j >= 0).length, legend.join(' | '));
  assert.equal((await panel.locator('#energy-coincide').innerText()) !== '', flagged.length > 0);
  console.log(`speed: ${flagged.length} coinciding energy curves of ${curves.length}; ${overlapping} pairs within the noise`);
});

test('the dexp\u207b\u00b9 truncations read as terms of the series, not as orders', async () => {
  const panel = await open(plain, 'solve');
  const options = await panel.getByLabel('Differential').locator('option').allInnerTexts();
  assert.ok(options.includes('dexp\u207b\u00b9 truncated after 1 term'), options.join(' | '));
  assert.ok(options.includes('dexp\u207b\u00b9 truncated after 2 terms'), options.join(' | '));
  const everywhere = await page.locator('main').evaluate((m) => m.textContent);
  assert.doesNotMatch(everywhere, /order [01]\b/);
});

test('no errors in the page', () => assert.deepEqual(errors, []));
