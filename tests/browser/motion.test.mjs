// The Motion panel end to end against the real server:
//   node tests/browser/motion.test.mjs <server-binary> <web-root> <screenshot-dir>
// Run draws the heavy top and the rigid body as animations (render/motion, decoded frame by frame); Play steps
// through the frames, the slider scrubs, a drag turns the view and the server draws it again; the state and the
// invariants' drift are charted. Screenshots at desktop and phone sizes.
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { after, before, test } from 'node:test';
import { launchChromium, openPage, sameMotionFrame, startServer, stopAll, testArguments, watchdog } from './harness.mjs';

const { binary, webRoot, shots } = testArguments('motion.test.mjs');
watchdog(200_000);
let browser; let server;
const errors = [];

before(async () => {
  server = await startServer(binary, webRoot);
  browser = await launchChromium();
});
after(stopAll);

async function openMotion(viewport, params = {}) {
  const page = await openPage(browser, viewport, errors);
  await page.goto(`${server.base}/?${new URLSearchParams(params)}#motion`);
  await page.locator('#server-state[data-ok="true"]').waitFor();
  return page;
}

// Play advances the frames, Pause holds one; the slider scrubs to frame k, which is the API's still of it; a drag
// turns the view (the server draws it again) and keeps the frame. Returns the view's azimuth after the drag.
async function playScrubTurn(page, sent, k) {
  await page.locator('#motion-figure-play').click();
  await page.waitForFunction(() => Number(document.querySelector('#motion-figure').dataset.frame) >= 3);
  await page.locator('#motion-figure-play').click();
  assert.equal(await page.locator('#motion-figure').getAttribute('data-playing'), 'false');
  await page.locator('#motion-figure-slider').fill(String(k));
  assert.equal(await page.locator('#motion-figure').getAttribute('data-frame'), String(k));
  assert.equal(await sameMotionFrame(page, 'motion-figure', sent), k);
  const turned = page.waitForRequest((r) => r.url().endsWith('/api/v1/render/motion'));
  const box = await page.locator('#motion-figure-canvas').boundingBox();
  await page.mouse.move(box.x + box.width / 2, box.y + box.height / 2);
  await page.mouse.down();
  await page.mouse.move(box.x + box.width / 2 + 100, box.y + box.height / 2 + 20, { steps: 5 });
  await page.mouse.up();
  const view = JSON.parse((await turned).postData());
  assert.equal(view.azimuth_deg, -5);  // 35 - 0.4 * 100
  await page.waitForFunction(() => document.querySelector('#motion-figure').dataset.azimuth === '-5');
  assert.equal(await page.locator('#motion-figure').getAttribute('data-frame'), String(k));
  assert.equal(await sameMotionFrame(page, 'motion-figure', view), k);
}

// Runs the panel; the number of frames its animation has, the steps the integration took, and the animation's
// request as sent.
async function run(page) {
  const motionSent = page.waitForRequest((r) => r.url().endsWith('/api/v1/render/motion'));
  await page.locator('#motion button[data-role="run"]').click();
  await page.locator('#motion .live', { hasText: 'Integrating' }).waitFor();
  await page.locator('#motion-figure[data-frames]').waitFor();
  await page.locator('#motion .live', { hasText: 'from Run to picture' }).waitFor();
  const steps = Number((await page.locator('#motion .live').innerText()).match(/(\d+) steps/)[1]);
  return { frames: Number(await page.locator('#motion-figure').getAttribute('data-frames')), steps,
    sent: JSON.parse((await motionSent).postData()) };
}

test('heavy top: play, scrub, turn, and its state against time', async () => {
  const page = await openMotion({ width: 1440, height: 900 });
  await page.locator('#motion select[name="problem"]').selectOption('heavy-top');
  const { frames, sent } = await run(page);
  assert.equal(frames, 101);  // y(0) and the motion route's default 100 frames
  // The slider names a frame's time: the server's (the animation's XMP); frame 60 of 100 over t = 2 is near 1.2.
  await playScrubTurn(page, sent, 60);
  const t = Number(await page.locator('#motion-figure').getAttribute('data-time'));
  assert.equal(await page.locator('#motion-figure-readout').innerText(), `t = ${Number(t.toPrecision(6))} (frame 60 of 100)`);
  assert.ok(Math.abs(t - 1.2) < 0.05, `frame 60 of 100 over t = 2 at t = ${t}`);
  // omega(t): three series over the 101 frame times; the drift chart: energy, vertical momentum, axial spin.
  assert.equal(await page.locator('#motion-state').getAttribute('data-series'), '3');
  // Every invariant is drawn, or said to be kept exactly (the symmetric top's axial spin can be, to the last bit:
  // J1 = J3 and chi on the axis make dw2/dt = 0 up to the rounding of two products).
  const drawn = Number(await page.locator('#motion-drift').getAttribute('data-series'));
  const exact = await page.locator('#motion-exact').isVisible() ? await page.locator('#motion-exact').innerText() : '';
  assert.ok(drawn === 3 || (drawn === 2 && exact === 'Kept exactly (drift 0 at every step): axial spin.'), `${drawn} drawn, "${exact}"`);
  // The picture is not blank: the disc's blue is somewhere in the canvas.
  const blue = await page.evaluate(() => {
    const c = document.querySelector('#motion-figure-canvas');
    const d = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;
    let n = 0;
    for (let i = 0; i < d.length; i += 4) n += d[i + 2] > d[i] + 40 && d[i + 2] > d[i + 1] + 10;
    return n;
  });
  assert.ok(blue > 500, `${blue} bluish pixels`);
  // rkmk-gauss2 at the problem's default step: within 1e-2 of the solution's scale (7.9e-4 of 150), no warning.
  assert.equal(await page.locator('#motion .live .badge.warning').count(), 0);
  await page.screenshot({ path: `${shots}/motion-heavy-top-1440x900.png`, fullPage: true });
  // Implicit Euler at the same step converges at every step over a damped path: global error 6.75 of 150, the
  // energy and the vertical momentum drifting by 5 % and 54 %. The panel says so beside the status.
  await page.locator('#motion select[name="integrator"]').selectOption('implicit-euler');
  await run(page);
  assert.match(await page.locator('#motion .live').innerText(), /^converged: /);
  const badge = (code) => page.locator(`#motion .live .badge.warning[data-warning="${code}"]`);
  assert.ok(await badge('inaccurate').isVisible());
  assert.match(await badge('inaccurate').getAttribute('title'), /^global_error .* the trajectory is not the solution's$/);
  // One badge for both drifting invariants, each named in its tooltip.
  assert.equal(await badge('invariant_drift').innerText(), '\u26a0 invariant drift (2)');
  assert.match(await badge('invariant_drift').getAttribute('title'), /^energy drifts by .*\nvertical_momentum drifts by /);
  await page.screenshot({ path: `${shots}/motion-heavy-top-warnings-1440x900.png`, fullPage: true });
  await page.close();
});

test('rigid body on a phone: its momentum on the sphere, then the chain', async () => {
  const page = await openMotion({ width: 390, height: 844 });
  await page.locator('#motion select[name="problem"]').selectOption('rigid-body');
  await page.locator('#motion input[name="t_end"]').fill('10');
  const body = await run(page);
  assert.equal(body.frames, 101, await page.locator('#motion .live').innerText());
  assert.equal(await page.locator('#motion-drift').getAttribute('data-series'), '1');  // energy only
  await playScrubTurn(page, body.sent, 30);
  // The keyboard turns it too: ArrowLeft adds 15 degrees of azimuth, and the frame stays.
  await page.locator('#motion-figure-canvas').focus();
  const keyed = page.waitForRequest((r) => r.url().endsWith('/api/v1/render/motion'));
  await page.keyboard.press('ArrowLeft');
  assert.equal(JSON.parse((await keyed).postData()).azimuth_deg, 10);  // -5 after the drag, + 15
  await page.waitForFunction(() => document.querySelector('#motion-figure').dataset.azimuth === '10');
  assert.equal(await page.locator('#motion-figure').getAttribute('data-frame'), '30');
  const width = await page.evaluate(() => document.querySelector('#motion-figure-canvas').getBoundingClientRect().width);
  assert.ok(width <= 390, `the animation fits the phone (${width} px)`);
  await page.screenshot({ path: `${shots}/motion-rigid-body-390x844.png`, fullPage: true });
  await page.locator('#motion select[name="problem"]').selectOption('chain');
  await page.locator('#motion input[name="t_end"]').fill('0.25');
  // The chain's steps come from its joints' time scale; the frames are the steps' when there are fewer than 100.
  const chain = await run(page);
  assert.equal(chain.frames, Math.min(chain.steps, 100) + 1);
  await page.close();
  assert.deepEqual(errors, []);
});

// A user's g on SE(3): a constant twist, whose motion from the start z is the screw y(t) = z exp(t g), with
// exp(t g) = [[Rz(t), p(t)], [0, 1]], p(t) = (sin t, 1 - cos t, t/2). Its state chart plots the entries that move;
// the chooser picks one, whose values are the closed form's.
test('your own g on SE(3): its bodies move, and the state chart plots the entries you choose', async () => {
  const page = await openMotion({ width: 1440, height: 900 });
  await page.locator('#motion summary', { hasText: 'Your own g(y)' }).click();
  await page.locator('#motion select[name="group"]').selectOption('SE');
  await page.locator('#motion textarea[name="g"]').fill('g = [0 -1 0 1; 1 0 0 0; 0 0 0 0.5; 0 0 0 0]');
  const { frames, sent } = await run(page);
  assert.equal(sent.group, 'SE');
  assert.ok(frames > 2, `${frames} frames`);
  // The entries that move: y(:,3) = z(:,3) stays (the rotation is about z), the last row is [0 0 0 1].
  const options = await page.locator('#motion-components option').allInnerTexts();
  assert.deepEqual(options, [1, 2, 3].flatMap((i) => [1, 2, 4].map((j) => `y(${i},${j})`)));
  assert.equal(await page.locator('#motion-state').getAttribute('data-series'), '3');
  await page.locator('#motion-components').selectOption(['y(3,4)']);
  assert.equal(await page.locator('#motion-state').getAttribute('data-series'), '1');
  assert.deepEqual(await page.locator('#motion-state .u-legend .u-series:not(.x-series) .u-label').allInnerTexts(), ['y(3,4)']);
  // What the chart draws is the closed form: y(3,4)(t) = z(3,1:3) p(t) + z(3,4), with z = y(0).
  const [file] = await Promise.all([page.waitForEvent('download'), page.locator('#motion').getByRole('button', { name: 'Download CSV' }).click()]);
  const [head, ...rows] = readFileSync(await file.path(), 'utf8').trimEnd().split('\n').map((l) => l.split(',').map(Number));
  const integration = await (await fetch(`${server.base}/api/v1/integrate`, { method: 'POST',
    headers: { 'Content-Type': 'application/json' }, body: JSON.stringify({ g: sent.g, group: 'SE', n: sent.n, integrator: sent.integrator, t_end: sent.t_end, frames: 1000 }) })).json();
  const z = integration.frames[0];
  const height = (t) => z[2][0] * Math.sin(t) + z[2][1] * (1 - Math.cos(t)) + z[2][2] * t / 2 + z[2][3];
  assert.equal(readFileSync(await file.path(), 'utf8').split('\n')[0], 't,y_3_4');
  assert.equal(head.length, 2);
  assert.equal(rows.length, integration.frame_times.length);
  rows.forEach(([t, y34], i) => {
    assert.equal(t, integration.frame_times[i]);
    assert.ok(Math.abs(y34 - height(t)) < 1e-11, `frame ${i}: y(3,4) = ${y34}, closed form ${height(t)}`);
  });
  assert.equal(await page.locator('#motion-drift p.hint').innerText(), 'This problem reports no invariants.');
  await page.screenshot({ path: `${shots}/motion-se3-program-1440x900.png`, fullPage: true });
  await page.close();
  assert.deepEqual(errors, []);
});

// The heavy top written as a program on SO(3) x R^3 has an angular velocity too: its state's w = y(4:6,7).
test('a program on SO(3) x R^3 plots its angular velocity', async () => {
  const page = await openMotion({ width: 1440, height: 900 });
  await page.locator('#motion select[name="problem"]').selectOption('heavy-top');
  await page.locator('#motion summary', { hasText: 'Your own g(y)' }).click();
  await page.locator('#motion').getByRole('button', { name: 'Edit the problem as a program' }).click();
  await page.locator('#motion input[name="t_end"]').fill('0.25');
  const { sent } = await run(page);
  assert.equal(sent.group, 'SOxR');
  assert.ok(sent.g);
  assert.equal((await page.locator('#motion-components option').first().innerText()), '\u03c9 (body angular velocity)');
  assert.deepEqual(await page.locator('#motion-components').evaluate((s) => [...s.selectedOptions].map((o) => o.value)), ['omega']);
  assert.equal(await page.locator('#motion-state').getAttribute('data-series'), '3');
  await page.close();
  assert.deepEqual(errors, []);
});
