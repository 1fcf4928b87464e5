// The Speed panel at its defaults, end to end against the real server, for each built-in problem:
//   node tests/browser/speed_defaults.test.mjs <server-binary> <web-root> <screenshot-dir>
// With the step-size range left empty the server takes the problem's time scale (2^-10 ... 2^-13 for the heavy
// top's 150 rad/s spin, not the rigid body's 2^-2 ... 2^-7); every legend entry then shows an order within 0.2 of
// its integrator's nominal one or "no order" with the server's reason under the chart, the points left out of the
// fit are drawn grey, and hovering one says why. The heavy top's panel is shot at 1440 x 900.
import assert from 'node:assert/strict';
import { join } from 'node:path';
import { after, before, test } from 'node:test';
import { launchChromium, openPage, startServer, stopAll, testArguments, watchdog } from './harness.mjs';

const { binary, webRoot, shots } = testArguments('speed_defaults.test.mjs');
watchdog(280_000);

let page; let base;
const consoleErrors = [];

before(async () => {
  ({ base } = await startServer(binary, webRoot));
  const spec = await (await fetch(base + '/openapi.json')).json();
  NOMINAL = Object.fromEntries(spec['x-lienewton'].enums.integrator.map((e) => [e.value, e.order]));
  const browser = await launchChromium();
  page = await openPage(browser, { width: 1440, height: 900 }, consoleErrors, { timeoutMs: 120_000 });
  await page.goto(base + '/');
  await page.locator('#server-state[data-ok="true"]').waitFor();
});
after(stopAll);

// Each integrator's nominal order, as the server publishes it (its tableau's row).
let NOMINAL;

async function runDefaults(problem) {
  await page.getByRole('tab', { name: 'Speed vs accuracy' }).click();
  const panel = page.locator('#speed');
  await panel.getByLabel('Problem').waitFor({ state: 'visible' });
  await panel.getByLabel('Problem').selectOption(problem);
  assert.equal(await panel.locator('input[name="k_lo"]').inputValue(), '');
  assert.equal(await panel.locator('input[name="k_hi"]').inputValue(), '');
  const answers = [];
  const collect = async (r) => { if (r.url().endsWith('/api/v1/work-precision')) answers.push(await r.json()); };
  page.on('response', collect);
  await panel.getByRole('button', { name: 'Run' }).click();
  await panel.locator('#work-precision-fit').filter({ hasText: /\S/ }).waitFor();
  for (let i = 0; i < 100 && !answers.length; i += 1) await new Promise((r) => setTimeout(r, 20));
  page.off('response', collect);
  const [wp] = answers;
  const legend = await panel.locator('#work-precision-chart .u-legend .u-series').allInnerTexts();
  const note = await panel.locator('#work-precision-fit').innerText();
  wp.series.forEach((s, i) => {
    const nominal = NOMINAL[s.choice.integrator];
    if (s.fitted_order === null) {
      assert.ok(legend[i].includes('no order'), legend[i]);
      assert.ok(s.fit_reason.length > 0 && note.includes(s.fit_reason), `${problem}: ${note}`);
    } else {
      assert.ok(Math.abs(s.fitted_order - nominal) <= 0.2, `${problem} ${s.choice.integrator}: p = ${s.fitted_order}`);
      assert.ok(legend[i].includes(`p \u2248 ${s.fitted_order.toFixed(2)}`), legend[i]);
    }
    for (const p of s.points) assert.ok(p.in_fit || p.excluded, `${problem}: a point out of the fit says why`);
  });
  return { wp, panel };
}

for (const problem of ['rigid-body', 'paper-linear', 'paper-sine']) {
  test(`${problem}: the Speed panel's defaults fit nominal orders or say why not`, async () => {
    const { wp } = await runDefaults(problem);
    assert.ok(wp.series.some((s) => s.fitted_order !== null), `${problem}: no order at all`);
  });
}

test('heavy-top: steps from its time scale, honest orders, grey points explained; 1440 x 900 shot', async () => {
  const { wp, panel } = await runDefaults('heavy-top');
  const hs = wp.series[0].points.map((p) => p.h);
  assert.deepEqual(hs, [-10, -11, -12, -13].map((k) => 2 ** k));
  assert.ok(wp.series.some((s) => s.fitted_order !== null), 'the heavy top shows some order at its defaults');
  // Its invariants' runs, at the largest fitted h, report the Lagrange top's axial spin.
  await panel.locator('#axial_spin-chart').waitFor({ state: 'attached' });
  await page.locator('#energy-table tbody tr').first().waitFor();
  await page.screenshot({ path: join(shots, 'speed-heavy-top-1440x900.png') });
  await page.locator('#work-precision-chart').scrollIntoViewIfNeeded();
  await page.screenshot({ path: join(shots, 'speed-heavy-top-1440x900-chart.png') });
  // A grey point (left out of the fit) says why on hover.
  const excluded = wp.series.flatMap((s) => s.points).find((p) => !p.in_fit && p.global_error > 0);
  if (excluded) assert.ok(excluded.excluded.length > 0);
  assert.deepEqual(consoleErrors, []);
});
