// End-to-end test of the dashboard against the real server:
//   node tests/browser/dashboard.test.mjs <server-binary> <web-root> <screenshot-dir>
// Each check compares what the page shows with what the API answers for the same request.
import assert from 'node:assert/strict';
import { join } from 'node:path';
import { after, before, test } from 'node:test';
import { launchChromium, openPage, sameMotionFrame, startServer, stopAll, testArguments, watchdog } from './harness.mjs';
import { staleVendored } from './vendor.mjs';

const { binary, webRoot, shots } = testArguments('dashboard.test.mjs');
watchdog(150_000);

let server; let browser; let page; let base;
const consoleErrors = [];
const external = [];
const cspViolations = [];

before(async () => {
  // The tests drive one page through every panel, whose long requests overlap when the machine is busy: room for
  // eight at once from this one address, so that a slow run is not refused 429 (the per-address limit has tests of
  // its own in tests/server).
  server = await startServer(binary, webRoot, { flags: ['--max-streams', '16'] });
  base = server.base;
  browser = await launchChromium();
  page = await openPage(browser, { width: 1280, height: 860 }, consoleErrors);
  page.on('request', (r) => !/^(blob|data):/.test(r.url()) && !r.url().startsWith(base) && external.push(r.url()));
  // Whatever the server's Content-Security-Policy refuses (an inline style, an image source) is reported here.
  await page.exposeFunction('reportCspViolation', (v) => cspViolations.push(v));
  await page.addInitScript(() => document.addEventListener('securitypolicyviolation',
    (e) => window.reportCspViolation(`${e.violatedDirective} ${e.blockedURI} ${e.sourceFile}:${e.lineNumber}`)));
});
after(stopAll);

const api = async (path, body) => {
  const res = await fetch(base + path, { method: 'POST', headers: { 'Content-Type': 'application/json' },
    body: JSON.stringify(body) });
  return { status: res.status, body: await res.json() };
};
const ndjson = async (path, body) => {
  const res = await fetch(base + path, { method: 'POST', body: JSON.stringify(body),
    headers: { 'Content-Type': 'application/json', Accept: 'application/x-ndjson' } });
  return (await res.text()).trim().split('\n').map((l) => JSON.parse(l));
};
const shot = (name, fullPage = true) => page.screenshot({ path: join(shots, `${name}.png`), fullPage });
const tab = (name) => page.getByRole('tab', { name }).click();
const text = (selector) => page.locator(selector).innerText();
// A shown number against the API's: null is shown as a dash, numbers are rounded for display.
function near(shown, expected, abs, rel) {
  if (expected === null) return assert.equal(shown, '\u2014');
  assert.ok(Math.abs(Number(shown) - expected) <= abs + rel * Math.abs(expected), `${shown} vs ${expected}`);
}

// The sweep of an N x h grid that Run sends, not the plan's probes (one N and at most 3 h each).
const sweepOf = (ns, hs) => (r) => r.url().endsWith('/api/v1/sweep') &&
  JSON.parse(r.postData()).n.length === ns && JSON.parse(r.postData()).h.length === hs;

// Every panel's visible text, tab by tab, free of the marks of a missing label or value.
async function everyPanelReadsWell() {
  const broken = /.{0,40}(undefined|\[object Object\]|\bnull\b).{0,40}/;
  for (const name of ['Solve', 'Compare', 'Stability map', 'Basins', 'Speed vs accuracy']) {
    await tab(name);
    const hit = (await page.locator('main').innerText()).match(broken);
    assert.equal(hit, null, `${name} panel shows: ${hit?.[0]}`);
  }
  await tab('Solve');
}

test('vendored uPlot matches the pinned npm package', () => {
  assert.deepEqual(staleVendored(), [], 'run `npm run vendor`');
});

test('page loads with no console errors and nothing fetched from outside', async () => {
  const response = await page.goto(base + '/');
  const headers = response.headers();
  assert.match(headers['content-security-policy'] ?? '', /script-src 'self'; style-src 'self';.*frame-ancestors 'none'/);
  assert.equal(headers['x-frame-options'], 'DENY');
  assert.equal(headers['referrer-policy'], 'same-origin');
  await page.locator('#server-state[data-ok="true"]').waitFor();
  assert.deepEqual(consoleErrors, []);
  assert.deepEqual(external, []);
  // Tabs are keyboard operable: ArrowRight moves to the next panel.
  await page.getByRole('tab', { name: 'Solve' }).focus();
  await page.keyboard.press('ArrowRight');
  assert.equal(await page.getByRole('tab', { name: 'Compare' }).getAttribute('aria-selected'), 'true');
  assert.equal(await page.locator('#compare').isVisible(), true);
  await tab('Solve');
});

test('first Tab reaches the skip link, which leads to the tabs; no chart before the first run', async () => {
  await page.goto('about:blank');
  await page.goto(base + '/#solve');
  await page.locator('#server-state[data-ok="true"]').waitFor();
  assert.equal(await page.evaluate(() => scrollY), 0);
  await page.keyboard.press('Tab');
  assert.equal(await page.evaluate(() => document.activeElement.outerHTML.slice(0, 60)), await page.evaluate(() => document.querySelector('.skip-link').outerHTML.slice(0, 60)));
  await page.keyboard.press('Enter');
  assert.equal(await page.evaluate(() => document.activeElement.id), 'tab-solve');
  // Before any run the chart box is an empty placeholder (no axes, no grid).
  assert.equal(await page.locator('#solve-chart').innerHTML(), '');
  assert.match(await page.evaluate(() => getComputedStyle(document.querySelector('#solve-chart'), '::before').content),
    /after Run/);
});

test('a bad range entry is flagged on its own box and named by its symbol', async () => {
  await tab('Stability map');
  const panel = page.locator('#stability');
  await panel.locator('input[name="k_lo"]').fill('3');
  await panel.locator('input[name="k_hi"]').fill('1');
  await panel.getByRole('button', { name: 'Run' }).click();
  const slot = panel.locator('.field[data-field="h"] .field-error');
  await slot.filter({ hasText: /\S/ }).waitFor();
  assert.equal(await slot.innerText(), 'k from (3) is above k to (1).');
  assert.equal(await panel.locator('input[name="k_hi"]').getAttribute('aria-invalid'), 'true');
  assert.equal(await panel.locator('input[name="k_lo"]').getAttribute('aria-invalid'), null);
  await panel.locator('input[name="k_lo"]').fill('1.5');
  await panel.getByRole('button', { name: 'Run' }).click();
  await slot.filter({ hasText: 'k from: give a whole number' }).waitFor();
  assert.equal(await panel.locator('input[name="k_lo"]').getAttribute('aria-invalid'), 'true');
  await panel.locator('input[name="k_lo"]').fill('-10');
  await panel.locator('input[name="k_hi"]').fill('10');
  await tab('Solve');
});

test('labels and colours come from the server catalog; no panel shows "undefined"', async () => {
  const catalog = (await (await fetch(base + '/openapi.json')).json())['x-lienewton'];
  const methods = await page.locator('#solve').getByLabel('Method').locator('option').allInnerTexts();
  assert.deepEqual(methods, catalog.enums.method.map((m) => m.label));
  await everyPanelReadsWell();
});

test('a solve streams its trace; the chart ends with iterations + 1 points', async () => {
  const panel = page.locator('#solve');
  await panel.getByLabel('Method').selectOption('fixed-point');
  const sent = page.waitForRequest((r) => r.url().endsWith('/api/v1/solve'));
  const motionRequest = page.waitForRequest((r) => r.url().endsWith('/api/v1/render/motion'));
  await panel.getByRole('button', { name: 'Run' }).click();
  const request = await sent;
  assert.match(request.headers().accept, /application\/x-ndjson/);
  assert.match((await request.response()).headers()['content-type'], /application\/x-ndjson/);
  // The same (deterministic) solve streamed again here: Chromium does not keep streamed bodies.
  const lines = await ndjson('/api/v1/solve', JSON.parse(request.postData()));
  const result = lines.at(-1);
  assert.equal(result.type, 'result');
  assert.equal(lines.filter((l) => l.type === 'iteration').length, result.iterations + 1);
  await panel.locator('[data-result="iterations"]').waitFor();
  assert.equal(await page.locator('#solve-chart').getAttribute('data-points'), String(result.iterations + 1));
  assert.equal(await text('#solve [data-result="iterations"]'), String(result.iterations));
  assert.equal(await panel.locator('[data-result="status"] .badge').getAttribute('data-status'), result.status);
  assert.equal(Number(await text('#solve [data-result="residual"]')).toPrecision(3), result.residual.toPrecision(3));
  // Which root: a plain solve does not check.
  assert.equal(result.branch, 'unchecked');
  assert.match(await text('#solve [data-result="branch"]'), /^unchecked/);
  // The reason in mathematical notation, not the API's ASCII (||f(y)||, pi, !=).
  const why = await text('#solve [data-result="reason"]');
  assert.doesNotMatch(why, /\|\||\bpi\b|!=/);
  assert.ok(why.includes('\u2016f(y)\u2016'), why);
  // Iteration ticks are whole numbers (no 2.5 on a phone-wide chart).
  const ticks = (await page.locator('#solve-chart').getAttribute('data-x-ticks')).split(' ');
  assert.ok(ticks.length > 1 && ticks.every((t) => /^\d+$/.test(t)), ticks.join(' '));
  // The iterates as a motion of bodies, on its last frame (the root found); the slider names each frame's iterate
  // and the API's ||f(y_n)||, and each frame is the API's still of that iterate.
  const motionSent = JSON.parse((await motionRequest).postData());
  assert.equal(motionSent.kind, 'solve');
  await page.locator('#solve-motion[data-frames]').waitFor();
  assert.equal(await page.locator('#solve-motion').getAttribute('data-frames'), String(result.iterations + 1));
  assert.equal(await page.locator('#solve-motion').getAttribute('data-frame'), String(result.iterations));
  await motionShownUnscaled('solve-motion', motionSent);
  await shot('solve');
  const iterates = lines.filter((l) => l.type === 'iteration');
  for (const k of [1, 0, result.iterations]) {
    await page.locator('#solve-motion-slider').fill(String(k));
    assert.equal(await page.locator('#solve-motion').getAttribute('data-frame'), String(k));
    assert.match(await text('#solve-motion-readout'), new RegExp(`^n = ${k}: .* = ${iterates[k].residual.toExponential(3).replace('+', '\\+')} \\(frame ${k}\\)$`));
    assert.equal(await sameMotionFrame(page, 'solve-motion', motionSent), k);
  }
});

// Server PNGs are requested at the width they are shown at: count of them, each pixel for pixel, filling the panel.
async function pngsShownUnscaled(where, selector, count) {
  await where.waitForFunction(([sel, n]) => [...document.querySelectorAll(sel)].filter((i) => i.naturalWidth > 0).length === n,
    [selector, count]);
  const sizes = await where.evaluate((sel) => [...document.querySelectorAll(sel)].map((img) =>
    [img.naturalWidth, img.clientWidth, img.naturalHeight, img.clientHeight, img.closest('.output').clientWidth]), selector);
  assert.equal(sizes.length, count);
  for (const [nw, cw, nh, ch, room] of sizes) {
    assert.deepEqual([cw, ch], [nw, nh], `${selector}: a ${nw}x${nh} PNG shown at ${cw}x${ch}`);
    assert.ok(nw > room - 40 && nw <= room, `${selector}: ${nw} wide in a panel of ${room}`);
  }
}

// A motion player's canvas is drawn as wide as its figure, at most 512, and shown at that size (not scaled).
async function motionShownUnscaled(id, sent) {
  const [width, height, shown, room] = await page.evaluate((sel) => {
    const canvas = document.querySelector(`#${sel}-canvas`);
    return [canvas.width, canvas.height, canvas.getBoundingClientRect().width, canvas.closest('figure').clientWidth];
  }, id);
  assert.deepEqual([sent.width, sent.height], [width, height], `#${id} asked for ${sent.width}x${sent.height}`);
  assert.equal(width, height);
  assert.equal(width, Math.min(512, room - 2), `#${id} drawn ${width} wide in a figure of ${room}`);
  assert.ok(Math.abs(shown - 2 - width) < 1, `#${id} drawn ${width} wide but shown ${shown}`);
}

test('"What is this?" next to the problem, method and differential selects follows the select', async () => {
  const panel = page.locator('#solve');
  const about = (name) => panel.locator(`details.about[data-about="${name}"]`);
  // Keyboard: Tab from the select reaches the disclosure, Enter opens it.
  await panel.getByLabel('Method').focus();
  await page.keyboard.press('Tab');
  assert.equal(await page.evaluate(() => document.activeElement.closest('details')?.dataset.about), 'method');
  await page.keyboard.press('Enter');
  assert.equal(await about('method').getAttribute('open'), '');
  for (const [method, eq] of [['fixed-point', '(1.2)'], ['newton-group', '(3.5)'], ['newton-algebra', '(3.20)']]) {
    await panel.getByLabel('Method').selectOption(method);
    assert.ok((await about('method').locator('.about-text').textContent()).includes(eq), `${method}: ${eq}`);
  }
  for (const [d, eq] of [['finite-difference', '(3.18)'], ['dexpinv-0', '(3.10)'], ['dexpinv-1', '(3.11)'], ['exact', '(3.9)']]) {
    await panel.getByLabel('Differential').selectOption(d);
    assert.ok((await about('differential').locator('.about-text').textContent()).includes(eq), `${d}: ${eq}`);
  }
  for (const [p, g] of [['paper-linear', 'diag(diag(y,1),1)'], ['paper-sine', 'sin(y)'], ['rigid-body', 'I\u207b\u00b9 y\u1d40m']]) {
    await panel.getByLabel('Problem').selectOption(p);
    assert.ok((await about('problem').locator('.about-text').textContent()).includes(g), `${p}: ${g}`);
  }
  await panel.getByLabel('Problem').selectOption('paper-linear');
  await panel.getByLabel('Method').selectOption('fixed-point');
  await panel.getByLabel('Differential').selectOption('exact');
  await about('method').locator('summary').click();
  // Every panel's problem select has one; tick tables and method lists explain every choice they offer.
  for (const id of ['compare', 'stability', 'basins', 'speed']) {
    assert.equal(await page.locator(`#${id} details.about[data-about="problem"]`).count(), 1, id);
  }
  const listed = async (id, about, value) => page.locator(`#${id} details.about[data-about="${about}"] dd[data-value="${value}"]`).textContent();
  assert.ok((await listed('compare', 'method differential', 'newton-algebra')).includes('(3.20)'));
  assert.ok((await listed('compare', 'method differential', 'finite-difference')).includes('(3.18)'));
  assert.ok((await listed('speed', 'integrator method differential', 'implicit-euler')).includes('(1.1)'));
  assert.ok((await listed('stability', 'method', 'fixed-point')).includes('(1.2)'));
  assert.ok((await listed('basins', 'method', 'newton-group')).includes('(3.5)'));
});

test('a bad field shows the server message next to that field', async () => {
  const panel = page.locator('#solve');
  await panel.getByLabel('Method').selectOption('newton-group');
  await panel.getByLabel('Step size h').fill('-1');
  await panel.getByRole('button', { name: 'Run' }).click();
  const expected = await api('/api/v1/solve', { problem: 'paper-linear', n: 3, h: -1, method: 'newton-group',
    differential: 'exact', tol: 1e-13, max_iterations: 100, seed: 1 });
  assert.ok([400, 422].includes(expected.status));
  assert.equal(expected.body.error.field, 'h');
  const slot = panel.locator('.field[data-field="h"] .field-error');
  await slot.filter({ hasText: /\S/ }).waitFor();
  assert.equal(await slot.innerText(), expected.body.error.message);
  assert.equal(await panel.getByLabel('Step size h').getAttribute('aria-invalid'), 'true');
  await shot('solve-error', false);
  await panel.getByLabel('Step size h').fill('0.5');
});

test('Your g(y): a built-in fills the editor as a program, a fault shows its line and column under g', async () => {
  const panel = page.locator('#solve');
  await panel.getByLabel('Problem').selectOption('paper-sine');
  await panel.locator('details.folded > summary', { hasText: 'Your own g(y)' }).click();
  await panel.getByRole('button', { name: 'Edit the problem as a program' }).click();
  const editor = panel.locator('textarea[name="g"]');
  assert.match(await editor.inputValue(), /u = sin\(y\)\*\(2\*y - 5\*y\^2\)/);
  assert.match(new URL(page.url()).searchParams.get('g'), /^u = sin/);  // kept in the URL, to share
  await editor.fill('a = y;\ng = a * [1 2; 3 4]');
  await panel.getByRole('button', { name: 'Run' }).click();
  const slot = panel.locator('.field[data-field="g"] .field-error');
  await slot.filter({ hasText: /\S/ }).waitFor();
  assert.match(await slot.innerText(), /^line 2, column \d+: matrix sizes 3\u00d73 and 2\u00d72 do not agree for \*/);
  // The rigid body's parameters land in the table, in MATLAB notation; the URL keeps them as the request's JSON
  // (read in the page: page.url() may lag behind a history.replaceState).
  const inAddress = async (name) => new URLSearchParams(await page.evaluate(() => location.search)).get(name);
  await panel.getByLabel('Problem').selectOption('rigid-body');
  await panel.getByRole('button', { name: 'Edit the problem as a program' }).click();
  const names = panel.getByLabel('Parameter name');
  const values = panel.getByLabel('Parameter value (MATLAB notation)');
  assert.deepEqual(await names.evaluateAll((xs) => xs.map((x) => x.value)), ['J', 'm']);
  assert.deepEqual(await values.evaluateAll((xs) => xs.map((x) => x.value)), ['[1 0 0; 0 2 0; 0 0 3]', '[0.6; 0.8; 0.5]']);
  await values.first().fill('[1 0 0; 0 2 0; 0 0 4]');
  assert.deepEqual(JSON.parse(await inAddress('parameters')),
    { J: [[1, 0, 0], [0, 2, 0], [0, 0, 4]], m: [[0.6], [0.8], [0.5]] });
  await panel.getByRole('button', { name: 'Run' }).click();
  await panel.locator('[data-result="status"] .badge[data-status="converged"]').waitFor();
  // A value that is not a matrix is sent as typed, and the server's answer lands under the table.
  await panel.getByRole('button', { name: 'Add a parameter' }).click();
  await names.last().fill('k');
  await values.last().fill('[1 2; 3]');
  await panel.getByRole('button', { name: 'Run' }).click();
  const parameterError = panel.locator('.field[data-field="parameters"] .field-error');
  await parameterError.filter({ hasText: /\S/ }).waitFor();
  // Text is read as an expression of constants: the server names the parameter and the place in its text.
  assert.match(await parameterError.innerText(), /^line 1, column \d+: parameters\.k: /);
  await shot('solve-parameters', false);
  await panel.getByRole('button', { name: 'Remove this parameter' }).last().click();
  assert.deepEqual(Object.keys(JSON.parse(await inAddress('parameters'))), ['J', 'm']);
  const remove = panel.getByRole('button', { name: 'Remove this parameter' });
  await remove.first().click();
  await remove.first().click();
  assert.equal(await inAddress('parameters'), null);
  await editor.fill('');
  await editor.dispatchEvent('change');
  assert.equal(new URL(page.url()).searchParams.get('g'), null);
  await panel.locator('details.folded > summary', { hasText: 'Your own g(y)' }).click();
  await panel.getByLabel('Problem').selectOption('paper-linear');
});

test('compare draws one residual curve per ticked method', async () => {
  await tab('Compare');
  const panel = page.locator('#compare');
  const ticked = await panel.locator('input[name="runs"]:checked').count();
  const clicked = Date.now();  // before the click: the N = 3 runs may be done before click() returns
  await panel.getByRole('button', { name: 'Run' }).click();
  await panel.locator('#compare-table tbody tr').nth(ticked - 1).waitFor();
  const wall = (Date.now() - clicked) / 1e3;
  console.log(`compare defaults: ${(wall * 1e3).toFixed(0)} ms wall time from click to complete (page and browser included)`);
  await panel.locator('#compare-noise').waitFor();  // the repeated timings: the chart is then scaled to their medians
  assert.equal(await page.locator('#compare-chart').getAttribute('data-series'), String(ticked));
  // Speed vs accuracy of the solvers: one line per run, x = the trace's cpu_seconds, and the time to tol.
  assert.equal(await page.locator('#compare-time-chart').getAttribute('data-series'), String(ticked));
  assert.ok(Number(await page.locator('#compare-time-chart').getAttribute('data-points')) >= ticked);
  const ttol = await panel.locator('#compare-table td[data-col="time-to-tol"]').allInnerTexts();
  assert.equal(ttol.length, ticked);
  for (const t of ttol) assert.match(t, /^(\d+(\.\d+)? (\u00b5s|ms|s)|not reached)$/);
  // The times shown are the solver's own CPU seconds (result cpu_seconds), labelled so: each run's time to tol
  // is the x of its first point at or below tol in the time chart and at most its total; the totals of the
  // runs, done one after the other, fit in the wall time from click to complete.
  const heads = await panel.locator('#compare-table thead th').allInnerTexts();
  const cpuColumn = await panel.locator('#compare-table tbody tr').first().locator('td[data-col="cpu-seconds"]')
    .evaluate((td) => td.cellIndex);
  assert.deepEqual(heads.slice(cpuColumn - 1, cpuColumn + 1), ['Time to tol (CPU)', 'Solver CPU time']);
  const unit = (t) => ({ '\u00b5s': 1e-6, ms: 1e-3, s: 1 })[t.split(' ')[1]];
  const seconds = (t) => Number(t.split(' ')[0]) * unit(t);
  const rounding = (t) => 0.5 * 10 ** -(t.split(' ')[0].split('.')[1] ?? '').length * unit(t);  // half the last digit
  const totals = await panel.locator('#compare-table td[data-col="cpu-seconds"]').allInnerTexts();
  const total = totals.map(seconds);
  // The chart shows each trace scaled to its run's median of the repeats (not the first, noisy run): it ends
  // there, and the time to tol is read off it.
  const { tables } = await page.evaluate(() => window.__lienewtonCharts['compare-time-chart']);
  const medians = (await panel.locator('#compare-table td[data-col="cpu-median"]').allInnerTexts()).map((m) => m.split(' (')[0]);
  const tolX = tables.map(([xs, ys]) => xs[ys.findIndex((y) => y <= 1e-13)]);
  ttol.forEach((t, i) => {
    assert.ok(total[i] > 0, `run ${i}: solver CPU time ${total[i]}`);
    assert.ok(Math.abs(seconds(medians[i]) - tables[i][0].at(-1)) <= rounding(medians[i]) * 1.0001, `run ${i}: median ${medians[i]} vs its last iterate`);
    if (t === 'not reached') return;
    assert.ok(seconds(t) <= seconds(medians[i]) + rounding(t) + rounding(medians[i]), `run ${i}: time to tol ${t} after the median ${medians[i]}`);
    assert.ok(Math.abs(seconds(t) - tolX[i]) <= rounding(t) * 1.0001, `run ${i}: ${t} vs the chart's ${tolX[i]} s`);
  });
  assert.ok(total.reduce((a, b) => a + b, 0) < wall, `solver CPU ${total} s in ${wall} s of wall time`);
  // Every run's iterates as a motion; pick the last run, step to an iterate, see the API's still and residual.
  assert.equal(await panel.locator('#compare-motion-run option').count(), ticked);
  await page.locator('#compare-motion[data-frames]').waitFor();
  const motionSent = page.waitForRequest((r) => r.url().endsWith('/api/v1/render/motion'));
  await panel.locator('#compare-motion-run').selectOption({ index: ticked - 1 });
  const sent = JSON.parse((await motionSent).postData());
  const [method, differential] = (await panel.locator('input[name="runs"]:checked').last().getAttribute('value')).split('|');
  const run = { problem: 'paper-linear', n: 3, h: 0.5, tol: 1e-13, max_iterations: 100, seed: 1, method, differential,
    include_iterates: false };
  assert.deepEqual({ ...run, kind: 'solve' }, Object.fromEntries(Object.keys(run).concat('kind').map((key) => [key, sent[key]])));
  const trace = (await ndjson('/api/v1/solve', run)).filter((l) => l.type === 'iteration');
  await page.waitForFunction((n) => document.querySelector('#compare-motion')?.dataset.frames === String(n), trace.length);
  await page.locator('#compare-motion-slider').fill('2');
  assert.equal(await text('#compare-motion-readout'), `n = 2: \u2016f(y\u2082)\u2016 = ${trace[2].residual.toExponential(3)} (frame 2)`);
  assert.equal(await sameMotionFrame(page, 'compare-motion', sent), 2);
  await shot('compare');
});

test('Esc cancels a run started by clicking Run', async () => {
  await tab('Stability map');
  const panel = page.locator('#stability');
  await panel.getByRole('button', { name: 'Run' }).click();
  await page.waitForFunction(() => document.querySelector('#stability progress')?.value >= 1);
  await page.keyboard.press('Escape');
  await panel.locator('.form-error', { hasText: 'Cancelled.' }).waitFor();
  assert.equal(await panel.getByRole('button', { name: 'Run' }).isEnabled(), true);
  // The legend counts the cells never computed, as many as the grid shows pending.
  const pending = await panel.locator('.cell.pending').count();
  assert.ok(pending > 0);
  assert.match(await text('#stability-legend [data-legend="missing"]'), new RegExp(`\\(${pending}\\)$`));
});

test('a sweep renders the heatmap and hovering a cell shows that cell', async () => {
  await tab('Stability map');
  const panel = page.locator('#stability');
  // The paper's full grid is a long run: it shows progress and Cancel stops it.
  await panel.getByRole('button', { name: 'Run' }).click();
  await page.waitForFunction(() => document.querySelector('#stability progress')?.value >= 1);
  await panel.getByRole('button', { name: 'Cancel' }).click();
  await panel.locator('.form-error', { hasText: 'Cancelled.' }).waitFor();
  assert.equal(await panel.getByRole('button', { name: 'Run' }).isEnabled(), true);
  assert.ok(await panel.locator('.cell.pending').count() > 0, 'the full sweep finished before Cancel');
  await panel.getByRole('checkbox', { name: 'Fixed point (1.2)' }).uncheck();
  for (const [name, v] of [['n_lo', '2'], ['n_hi', '5'], ['k_lo', '-3'], ['k_hi', '3']]) {
    await panel.locator(`input[name="${name}"]`).fill(v);
  }
  const sent = page.waitForRequest(sweepOf(4, 7));
  await panel.getByRole('button', { name: 'Run' }).click();
  const request = JSON.parse((await sent).postData());
  await page.waitForFunction(() => document.querySelector('#heatmap-img')?.naturalWidth > 0);
  await panel.locator('#stability-png > summary').click();  // the PNG is folded: the grids show the cells
  await pngsShownUnscaled(page, '#stability .heatmap img', 1);
  await panel.locator('#stability-png > summary').click();
  const { body: sweep } = await api('/api/v1/sweep', request);
  assert.equal(sweep.cells.length, 2 * 4 * 7);
  assert.equal(await panel.locator('.cell:not(.pending)').count(), sweep.cells.length);
  for (const cell of sweep.cells) {
    const loc = panel.locator(`.cell[data-method="${cell.method}"][data-n="${cell.n}"][data-h="${cell.h}"]`);
    assert.equal(await loc.getAttribute('data-status'), cell.status, `status of ${JSON.stringify(cell)}`);
  }
  for (const cell of [sweep.cells[0], sweep.cells[17], sweep.cells.at(-1)]) {
    await panel.locator(`.cell[data-method="${cell.method}"][data-n="${cell.n}"][data-h="${cell.h}"]`).hover();
    const detail = (key) => text(`#cell-details [data-detail="${key}"]`);
    const methodLabel = (await (await fetch(base + '/openapi.json')).json())['x-lienewton'].enums.method.find((m) => m.value === cell.method).label;
    assert.equal(await detail('method'), methodLabel); // the method's name, not its API value
    assert.equal(Number(await detail('n')), cell.n);
    assert.equal(parseFloat(await detail('h')), cell.h);
    assert.equal(await panel.locator('#cell-details .badge').getAttribute('data-status'), cell.status);
    assert.equal(Number(await detail('iterations')), cell.iterations);
    near(await detail('rate'), cell.rate, 5e-4, 0);
    near(await detail('residual'), cell.residual, 0, 5e-4);
  }
  // Figures 5.1/5.2 as tables (folded): one per method, a row per N, a cell "iterations · rate".
  await panel.locator('#stability-tables > summary').click();
  for (const cell of [sweep.cells[0], sweep.cells.at(-1)]) {
    const table = panel.locator(`#figure-tables table[data-method="${cell.method}"]`);
    const row = request.n.indexOf(cell.n);
    const col = request.h.indexOf(cell.h);
    const shown = await table.locator('tbody tr').nth(row).locator('td').nth(col).innerText();
    assert.equal(shown, cell.status === 'converged' ? `${cell.iterations} \u00b7 ${cell.rate === null ? '\u2014' : cell.rate.toFixed(3)}` : cell.status.replace(/_/g, ' '));
  }
  await panel.locator('#stability-tables > summary').click();
  // Rate colouring is clamped to 0..3; cells outside are marked and counted in the legend.
  await panel.getByLabel('Colour converged cells by').selectOption('rate');
  const outliers = sweep.cells.filter((c) => c.status === 'converged' && Number.isFinite(c.rate) && (c.rate < 0 || c.rate > 3));
  assert.equal(await panel.locator('.cell.outlier').count(), outliers.length);
  assert.match(await text('#stability-legend [data-legend="outliers"]'), new RegExp(`\\(${outliers.length}\\)\\.?$`));
  await page.locator('#heatmap-img').waitFor({ state: 'attached' });
  await panel.getByLabel('Colour converged cells by').selectOption('iterations');
  // Keyboard: the grid is one tab stop; arrows move between cells and show their numbers.
  const first = sweep.cells[0];
  await panel.locator(`.cell[data-method="${first.method}"][data-n="${first.n}"][data-h="${first.h}"]`).focus();
  await page.keyboard.press('ArrowRight');
  assert.equal(parseFloat(await text('#cell-details [data-detail="h"]')), sweep.cells[1].h);
  await shot('stability');
  // Click opens the cell's solve in the Solve panel.
  const cell = sweep.cells[17];
  await panel.locator(`.cell[data-method="${cell.method}"][data-n="${cell.n}"][data-h="${cell.h}"]`).click();
  assert.equal(await page.getByRole('tab', { name: 'Solve' }).getAttribute('aria-selected'), 'true');
  await page.locator('#solve [data-result="iterations"]').waitFor();
  assert.equal(Number(await page.locator('#solve input[name="h"]').inputValue()), cell.h);
  assert.equal(Number(await page.locator('#solve input[name="n"]').inputValue()), cell.n);
});

test('the work-precision chart has one series per ticked choice', async () => {
  await tab('Speed vs accuracy');
  const panel = page.locator('#speed');
  await panel.locator('input[name="k_lo"]').fill('-5');
  await panel.locator('input[name="k_hi"]').fill('-2');
  await panel.locator('details.folded > summary', { hasText: 'More options' }).click();
  await panel.locator('input[name="energy_h"]').fill('0.125');
  const ticked = await panel.locator('input[name="choices"]:checked').count();
  assert.ok(ticked >= 2);
  // The work-precision request is sent 5 times (repeated timings); the chart plots each point's median.
  const answers = [];
  const collect = async (r) => { if (r.url().endsWith('/api/v1/work-precision')) answers.push(await r.json()); };
  page.on('response', collect);
  await panel.getByRole('button', { name: 'Run' }).click();
  const clicked = Date.now();
  await panel.locator('#work-precision-noise').filter({ hasText: /\S/ }).waitFor();
  console.log(`work-precision (speed panel) defaults, k from -5: ${Date.now() - clicked} ms from click to chart (5 runs)`);
  for (let i = 0; i < 100 && answers.length < 5; i += 1) await new Promise((r) => setTimeout(r, 20));  // bodies read
  page.off('response', collect);
  const [wp] = answers;
  const median = (xs) => xs.sort((a, b) => a - b)[xs.length >> 1];
  assert.equal(wp.series.length, ticked);
  // Legend: every series with its fitted order p, in the server's style (colour x dash x marker).
  const catalog = (await (await fetch(base + '/openapi.json')).json())['x-lienewton'];
  assert.ok(catalog.series_styles.length >= 24);
  const legend = await panel.locator('#work-precision-chart .u-legend .u-series').allInnerTexts();
  assert.equal(legend.length, ticked);
  wp.series.forEach((ser, i) => {
    if (ser.fitted_order !== null) assert.ok(legend[i].includes(`p \u2248 ${ser.fitted_order.toFixed(2)}`), legend[i]);
  });
  // Implicit Euler is first order, DIRK-CG2 second (rigid body, exact Newton).
  const order = (integrator) => wp.series.find((x) => x.choice.integrator === integrator && x.choice.method === 'newton-group').fitted_order;
  assert.ok(Math.abs(order('implicit-euler') - 1) < 0.25, `implicit Euler p = ${order('implicit-euler')}`);
  assert.ok(Math.abs(order('dirk-cg2') - 2) < 0.35, `DIRK-CG2 p = ${order('dirk-cg2')}`);
  // The lines join each series' h in order: the plotted CPU times (y) of series i are its points by decreasing h.
  const plotted = await page.evaluate(() => window.__lienewtonCharts?.['work-precision-chart']);
  wp.series.forEach((ser, i) => {
    const expected = ser.points.map((p, j) => ({ ...p, cpu_seconds: median(answers.map((a) => a.series[i].points[j].cpu_seconds)) }))
      .filter((p) => p.cpu_seconds > 0 && p.global_error > 0).sort((a, b) => b.h - a.h).map((p) => p.cpu_seconds);
    assert.deepEqual(plotted.cpu[i], expected);
    assert.deepEqual(plotted.styles[i], { color: catalog.series_styles[i].color, marker: catalog.series_styles[i].marker });
  });
  // Clicking a legend entry hides its line; clicking again shows it.
  const entry = panel.locator('#work-precision-chart .u-legend .u-series').first();
  await entry.click();
  assert.match(await entry.getAttribute('class'), /u-off/);
  await entry.click();
  assert.doesNotMatch(await entry.getAttribute('class'), /u-off/);
  // Hover over a marker reads back that point's h, CPU time, error and iterations. The energy runs end first: the
  // status line above the chart changes while they run, and a line more would move the chart from under the mouse.
  await panel.locator('#energy-table tbody tr').nth(ticked - 1).waitFor();
  await page.locator('#work-precision-chart').scrollIntoViewIfNeeded();
  const at = await page.evaluate(() => window.__lienewtonCharts['work-precision-chart'].firstMarker());
  await page.mouse.move(at.x + 20, at.y + 20);
  await page.mouse.move(at.x, at.y, { steps: 4 });
  await page.locator('#work-precision-hover', { hasText: 'iterations,' }).or(page.locator('#work-precision-hover', { hasText: / iterations$/ })).first().waitFor();
  const hover = await text('#work-precision-hover');
  assert.match(hover, /h = .*solver CPU time .*global error .*iterations/);
  assert.equal(await page.locator('#work-precision-chart').getAttribute('data-series'), String(ticked));
  assert.equal(await page.locator('#energy-chart').getAttribute('data-series'), String(ticked));
  // The rigid body's motion in the chosen run: the slider names each frame's time, step and energy error.
  const energyRequest = { problem: 'rigid-body', n: 3, t_end: 1, tol: 1e-13, max_iterations: 100, seed: 1, h: 0.125 };
  await page.locator('#trajectory-motion[data-frames]').waitFor();
  const motionSent = page.waitForRequest((r) => r.url().endsWith('/api/v1/render/motion'));
  await panel.locator('#trajectory-motion-run').selectOption({ index: 1 });
  const sent = JSON.parse((await motionSent).postData());
  const choice = wp.series[1].choice;
  const run = (await api('/api/v1/integrate', { ...energyRequest, ...choice })).body;
  // Every one of the 8 steps is a frame (fewer than the animation's 100).
  await page.waitForFunction(() => document.querySelector('#trajectory-motion')?.dataset.frames === '9');
  for (const k of [3, 0, run.steps.length]) {
    await page.locator('#trajectory-motion-slider').fill(String(k));
    const energy = k ? run.steps[k - 1].energy : run.initial_energy;
    assert.equal(await text('#trajectory-motion-readout'),
      `step ${k}, t = ${k * 0.125} (frame ${k}): energy \u2212 energy(0) = ${(energy - run.initial_energy) === 0 ? '0' : (energy - run.initial_energy).toExponential(3)}`);
    assert.equal(await sameMotionFrame(page, 'trajectory-motion', sent), k);
  }
  assert.equal(sent.kind, 'integrate');
  await shot('speed');
});

test('a basin map streams in, matches the API pixel by pixel, and a pixel opens as a solve with y0', async () => {
  await tab('Basins');
  const panel = page.locator('#basins');
  for (const [name, v] of [['n', '3'], ['h', '4'], ['size', '24']]) await panel.locator(`[name="${name}"]`).fill(v);
  await panel.getByRole('checkbox', { name: 'Fixed point (1.2)' }).uncheck();
  const sent = page.waitForRequest((r) => r.url().endsWith('/api/v1/basins'));
  await panel.getByRole('button', { name: 'Run' }).click();
  const request = JSON.parse((await sent).postData());
  await page.waitForFunction(() => document.querySelector('#basin-img')?.naturalWidth > 0);
  await panel.locator('#basins-png > summary').click();  // the PNG repeats the canvases: folded
  await pngsShownUnscaled(page, '#basin-img', 1);
  await panel.locator('#basins-png > summary').click();
  const { status, body: map } = await api('/api/v1/basins', request);
  assert.equal(status, 200);
  assert.equal(map.rows.length, 24);
  // The summary table says what the API says.
  for (const m of map.methods) {
    const row = panel.locator(`.basin-summary tr[data-method="${m.method}"] td`);
    assert.equal(await row.nth(0).innerText(), `${(100 * m.converged_fraction).toFixed(1)}%`);
    assert.equal(Number(await row.nth(1).innerText()), m.basins);
  }
  // Every pixel of every canvas: failures in their status colour, converged pixels in their root's hue.
  const catalog = (await (await fetch(base + '/openapi.json')).json())['x-lienewton'];
  const statusColor = Object.fromEntries(catalog.enums.status.map((s) => [s.value, s.color]));
  const shown = await page.evaluate(() => [...document.querySelectorAll('#basin-maps canvas')].map((c) =>
    Array.from(c.getContext('2d').getImageData(0, 0, c.width, c.height).data)));
  const rgb = (css) => (css.startsWith('#') ? [1, 3, 5].map((i) => parseInt(css.slice(i, i + 2), 16)) : css.match(/\d+/g).map(Number));
  let converged = 0;
  map.methods.forEach((m, k) => {
    for (const row of map.rows) {
      const per = row.methods[k];
      for (let c = 0; c < 24; c += 1) {
        const at = ((23 - row.row) * 24 + c) * 4;
        const px = shown[k].slice(at, at + 3);
        if (per.status[c] !== 'converged') {
          assert.deepEqual(px, rgb(statusColor[per.status[c]]), `${m.method} row ${row.row} col ${c} ${per.status[c]}`);
          continue;
        }
        converged += 1;
        const hue = rgb(catalog.colors.basin_roots[per.root[c] % catalog.colors.basin_roots.length]);
        const scale = px.map((v, i) => (hue[i] ? v / hue[i] : 1));  // one shade factor for all three channels
        assert.ok(Math.max(...scale) - Math.min(...scale) < 0.05, `${m.method} row ${row.row} col ${c}: ${px} vs root ${hue}`);
      }
    }
  });
  assert.ok(converged > 0);
  await shot('basins');
  // A pixel inside a basin (its neighbours reached the same root) opens as a solve from its start: same root.
  const k = 0;
  const inside = [];
  for (let r = 1; r < 23; r += 1) for (let c = 1; c < 23; c += 1) {
    const root = (rr, cc) => map.rows[rr].methods[k].root[cc];
    if (root(r, c) !== null && [[-1, 0], [1, 0], [0, -1], [0, 1]].every(([dr, dc]) => root(r + dr, c + dc) === root(r, c))) inside.push([r, c]);
  }
  assert.ok(inside.length > 0, 'no pixel inside a basin');
  const [r, c] = inside[0];
  const canvas = panel.locator('canvas').nth(k);
  const box = await canvas.boundingBox();
  const solveSent = page.waitForRequest((q) => q.url().endsWith('/api/v1/solve'));
  await canvas.click({ position: { x: (c + 0.5) * box.width / 24, y: (23 - r + 0.5) * box.height / 24 } });
  assert.equal(await page.getByRole('tab', { name: 'Solve' }).getAttribute('aria-selected'), 'true');
  const solve = JSON.parse((await solveSent).postData());
  assert.equal(solve.method, map.methods[k].method);
  assert.equal(solve.y0.length, 3);
  await page.locator('#solve [data-result="iterations"]').waitFor();
  const { body: result } = await api('/api/v1/solve', solve);
  assert.equal(result.status, 'converged');
  const root = map.roots[map.rows[r].methods[k].root[c]].y;
  const distance = Math.hypot(...result.y.flat().map((v, i) => v - root.flat()[i]));
  assert.ok(distance < 1e-9, `the opened solve reached another root (${distance})`);
  assert.notEqual(await page.locator('#solve textarea[name="y0"]').inputValue(), '');
});

test('after every panel has run, none shows "undefined"', everyPanelReadsWell);

// docs/screenshots/ holds copies of these (README): each panel after its run, at a laptop and a phone size.
test('screenshots of every panel at 1440x900 and 390x844', async () => {
  for (const [w, hgt] of [[1440, 900], [390, 844]]) {
    await page.setViewportSize({ width: w, height: hgt });
    for (const [name, id] of [['Solve', 'solve'], ['Compare', 'compare'], ['Stability map', 'stability'], ['Basins', 'basins'],
      ['Speed vs accuracy', 'speed']]) {
      await tab(name);
      await page.evaluate(() => window.scrollTo(0, 0));
      await page.waitForTimeout(150); // charts follow the new width on the next frame
      await shot(`${id}-${w}x${hgt}`);
      // Each legend entry is one piece: its marker on the first line of its label.
      const apart = await page.evaluate((panel) => [...document.querySelectorAll(`#${panel} .u-legend .u-series`)]
        .filter((s) => s.querySelector('.u-marker') && s.offsetParent !== null)
        .map((s) => [s.querySelector('.u-marker').getBoundingClientRect(), s.querySelector('.u-label').getBoundingClientRect(), s.innerText])
        .filter(([m, l]) => m.bottom <= l.top || m.top >= l.bottom).map(([, , t]) => t), id);
      assert.deepEqual(apart, [], `${id} at ${w}x${hgt}: legend markers apart from their labels`);
    }
  }
  await page.setViewportSize({ width: 1280, height: 860 });
});

test('on a touch phone a first tap shows a cell, a second tap opens it', async () => {
  const phone = await openPage(browser, { width: 390, height: 844 }, consoleErrors, { console: false, hasTouch: true, isMobile: true });
  await phone.goto(base + '/#stability');
  const panel = phone.locator('#stability');
  for (const [name, v] of [['n_lo', '2'], ['n_hi', '3'], ['k_lo', '0'], ['k_hi', '1']]) {
    await panel.locator(`input[name="${name}"]`).fill(v);
  }
  await panel.getByRole('button', { name: 'Run' }).tap();
  await phone.waitForFunction(() => document.querySelector('#heatmap-img')?.naturalWidth > 0);
  // Too narrow for the methods side by side: one heatmap per method, each as wide as the panel.
  const methods = await panel.locator('input[name="methods"]:checked').count();
  await panel.locator('#stability-png > summary').tap();
  await pngsShownUnscaled(phone, '#stability .heatmap img', methods);
  const cell = panel.locator('.cell[data-method="newton-group"][data-n="3"][data-h="2"]');
  await cell.tap();
  assert.equal(await phone.locator('#cell-details [data-detail="n"]').innerText(), '3');
  assert.equal(await phone.getByRole('tab', { name: 'Stability map' }).getAttribute('aria-selected'), 'true');
  await phone.screenshot({ path: join(shots, 'stability-phone.png'), fullPage: true });
  await cell.tap();
  assert.equal(await phone.getByRole('tab', { name: 'Solve' }).getAttribute('aria-selected'), 'true');
  await phone.locator('#solve [data-result="iterations"]').waitFor();
  await phone.screenshot({ path: join(shots, 'solve-phone.png'), fullPage: true });
  await phone.close();
});

// After the screenshots, so that they show the paper's setup.
test('the stability map shows a Newton variant and continuation beside the paper\'s methods', async () => {
  await tab('Stability map');
  const panel = page.locator('#stability');
  await panel.getByLabel('Differential').selectOption('exact');
  await panel.locator('details.folded > summary', { hasText: 'More options' }).click();
  await panel.getByLabel('Newton variant').selectOption('line-search');
  await panel.getByLabel('Continuation in h').selectOption('true');
  await panel.getByLabel('Multistart').fill('16');
  for (const [name, v] of [['n_lo', '3'], ['n_hi', '3'], ['k_lo', '3'], ['k_hi', '6']]) {
    await panel.locator(`input[name="${name}"]`).fill(v);
  }
  const sent = page.waitForRequest(sweepOf(1, 4));
  // The run's end, as the page marks it: the form busy from the click, then no longer.
  await page.evaluate(() => {
    const form = document.querySelector('#stability form');
    window.stabilityRunEnded = new Promise((resolve) => {
      let began = false;
      new MutationObserver((_, observer) => {
        if (form.getAttribute('aria-busy') === 'true') began = true;
        else if (began) { observer.disconnect(); resolve(); }
      }).observe(form, { attributes: true, attributeFilter: ['aria-busy'] });
    });
  });
  await panel.getByRole('button', { name: 'Run' }).click();
  const request = JSON.parse((await sent).postData());
  assert.equal(request.globalization, 'line-search');
  assert.equal(request.continuation, true);
  assert.equal(request.multistart, 16);
  const { body: variant } = await api('/api/v1/sweep', request);
  const { body: paper } = await api('/api/v1/sweep', { ...request, globalization: 'none', continuation: false, multistart: 0 });
  // The grid once this run has ended (a cell of the previous grid with the same method, n and h keeps that grid's
  // status until this run's record replaces it).
  await page.evaluate(() => window.stabilityRunEnded);
  // A live re-run of the edited form may end first (its busy mark is the one seen): wait, bounded, until the
  // clicked run's cells are drawn, then check each.
  await page.waitForFunction((cells) => cells.every((c) => document.querySelector(
    `#stability .cell[data-method="${c.method}"][data-n="${c.n}"][data-h="${c.h}"]`)?.getAttribute('data-status') === c.status),
  variant.cells, { timeout: 60000 }).catch(() => { /* the assertions below name the cell that differs */ });
  for (const cell of variant.cells) {
    const loc = panel.locator(`.cell[data-method="${cell.method}"][data-n="${cell.n}"][data-h="${cell.h}"]`);
    assert.equal(await loc.getAttribute('data-status'), cell.status, `status of ${JSON.stringify(cell)}`);
  }
  await page.waitForFunction(() => document.querySelector('#heatmap-img')?.naturalWidth > 0);
  // The variant is not the paper's method under another name: the cells differ (continued cells cost more
  // iterations in total, and some converge only continued).
  assert.ok(variant.cells.some((c, i) => c.status !== paper.cells[i].status || c.iterations !== paper.cells[i].iterations));
  // A cell opens in Solve with the same variant, and the solve sent carries it.
  const cell = variant.cells[0];
  const solveSent = page.waitForRequest((r) => r.url().endsWith('/api/v1/solve'));
  await panel.locator(`.cell[data-method="${cell.method}"][data-n="${cell.n}"][data-h="${cell.h}"]`).click();
  const solveRequest = JSON.parse((await solveSent).postData());
  assert.equal(solveRequest.globalization, 'line-search');
  assert.equal(solveRequest.continuation, true);
  assert.equal(solveRequest.multistart, 16);
  await page.locator('#solve [data-result="iterations"]').waitFor();
  assert.equal(await page.locator('#solve select[name="continuation"]').inputValue(), 'true');
  // Back to the paper's setup for the tests after this one.
  await page.locator('#solve details.folded > summary', { hasText: 'More options' }).click();
  await page.locator('#solve select[name="globalization"]').selectOption('none');
  await page.locator('#solve select[name="continuation"]').selectOption('false');
  await tab('Stability map');
  await panel.getByLabel('Newton variant').selectOption('none');
  await panel.getByLabel('Continuation in h').selectOption('false');
  await panel.getByLabel('Multistart').fill('0');
});

test('no console errors beyond the deliberate bad request, nothing fetched from outside', () => {
  const unexpected = consoleErrors.filter((m) => !/status of 4(00|22)/.test(m));
  assert.deepEqual(unexpected, []);
  assert.deepEqual(external, []);
  assert.deepEqual(cspViolations, [], 'the dashboard did something its Content-Security-Policy forbids');
});
