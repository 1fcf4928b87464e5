// The Motion panel end to end against the real server:
//   node tests/browser/motion.test.mjs <server-binary> <web-root> <screenshot-dir>
// Run draws the heavy top and the rigid body as animations (render/motion, decoded frame by frame); Play steps
// through the frames, the slider scrubs, a drag turns the view and the server draws it again; the state and the
// invariants' drift are charted. Screenshots at desktop and phone sizes.
import assert from 'node:assert/strict';
import { after, before, test } from 'node:test';
import { launchChromium, loadPlaywright, startServer, stopAll, testArguments, watchdog } from './harness.mjs';

const { binary, webRoot, shots } = testArguments('motion.test.mjs');
watchdog(150_000);
let browser; let server;
const errors = [];

before(async () => {
  const { chromium } = await loadPlaywright();
  server = await startServer(binary, webRoot);
  browser = await launchChromium(chromium);
});
after(stopAll);

async function openMotion(viewport, params = {}) {
  const page = await browser.newPage({ viewport });
  page.setDefaultTimeout(60_000);  // a sanitizer build under a parallel ctest is slow, not wrong
  page.on('pageerror', (e) => errors.push(e.stack ?? String(e)));
  page.on('console', (m) => m.type() === 'error' && errors.push(m.text()));
  await page.goto(`${server.base}/?${new URLSearchParams(params)}#motion`);
  await page.locator('#server-state[data-ok="true"]').waitFor();
  return page;
}

// Runs the panel; the number of frames its animation has, and the steps the integration took.
async function run(page) {
  await page.locator('#motion button[data-role="run"]').click();
  await page.locator('#motion .live', { hasText: 'Integrating' }).waitFor();
  await page.locator('#motion-figure[data-frames]').waitFor();
  await page.locator('#motion .live', { hasText: 'from Run to picture' }).waitFor();
  const steps = Number((await page.locator('#motion .live').innerText()).match(/(\d+) steps/)[1]);
  return { frames: Number(await page.locator('#motion-figure').getAttribute('data-frames')), steps };
}

test('heavy top: play, scrub, turn, and its state against time', async () => {
  const page = await openMotion({ width: 1440, height: 900 });
  await page.locator('#motion select[name="problem"]').selectOption('heavy-top');
  const { frames } = await run(page);
  assert.equal(frames, 101);  // y(0) and the 100 frames the panel asks for
  // Play advances the frames; Pause holds one.
  await page.locator('#motion-play').click();
  await page.waitForFunction(() => Number(document.querySelector('#motion-figure').dataset.frame) >= 3);
  await page.locator('#motion-play').click();
  assert.equal(await page.locator('#motion-figure').getAttribute('data-playing'), 'false');
  // The slider scrubs to a frame and the readout says its time.
  await page.locator('#motion-slider').fill('60');
  assert.equal(await page.locator('#motion-figure').getAttribute('data-frame'), '60');
  assert.equal(await page.locator('#motion-readout').innerText(), 'frame 60 of 100');
  // A drag turns the view; the server draws it, and the frame shown stays.
  const box = await page.locator('#motion-canvas').boundingBox();
  await page.mouse.move(box.x + box.width / 2, box.y + box.height / 2);
  await page.mouse.down();
  await page.mouse.move(box.x + box.width / 2 + 100, box.y + box.height / 2 + 20, { steps: 5 });
  await page.mouse.up();
  await page.waitForFunction(() => document.querySelector('#motion-figure').dataset.azimuth === '-5');
  assert.equal(await page.locator('#motion-figure').getAttribute('data-frame'), '60');
  // omega(t): three series over the 101 frame times; the drift chart: energy, vertical momentum, axial spin.
  assert.equal(await page.locator('#motion-state').getAttribute('data-series'), '3');
  assert.equal(await page.locator('#motion-drift').getAttribute('data-series'), '3');
  // The picture is not blank: the disc's blue is somewhere in the canvas.
  const blue = await page.evaluate(() => {
    const c = document.querySelector('#motion-canvas');
    const d = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;
    let n = 0;
    for (let i = 0; i < d.length; i += 4) n += d[i + 2] > d[i] + 40 && d[i + 2] > d[i + 1] + 10;
    return n;
  });
  assert.ok(blue > 500, `${blue} bluish pixels`);
  await page.screenshot({ path: `${shots}/motion-heavy-top-1440x900.png`, fullPage: true });
  await page.close();
});

test('rigid body on a phone: its momentum on the sphere, then the chain', async () => {
  const page = await openMotion({ width: 390, height: 844 });
  await page.locator('#motion select[name="problem"]').selectOption('rigid-body');
  await page.locator('#motion input[name="t_end"]').fill('10');
  const body = await run(page);
  assert.equal(body.frames, 101, await page.locator('#motion .live').innerText());
  assert.equal(await page.locator('#motion-drift').getAttribute('data-series'), '1');  // energy only
  const width = await page.evaluate(() => document.querySelector('#motion-canvas').getBoundingClientRect().width);
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
