// The API reference page (web/reference.html) in Chromium against the real server:
//   node tests/browser/reference.test.mjs <server-binary> <web-root> <screenshot-dir>
// It renders the server's own /openapi.json: every operation, its README request examples as curl lines to
// this server, the defaults the server applies, each stream's records by type, the error codes and the
// deprecated field marked.
import assert from 'node:assert/strict';
import { after, before, test } from 'node:test';
import { launchChromium, openPage, startServer, stopAll, testArguments, watchdog } from './harness.mjs';

const { binary, webRoot, shots } = testArguments('reference.test.mjs');
watchdog(90_000);
let browser; let page; let server;
const errors = [];

before(async () => {
  server = await startServer(binary, webRoot);
  browser = await launchChromium();
  page = await openPage(browser, { width: 1200, height: 900 }, errors);
});
after(stopAll);

test('the reference page renders the served document', async () => {
  const doc = await (await fetch(`${server.base}/openapi.json`)).json();
  await page.goto(`${server.base}/reference.html`);
  await page.locator('#schemas').waitFor();
  for (const [path, item] of Object.entries(doc.paths)) {
    for (const op of Object.values(item)) {
      const section = page.locator(`#op-${op.operationId}`);
      assert.equal(await section.count(), 1, `operation ${op.operationId}`);
      assert.match(await section.locator('h3').innerText(), new RegExp(path.replace(/[.*+?^${}()|[\]\\]/g, '\\$&')));
    }
  }
  // The README's solve, as a curl line to this server.
  const solve = await page.locator('#op-solve').innerText();
  assert.match(solve, new RegExp(`curl -s ${server.base}/api/v1/solve -d '\\{"differential":"exact","h":0.5,`));
  // Defaults come from the document: h of a solve.
  const row = (schema, field) => page.evaluate(([s, f]) => [...document.querySelectorAll(`#schema-${s} tbody tr`)]
    .map((tr) => [...tr.cells].map((td) => td.innerText.trim())).find((cells) => cells[0].split(' ')[0] === f), [schema, field]);
  assert.equal((await row('SolveRequest', 'h'))[2], '0.5');
  assert.equal((await row('IntegrateRequest', 'problem'))[2], '"rigid-body"');
  // Streams list their records by type; the error codes are an enum; error is marked deprecated.
  assert.match(await page.locator('#schema-SolveStreamRecord').innerText(), /iteration: IterationRecord[\s\S]*error: ErrorRecord/);
  assert.match(await page.locator('#schema-ErrorDetail').innerText(), /invalid_field[\s\S]*deadline_exceeded/);
  assert.match(await page.locator('#schema-WorkPrecisionSeries').innerText(), /points\[\]\.error deprecated/);
  await page.locator('#schema-IterationRecord a').first().click();
  await page.screenshot({ path: `${shots}/reference.png` });
  assert.deepEqual(errors, []);
});
