// Presets, live results, the stability map's key and chart export, end to end against the real server:
//   node tests/browser/presets.test.mjs <server-binary> <web-root> <screenshot-dir>
// Each preset opened from its link shows its result without Run; a cheap panel runs again as its h slider moves
// and a map whose settings changed is marked stale; the page's address of a result opens with that result; the
// stability key lists only the statuses its grid shows, in colours off the converged ramp, next to the grid on a
// phone, and a tapped cell's card comes into view; every chart saves as PNG and SVG.
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { join } from 'node:path';
import { after, before, test } from 'node:test';
import { launchChromium, openPage, startServer, stopAll, testArguments, watchdog } from './harness.mjs';

const { binary, webRoot, shots } = testArguments('presets.test.mjs');
watchdog(880_000);  // Figures 5.1 and 5.2 are two full sweeps: minutes under the sanitizers

let browser; let page; let base;
const errors = [];

before(async () => {
  base = (await startServer(binary, webRoot)).base;
  browser = await launchChromium();
  // Figure 5.1 is a 882-cell sweep: minutes in the sanitizer build.
  page = await openPage(browser, { width: 1440, height: 900 }, errors, { timeoutMs: 120_000 });
});
after(stopAll);

const finished = (id) => page.waitForFunction((panel) => {
  const out = document.querySelector(`#${panel} .output`);
  return out?.dataset.runMs !== undefined && document.querySelector(`#${panel} form`).getAttribute('aria-busy') !== 'true';
}, id);

// Opens an address and waits until the panel it names has run by itself: returns the ms from load to result.
async function openWithResult(href) {
  let runs = 0;
  const count = (r) => { if (/\/api\/v1\/(solve|sweep|work-precision|integrate)$/.test(new URL(r.url()).pathname)) runs += 1; };
  page.on('request', count);
  await page.goto('about:blank');
  const t0 = Date.now();
  await page.goto(new URL(href, base).href);
  const id = new URL(href, base).hash.slice(1);
  await finished(id);
  const ms = Date.now() - t0;
  page.off('request', count);
  assert.ok(runs > 0, `${href}: nothing was run`);
  assert.equal(await page.locator(`#${id} .form-error`).first().innerText(), '', `${href}: the run failed`);
  return { id, ms, panel: page.locator(`#${id}`) };
}

test('each preset opens from its link with its result, without Run', async () => {
  await page.goto(base + '/');
  await page.locator('#presets a[data-preset]').first().waitFor({ state: 'attached' });
  const presets = await page.locator('#presets a[data-preset]').evaluateAll((as) => as.map((a) => ({ id: a.dataset.preset, href: a.getAttribute('href'), text: a.textContent })));
  assert.deepEqual(presets.map((p) => p.text), ['Figure 5.1', 'Figure 5.2', 'Newton vs fixed point at h = 4',
    'The heavy-top benchmark', 'The stiff body']);
  const times = [];
  // The paper's full grids and the heavy-top benchmark take 20 to 45 s each in a Release build: the sanitizer build
  // (LIENEWTON_SANITIZED, set by CMake) checks their links only, and opens the cheap presets with their results.
  const slow = new Set(['Figure 5.1', 'Figure 5.2', 'The heavy-top benchmark']);
  for (const p of presets) {
    assert.match(p.href, /[?&]run=1(&|#)/);
    if (process.env.LIENEWTON_SANITIZED && slow.has(p.text)) continue;
    const { id, ms, panel } = await openWithResult(p.href);
    times.push(`${p.text}: ${ms} ms`);
    if (id === 'stability') {
      // Every cell of the paper's grid is drawn, at the paper's tolerance.
      assert.equal(await panel.locator('input[name="tol"]').inputValue(), '1e-13');
      assert.equal(await panel.locator('.cell.pending').count(), 0);
      assert.equal(await panel.locator('.cell').count(), 3 * 14 * 21);
    } else if (id === 'compare') {
      // The lesson: at h = 4 Newton converges and the fixed point does not.
      const rows = await panel.locator('#compare-table tbody tr').evaluateAll((trs) => trs.map((tr) => [tr.dataset.method ?? tr.cells[0].innerText, tr.querySelector('.badge')?.dataset.status]));
      const fixed = rows.filter(([m]) => /fixed/i.test(m));
      const newton = rows.filter(([m]) => !/fixed/i.test(m));
      assert.ok(fixed.length && fixed.every(([, s]) => s !== 'converged'), JSON.stringify(rows));
      assert.ok(newton.length && newton.some(([, s]) => s === 'converged'), JSON.stringify(rows));
    } else {
      assert.ok(Number(await panel.locator('#work-precision-chart').getAttribute('data-points')) > 0);
    }
    // The address still asks for the result it shows.
    assert.equal(new URL(page.url()).searchParams.get('run'), '1');
  }
  console.log(`click-to-result per preset (load to result, 1440x900): ${times.join('; ')}`);
  assert.deepEqual(errors, []);
});

test('a cheap panel runs again as the h slider moves; a map whose settings changed is marked stale', async () => {
  const { panel, ms } = await openWithResult('/?run=1#solve');
  console.log(`Solve from its link: ${ms} ms`);
  assert.equal(await panel.locator('.stale-note').isHidden(), true);
  const sent = page.waitForRequest((r) => r.url().endsWith('/api/v1/solve') && JSON.parse(r.postData()).h === 4);
  await panel.locator('input.log-slider').fill('2');
  await sent;
  await page.waitForFunction(() => document.querySelector('#solve .output').dataset.stale === 'false'
    && document.querySelector('#solve form').getAttribute('aria-busy') !== 'true'
    && document.querySelector('#solve-result [data-result="iterations"]'));
  const q = new URL(page.url()).searchParams;
  assert.deepEqual([q.get('h'), q.get('run')], ['4', '1'], 'the address opens with the result shown');

  // A small map; then a new N range: the grid stays, marked as the previous settings', and the address no longer
  // asks for a run.
  await page.goto(`${base}/?n_hi=4&k_lo=-2&k_hi=2&run=1#stability`);
  await finished('stability');
  const stability = page.locator('#stability');
  await stability.locator('input[name="n_hi"]').fill('6');
  await stability.locator('.stale-note').waitFor();
  assert.equal(await stability.locator('.output').getAttribute('data-stale'), 'true');
  assert.equal(new URL(page.url()).searchParams.get('run'), null);
  await shot(page, 'stability-stale');
  assert.deepEqual(errors, []);
});

// The renderer's viridis, sampled from the catalog the page uses: a failure colour must not be near any of it.
async function rampDistance(colors) {
  return page.evaluate((list) => {
    const stops = window.__catalogViridis;
    const rgb = (css) => css.match(/\d+/g).slice(0, 3).map(Number);
    return list.map((c) => Math.min(...stops.map((s) => Math.hypot(...rgb(c).map((v, k) => v - s[k])))));
  }, colors);
}

test('the stability key lists only the statuses the grid shows, each off the converged ramp', async () => {
  await page.goto(`${base}/?n_hi=8&k_lo=-4&k_hi=6&run=1#stability`);
  await finished('stability');
  const panel = page.locator('#stability');
  const statuses = await panel.locator('.cell').evaluateAll((cs) => [...new Set(cs.map((c) => c.dataset.status))]);
  const keyed = await panel.locator('#stability-legend li[data-status]').evaluateAll((ls) => ls.map((l) => l.dataset.status));
  assert.deepEqual(keyed.sort(), statuses.filter((s) => s !== 'converged').sort());
  assert.ok(keyed.length > 0, 'this grid has failures to key');
  assert.equal(await panel.locator('#stability-legend li', { hasText: '(0)' }).count(), 0);
  // Each failure swatch is far (RGB distance) from every shade of the iteration ramp.
  await page.evaluate(async () => { window.__catalogViridis = (await (await fetch('/openapi.json')).json())['x-lienewton'].colors.viridis; });
  const swatches = await panel.locator('#stability-legend li[data-status] .swatch').evaluateAll((ss) => ss.map((s) => getComputedStyle(s).backgroundColor));
  for (const [i, d] of (await rampDistance(swatches)).entries()) assert.ok(d > 40, `${keyed[i]} ${swatches[i]} is ${d.toFixed(1)} from the ramp`);
  assert.deepEqual(errors, []);
});

test('on a phone the key is next to its grid and a tapped cell brings its card into view', async () => {
  const phone = await browser.newContext({ viewport: { width: 390, height: 844 }, hasTouch: true, isMobile: true });
  const p = await phone.newPage();
  p.setDefaultTimeout(120_000);
  await p.goto(`${base}/?n_hi=8&k_lo=-4&k_hi=6&run=1#stability`);
  await p.waitForFunction(() => document.querySelector('#stability .output')?.dataset.runMs !== undefined);
  const box = async (sel) => p.locator(sel).first().boundingBox();
  const key = await box('#stability-legend');
  const grid = await box('#stability-grids');
  // Above the grids, touching them: not screens away.
  assert.ok(key.y + key.height <= grid.y + 1 && grid.y - (key.y + key.height) < 40, JSON.stringify({ key, grid }));
  await p.locator('#stability-grids').scrollIntoViewIfNeeded();
  await shot(p, 'stability-phone-key');
  await p.locator('#stability .cell:not(.pending)').first().tap();
  await p.waitForFunction(() => {
    const r = document.querySelector('#cell-details').getBoundingClientRect();
    return r.top >= 0 && r.bottom <= innerHeight + 1 && document.querySelector('#cell-details [data-detail="n"]');
  });
  await phone.close();
});

async function saved(panel, chartId, kind) {
  const button = panel.locator(`#${chartId} + .chart-export [data-export="${kind}"]`);
  const [file] = await Promise.all([page.waitForEvent('download'), button.click()]);
  assert.equal(file.suggestedFilename(), `${chartId}.${kind}`);
  return readFileSync(await file.path());
}

test('every chart saves as PNG and SVG', async () => {
  const charts = { solve: ['solve-chart'], compare: ['compare-time-chart', 'compare-chart'],
    speed: ['work-precision-chart', 'energy-chart'], motion: ['motion-state', 'motion-drift'] };
  const linear = new Set(['motion-state']);  // omega(t) is signed: a linear axis
  for (const [id, ids] of Object.entries(charts)) {
    const { panel } = await openWithResult(`/?run=1#${id}`);
    for (const chartId of ids) {
      const series = Number(await panel.locator(`#${chartId}`).getAttribute('data-series'));
      const png = await saved(panel, chartId, 'png');
      assert.deepEqual([...png.subarray(0, 8)], [137, 80, 78, 71, 13, 10, 26, 10], `${chartId}: a PNG`);
      const width = png.readUInt32BE(16); const height = png.readUInt32BE(20);
      assert.ok(width >= 280 && height >= 200, `${chartId}: ${width}x${height}`);
      const svg = (await saved(panel, chartId, 'svg')).toString('utf8');
      const parsed = await page.evaluate((text) => {
        const doc = new DOMParser().parseFromString(text, 'image/svg+xml');
        if (doc.querySelector('parsererror')) return { error: doc.querySelector('parsererror').textContent };
        return { series: new Set([...doc.querySelectorAll('polyline[data-series]')].map((l) => l.dataset.series)).size,
          texts: [...doc.querySelectorAll('text')].map((t) => t.textContent) };
      }, svg);
      assert.equal(parsed.error, undefined, `${chartId}: ${parsed.error}`);
      assert.equal(parsed.series, series, `${chartId}: one line per series`);
      if (linear.has(chartId)) assert.ok(parsed.texts.some((t) => /^-?\d+(\.\d+)?$/.test(t)), `${chartId}: tick labels in the SVG`);
      else assert.ok(parsed.texts.some((t) => /^1e-?\d+$/.test(t)), `${chartId}: log tick labels in the SVG`);
    }
  }
  assert.deepEqual(errors, []);
});

test('a program on SE(3) with a wrong line gets an error marker at the line the server reports', async () => {
  await page.goto(`${base}/#solve`);
  const panel = page.locator('#solve');
  await panel.locator('details.folded', { hasText: 'Your own g' }).locator('summary').click();
  await panel.getByLabel('Group of your g').selectOption('SE');
  // Line 3 builds a 3 x 3 g where SE(3)'s y is 4 x 4.
  const program = "R = y(1:3,1:3);\nw = R' * [0; 0; 1];\ng = [0 -w(3) w(2); w(3) 0 -w(1); -w(2) w(1) 0]";
  await panel.locator('textarea[name="g"]').fill(program);
  // The gutter numbers every line.
  assert.deepEqual((await panel.locator('.code-gutter .line').allInnerTexts()).slice(0, 3).map((t) => t.trim()), ['1', '2', '3']);
  const answered = page.waitForResponse((r) => r.url().endsWith('/api/v1/solve'));
  await panel.getByRole('button', { name: 'Run' }).click();
  const { error } = await (await answered).json();
  assert.equal(error.field, 'g');
  assert.equal(error.line, 3);
  await panel.locator('.code-editor[data-error-line="3"]').waitFor();
  assert.deepEqual(await panel.locator('.code-gutter .line.error').allInnerTexts(), ['3']);
  assert.match(await panel.locator('[data-field="g"] .field-error').innerText(), /^line 3, column \d+: /);
  // The caret is on the reported line and column.
  const caret = await panel.locator('textarea[name="g"]').evaluate((t) => t.selectionStart);
  assert.equal(caret, program.split('\n').slice(0, 2).join('\n').length + 1 + error.column - 1);
  await shot(page, 'solve-program-error');
  // Typing clears the marker.
  await panel.locator('textarea[name="g"]').press('End');
  await panel.locator('textarea[name="g"]').press('Space');
  assert.equal(await panel.locator('.code-gutter .line.error').count(), 0);
});

test('the heavy top and the stiff body can be edited as programs on SO(3)xR^3, and solve', async () => {
  errors.length = 0;  // the 422 of the test before is the page's console error, rightly
  for (const problem of ['heavy-top', 'stiff-body']) {
    await page.goto(`${base}/?problem=${problem}#solve`);
    const panel = page.locator('#solve');
    await panel.locator('details.folded', { hasText: 'Your own g' }).locator('summary').click();
    await panel.getByRole('button', { name: 'Edit the problem as a program' }).click();
    assert.ok((await panel.locator('textarea[name="g"]').inputValue()).length > 50, `${problem}: a program`);
    assert.equal(await panel.getByLabel('Group of your g').inputValue(), 'SOxR');
    const sent = page.waitForRequest((r) => r.url().endsWith('/api/v1/solve'));
    await panel.getByRole('button', { name: 'Run' }).click();
    const body = JSON.parse((await sent).postData());
    assert.equal(body.group, 'SOxR');
    assert.ok(body.g && body.parameters, `${problem}: g and its parameters sent`);
    await panel.locator('#solve-result [data-result="status"] .badge').waitFor();
    // A root to rounding: the stiff spring (k = 1e4) puts tol 1e-13 below the rounding floor, which is "stagnated".
    const status = await panel.locator('#solve-result [data-result="status"] .badge').getAttribute('data-status');
    assert.ok(['converged', 'stagnated'].includes(status), `${problem}: ${status}`);
    assert.ok(Number(await panel.locator('#solve-result [data-result="residual"]').innerText()) < 1e-9);
    // The iterates' motion draws too.
    await page.locator('#solve-motion[data-frames]').waitFor();
  }
  assert.deepEqual(errors, []);
});

test('parameters written as expressions of constants (pi/4, 0.1*eye(3)) are evaluated by the server', async () => {
  errors.length = 0;
  const g = 'g = a * (J*y - (J*y)\')';
  const run = async (params) => {
    await page.goto(`${base}/?${new URLSearchParams({ g, parameters: JSON.stringify(params) })}#solve`);
    const panel = page.locator('#solve');
    const answered = page.waitForResponse((r) => r.url().endsWith('/api/v1/solve'));
    await panel.getByRole('button', { name: 'Run' }).click();
    return { panel, response: await answered };
  };
  const { panel, response } = await run({ a: 'pi/4', J: '0.1*eye(3)' });
  assert.equal(response.status(), 200);
  // The table shows them as written.
  assert.deepEqual(await panel.getByLabel('Parameter value (MATLAB notation)').evaluateAll((xs) => xs.map((x) => x.value)),
    ['pi/4', '0.1*eye(3)']);
  await panel.locator('#solve-result [data-result="status"] .badge').waitFor();
  // One that reads y is refused, naming the parameter, under the table.
  const bad = await run({ a: '2*y(1,1)', J: 'eye(3)' });
  const { error } = await bad.response.json();
  assert.equal(error.field, 'parameters.a');
  await bad.panel.locator('[data-field="parameters"] .field-error', { hasText: 'parameters.a' }).waitFor();
});

async function shot(p, name) {
  const size = p.viewportSize();
  await p.screenshot({ path: join(shots, `${name}-${size.width}x${size.height}.png`) });
}
