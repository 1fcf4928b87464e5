// Share and export, end to end against the real server:
//   node tests/browser/share.test.mjs <server-binary> <web-root> <screenshot-dir>
// Every panel opened from a URL with settings shows them in its form; Run gives a result that the panel's
// "Copy as curl" command, run by a shell, reproduces through the API; both "Download" files parse and hold the
// numbers the charts and tables show. Also: Run is on the first screen at a laptop and a phone size.
import assert from 'node:assert/strict';
import { execFileSync } from 'node:child_process';
import { readFileSync } from 'node:fs';
import { after, before, test } from 'node:test';
import { launchChromium, openPage, startServer, stopAll, testArguments, watchdog } from './harness.mjs';

const { binary, webRoot, shots } = testArguments('share.test.mjs');
watchdog(120_000);

let browser; let page; let base;
const errors = [];

before(async () => {
  base = (await startServer(binary, webRoot)).base;
  browser = await launchChromium();
  page = await openPage(browser, { width: 1280, height: 860 }, errors);
});
after(stopAll);

// Opens a panel from its address and checks that the form shows every setting of the address.
async function open(id, params) {
  const q = new URLSearchParams(params);
  await page.goto('about:blank');
  await page.goto(`${base}/?${q}#${id}`);
  await page.locator('#server-state[data-ok="true"]').waitFor();
  const panel = page.locator(`#${id}`);
  for (const name of new Set(q.keys())) {
    const want = q.getAll(name);
    const shown = await panel.locator(`[name="${name}"]`).evaluateAll((cs) => (cs[0].type === 'checkbox'
      ? cs.filter((c) => c.checked).map((c) => c.value) : [cs[0].value]));
    assert.deepEqual(shown.sort(), [...want].sort(), `${id}: ${name}`);
  }
  // The address still names those settings that differ from the defaults (the page rewrites it from the form).
  const kept = [...new URL(page.url()).searchParams].map(([k, v]) => `${k}=${v}`);
  const given = [...q].map(([k, v]) => `${k}=${v}`);
  assert.ok(kept.length > 0 && kept.every((p) => given.includes(p)), `${kept} not within ${given}`);
  return panel;
}

// The panel's curl commands as the page shows them, each run by a shell: the API's answers.
async function curlAnswers(panel) {
  await panel.getByRole('button', { name: 'Copy as curl' }).click();
  const commands = (await panel.locator('.share-text[data-kind="curl"]').innerText()).trim().split('\n');
  return commands.map((c) => {
    assert.match(c, /^curl -s http:\/\/127\.0\.0\.1:\d+\/api\/v1\/[a-z-]+ -H 'Content-Type: application\/json' -d '/);
    return JSON.parse(execFileSync('sh', ['-c', c], { encoding: 'utf8', maxBuffer: 64 << 20 }));
  });
}

// "Copy request JSON": the bodies the curl commands send.
async function requestJson(panel) {
  await panel.getByRole('button', { name: 'Copy request JSON' }).click();
  return JSON.parse(await panel.locator('.share-text[data-kind="request"]').innerText());
}

async function downloaded(panel, name) {
  const [file] = await Promise.all([page.waitForEvent('download'), panel.getByRole('button', { name }).click()]);
  return { name: file.suggestedFilename(), text: readFileSync(await file.path(), 'utf8') };
}

// Both downloads: the CSV as header + rows of strings, the JSON parsed.
async function downloads(panel) {
  const csv = await downloaded(panel, 'Download CSV');
  const json = await downloaded(panel, 'Download JSON');
  assert.match(csv.name, /\.csv$/);
  assert.match(json.name, /\.json$/);
  const [head, ...rows] = csv.text.trimEnd().split('\n').map((l) => l.split(','));
  assert.ok(rows.every((r) => r.length === head.length), 'every CSV row has the header\'s columns');
  const column = (name) => rows.map((r) => r[head.indexOf(name)]);
  return { head, rows, column, json: JSON.parse(json.text) };
}

const number = (s) => (s === '' ? null : Number(s));
const charts = () => page.evaluate(() => window.__lienewtonCharts);

test('Solve from a URL: the form, the curl command and the downloads agree with the result', async () => {
  const panel = await open('solve', { n: '4', h: '2', method: 'newton-algebra', differential: 'dexpinv-1', tol: '1e-12' });
  assert.equal(await panel.locator('details.folded', { hasText: 'More options' }).getAttribute('open'), '', 'a fold with a URL value opens');
  assert.equal(await panel.locator('details.folded', { hasText: 'Your own g' }).getAttribute('open'), null);
  await panel.getByRole('button', { name: 'Run' }).click();
  await panel.locator('[data-result="iterations"]').waitFor();
  const [answer] = await curlAnswers(panel);
  assert.equal(answer.iterations, Number(await panel.locator('[data-result="iterations"]').innerText()));
  assert.equal(answer.status, await panel.locator('[data-result="status"] .badge').getAttribute('data-status'));
  assert.equal(answer.residual.toExponential(3), await panel.locator('[data-result="residual"]').innerText());
  const body = await requestJson(panel);
  assert.deepEqual([body.n, body.h, body.method, body.differential, body.tol], [4, 2, 'newton-algebra', 'dexpinv-1', 1e-12]);
  const { column, json } = await downloads(panel);
  const { columns } = (await charts())['solve-chart'];
  assert.deepEqual(column('residual').map(number), columns[0]);
  assert.deepEqual(column('iteration').map(number), answer.trace.map((t) => t.iteration));
  assert.deepEqual(json.trace.map((t) => t.residual), columns[0]);
  assert.equal(json.result.iterations, answer.iterations);
  assert.deepEqual(json.request, body);
});

test('A g(y) with parameters from a URL: the table shows them in MATLAB notation, and the curl command sends them', async () => {
  const parameters = { J: [[1, 0, 0], [0, 2, 0], [0, 0, 3]], m: [[0.6], [0.8], [0.5]] };
  const panel = await open('solve', { g: "w = J \\ (y' * m);\ng = [0 -w(3) w(2); w(3) 0 -w(1); -w(2) w(1) 0]",
    parameters: JSON.stringify(parameters) });
  assert.equal(await panel.locator('details.folded', { hasText: 'Your own g' }).getAttribute('open'), '');
  assert.deepEqual(await panel.getByLabel('Parameter value (MATLAB notation)').evaluateAll((xs) => xs.map((x) => x.value)),
    ['[1 0 0; 0 2 0; 0 0 3]', '[0.6; 0.8; 0.5]']);
  await panel.getByRole('button', { name: 'Run' }).click();
  await panel.locator('[data-result="iterations"]').waitFor();
  const [answer] = await curlAnswers(panel);
  assert.equal(answer.status, await panel.locator('[data-result="status"] .badge').getAttribute('data-status'));
  assert.equal(answer.iterations, Number(await panel.locator('[data-result="iterations"]').innerText()));
  assert.deepEqual((await requestJson(panel)).parameters, parameters);
});

test('Compare from a URL: one curl command per run, each reproducing its row', async () => {
  const panel = await open('compare', new URLSearchParams([['n', '4'], ['h', '0.25'], ['runs', 'newton-group|exact'],
    ['runs', 'fixed-point|exact']]));
  await panel.getByRole('button', { name: 'Run' }).click();
  await panel.locator('#compare-table tbody tr').nth(1).waitFor();
  const answers = await curlAnswers(panel);
  assert.equal(answers.length, 2);
  const rows = panel.locator('#compare-table tbody tr');
  for (const [i, a] of answers.entries()) {
    assert.equal(await rows.nth(i).locator('td').nth(1).innerText(), String(a.iterations));
    assert.equal(await rows.nth(i).locator('.badge').getAttribute('data-status'), a.status);
  }
  const { rows: csv, column, json } = await downloads(panel);
  const { columns } = (await charts())['compare-chart'];
  for (const [i, run] of json.entries()) {
    const mine = csv.filter((r) => r[1] === run.request.method && r[2] === run.request.differential);
    assert.deepEqual(mine.map((r) => number(r[4])), columns[i], `run ${i}: CSV residuals are the chart's`);
    assert.deepEqual(run.trace.map((t) => t.residual), columns[i]);
    assert.equal(run.result.iterations, answers[i].iterations);
  }
  assert.equal(column('run').length, columns[0].length + columns[1].length);
});

test('Stability map from a URL: the curl command\'s cells are the grid\'s, and so are the downloads\'', async () => {
  const panel = await open('stability', new URLSearchParams([['methods', 'newton-group'], ['methods', 'newton-algebra'],
    ['differential', 'exact'], ['n_lo', '3'], ['n_hi', '4'], ['k_lo', '0'], ['k_hi', '2']]));
  await panel.getByRole('button', { name: 'Run' }).click();
  await page.waitForFunction(() => document.querySelector('#heatmap-img')?.naturalWidth > 0);
  const [answer] = await curlAnswers(panel);
  assert.equal(answer.cells.length, 2 * 2 * 3);
  const grid = await panel.locator('.cell[data-status]').evaluateAll((cs) => cs.map((c) =>
    `${c.dataset.method}|${c.dataset.n}|${c.dataset.h}|${c.dataset.status}`).sort());
  assert.deepEqual(grid, answer.cells.map((c) => `${c.method}|${c.n}|${c.h}|${c.status}`).sort());
  const { rows, head, json } = await downloads(panel);
  const at = (r, k) => r[head.indexOf(k)];
  assert.deepEqual(rows.map((r) => `${at(r, 'method')}|${at(r, 'n')}|${at(r, 'h')}|${at(r, 'status')}`).sort(), grid);
  assert.deepEqual(rows.map((r) => number(at(r, 'iterations'))), answer.cells.map((c) => c.iterations));
  assert.deepEqual(json.cells.map((c) => c.iterations), answer.cells.map((c) => c.iterations));
  // Each datum once: the tables and the PNG are folded away until asked for.
  assert.equal(await panel.locator('#stability-tables').getAttribute('open'), null);
  assert.equal(await panel.locator('#stability-png').getAttribute('open'), null);
  // The picture as SVG for a paper: the server's vector copy, its caption as text.
  await panel.locator('#stability-png > summary').click();
  const svg = await downloaded(panel, 'Download SVG');
  assert.equal(svg.name, 'stability-map.svg');
  assert.match(svg.text, /^<svg xmlns="http:\/\/www.w3.org\/2000\/svg"/);
  assert.match(svg.text, />Where each method converges: paper-linear on SO\(N\)<\/text>/);  // titled by its request
  assert.match(svg.text, /N = 3\u20264 \u00b7 h = 2\u2070\u20262\u00b2/);
});

test('Basins from a URL: the curl command\'s map is the pixels downloaded and the summary shown', async () => {
  const panel = await open('basins', new URLSearchParams([['n', '3'], ['h', '4'], ['size', '12'], ['methods', 'newton-group']]));
  await panel.getByRole('button', { name: 'Run' }).click();
  await page.waitForFunction(() => document.querySelector('#basin-img')?.naturalWidth > 0);
  const [answer] = await curlAnswers(panel);
  assert.equal(answer.rows.length, 12);
  const shown = await panel.locator('.basin-summary tr[data-method="newton-group"] td').first().innerText();
  assert.equal(shown, `${(100 * answer.methods[0].converged_fraction).toFixed(1)}%`);
  const { rows, head, json } = await downloads(panel);
  assert.equal(rows.length, 12 * 12);
  const at = (r, k) => r[head.indexOf(k)];
  for (const r of rows) {
    const px = answer.rows.find((x) => x.row === Number(at(r, 'row'))).methods[0];
    const c = Number(at(r, 'column'));
    assert.equal(at(r, 'status'), px.status[c]);
    assert.equal(number(at(r, 'root')), px.root[c]);
    assert.equal(Number(at(r, 'iterations')), px.iterations[c]);
  }
  assert.deepEqual(json.methods.map((m) => [m.method, m.converged_fraction, m.basins]),
    answer.methods.map((m) => [m.method, m.converged_fraction, m.basins]));
  assert.deepEqual(json.rows.map((r) => r.methods[0].status), answer.rows.map((r) => r.methods[0].status));
  await panel.locator('#basins-png > summary').click();
  const svg = await downloaded(panel, 'Download SVG');
  // The title, wrapped between words on a narrow picture: its <text> lines read as one.
  const words = [...svg.text.matchAll(/<text[^>]*>([^<]*)<\/text>/g)].map((m) => m[1]).join(' ');
  assert.ok(words.includes('From which starts each method converges: paper-linear on SO(3), h = 2\u00b2'), words);
  assert.equal(svg.text.match(/<image /g).length, 1);  // the one method's panel
});

test('Speed from a URL: the work-precision curl command reproduces the errors charted and downloaded', async () => {
  const panel = await open('speed', new URLSearchParams([['k_lo', '-4'], ['k_hi', '-3'],
    ['choices', 'implicit-euler|newton-group|exact'], ['choices', 'dirk-cg2|newton-group|exact']]));
  await panel.getByRole('button', { name: 'Run' }).click();
  await panel.locator('#energy-table tbody tr').nth(1).waitFor({ timeout: 40_000 });
  const [wp, ...energy] = await curlAnswers(panel);
  assert.equal(wp.series.length, 2);
  assert.equal(energy.length, 2);
  const { rows, head, json } = await downloads(panel);
  const at = (r, k) => r[head.indexOf(k)];
  // Errors are deterministic: the same from the page's run and from curl's.
  assert.deepEqual(rows.map((r) => number(at(r, 'global_error'))), wp.series.flatMap((s) => s.points.map((p) => p.global_error)));
  // CPU times are the run's own: the chart plots exactly the downloaded ones.
  const { cpu } = (await charts())['work-precision-chart'];
  json.work_precision.series.forEach((s, i) => {
    const sorted = s.points.filter((p) => p.cpu_seconds > 0 && p.global_error > 0).sort((a, b) => b.h - a.h).map((p) => p.cpu_seconds);
    assert.deepEqual(cpu[i], sorted);
  });
  assert.deepEqual(json.energy_runs.map((r) => r.result.global_error), energy.map((e) => e.global_error));
});

test('Run is on the first screen of every panel at 1440x900 and 390x844', async () => {
  for (const [width, height] of [[1440, 900], [390, 844]]) {
    await page.setViewportSize({ width, height });
    for (const id of ['solve', 'compare', 'stability', 'basins', 'speed']) {
      await page.goto('about:blank');
      await page.goto(`${base}/#${id}`);
      const run = await page.locator(`#${id}`).getByRole('button', { name: 'Run' }).boundingBox();
      assert.ok(run && run.y >= 0 && run.y + run.height <= height, `${id} at ${width}x${height}: Run at ${JSON.stringify(run)}`);
    }
  }
  // On a phone, once a run has started the result is on screen, above the form, and stays there as it grows.
  await page.goto('about:blank');
  await page.goto(`${base}/#solve`);
  await page.locator('#solve').getByRole('button', { name: 'Run' }).click();
  await page.locator('#solve [data-result="iterations"]').waitFor();
  await page.locator('#solve-motion[data-frames]').waitFor();
  const [output, form] = await page.evaluate(() => ['.output', 'form'].map((s) => document.querySelector(`#solve ${s}`).getBoundingClientRect().top));
  assert.ok(Math.abs(output) < 2 && form > output, `output at ${output}, form at ${form}`);
  await page.setViewportSize({ width: 1280, height: 860 });
});

test('the page follows the system\'s dark theme', async () => {
  const background = async (colorScheme) => {
    const p = await browser.newPage({ colorScheme });
    await p.goto(`${base}/#solve`);
    await p.locator('#server-state[data-ok="true"]').waitFor();
    const rgb = await p.evaluate(() => getComputedStyle(document.documentElement).backgroundColor.match(/\d+/g).slice(0, 3).map(Number));
    await p.close();
    return rgb.reduce((a, b) => a + b, 0) / 3;
  };
  assert.ok(await background('light') > 200, 'light theme: a light page');
  assert.ok(await background('dark') < 60, 'dark theme: a dark page');
});

test('no errors in the page', () => assert.deepEqual(errors, []));
