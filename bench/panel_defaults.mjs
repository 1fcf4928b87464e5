// Click-to-complete time of every dashboard panel with its default form: from the click on Run until the run
// has ended (the form is no longer aria-busy) and every picture the panel shows has loaded (heatmap, basin PNG,
// every frame of a motion); for the stability and basin maps also the plan's estimate made before Run. Each panel runs `repetitions` times in one page at 1440x900; prints the median, the spread and
// the machine's load average before and after, since the machine is shared. With a screenshot directory it then
// saves every panel's first screen before and after its defaults run at 1440x900 and 390x844, and every scene of
// the Motion panel at both sizes (docs/screenshots/ holds these).
//   node bench/panel_defaults.mjs <server-binary> <web-root> [repetitions=3] [screenshot-dir]
import { loadavg } from 'node:os';
import { mkdirSync } from 'node:fs';
import { join, resolve } from 'node:path';
import { launchChromium, startServer, stopAll, watchdog } from '../tests/browser/harness.mjs';

const [binary, webRoot, reps = '3', shots] = process.argv.slice(2);
if (!binary || !webRoot) {
  console.error('usage: node bench/panel_defaults.mjs <server-binary> <web-root> [repetitions] [screenshot-dir]');
  process.exit(2);
}
watchdog(1_800_000);
const median = (xs) => [...xs].sort((a, b) => a - b)[Math.floor(xs.length / 2)];
const load = () => loadavg().map((x) => x.toFixed(2)).join(' ');
// The Motion panel's scenes and their end times: long enough to show the motion, short enough to draw in seconds
// (the stiff body takes 2^13 steps per unit of time).
const SCENES = [['heavy-top', '2'], ['rigid-body', '10'], ['stiff-body', '0.5'], ['chain', '0.5']];
const PANELS = [['Solve', 'solve'], ['Compare', 'compare'], ['Stability map', 'stability'], ['Basins', 'basins'],
  ['Speed vs accuracy', 'speed'], ['Motion', 'motion']];

// The panels that plan before Run (stability map, basins): waits for the plan's estimate and returns it in
// seconds (null for the other panels).
async function planned(page, id) {
  if (!['stability', 'basins'].includes(id)) return null;
  const line = page.locator(`#${id} .live[data-estimate]`);
  await line.waitFor({ state: 'attached', timeout: 60_000 });
  return Number(await line.getAttribute('data-estimate'));
}

// Resolves to the ms from the click to a finished run with its pictures loaded; throws if the run failed.
async function clickToComplete(page, id) {
  const form = page.locator(`#${id} form.controls`);
  const t0 = await page.evaluate(() => performance.now());
  await form.getByRole('button', { name: 'Run' }).click();
  const done = await page.waitForFunction((panel) => {
    const f = document.querySelector(`#${panel} form.controls`);
    if (f.getAttribute('aria-busy') === 'true') return 0;
    const pictures = [...document.querySelectorAll(`#${panel} img[src]`)].filter((img) => img.offsetParent !== null);
    const motions = [...document.querySelectorAll(`#${panel} figure.motion`)].filter((f) => f.offsetParent !== null);
    return pictures.every((img) => img.complete && img.naturalWidth > 0) && motions.every((f) => f.dataset.frames)
      ? performance.now() : 0;
  }, id, { polling: 'raf', timeout: 600_000 });
  const ms = (await done.jsonValue()) - t0;
  const error = await form.locator('.form-error').innerText();
  if (error) throw new Error(`${id}: ${error}`);
  return ms;
}

const server = await startServer(resolve(binary), resolve(webRoot));
const browser = await launchChromium();
const page = await browser.newPage({ viewport: { width: 1440, height: 900 } });
await page.goto(server.base + '/');
await page.locator('#server-state[data-ok="true"]').waitFor();
console.log(`load average (1, 5, 15 min) before: ${load()}`);
for (const [name, id] of PANELS) {
  await page.getByRole('tab', { name }).click();
  const times = [];
  const estimate = await planned(page, id);
  for (let i = 0; i < Number(reps); i++) times.push(await clickToComplete(page, id));
  console.log(`${name}: median ${median(times).toFixed(0)} ms click to complete ` +
    (estimate === null ? '' : `(the plan estimated ${(estimate * 1e3).toFixed(0)} ms) `) +
    `(runs: ${times.map((t) => t.toFixed(0)).join(', ')} ms), load average now ${load()}`);
}
// Each panel freshly opened at each size: its first screen before Run (Run must be on it) and after its defaults
// ran (what the window shows then: on a phone the result, scrolled into view above the form).
if (shots) {
  mkdirSync(shots, { recursive: true });
  for (const [w, h] of [[1440, 900], [390, 844]]) {
    const fresh = await browser.newPage({ viewport: { width: w, height: h } });
    for (const [, id] of PANELS) {
      await fresh.goto('about:blank');
      await fresh.goto(`${server.base}/#${id}`);
      await fresh.locator('#server-state[data-ok="true"]').waitFor();
      await planned(fresh, id);
      await fresh.screenshot({ path: join(shots, `${id}-${w}x${h}-before.png`) });
      console.log(`${id} at ${w}x${h}: ${(await clickToComplete(fresh, id)).toFixed(0)} ms click to complete`);
      if (w === 1440) await fresh.evaluate(() => window.scrollTo(0, 0));
      // Charts and server PNGs follow their final width (PNGs after a 250 ms settle and a new request).
      await fresh.waitForTimeout(900);
      await fresh.waitForFunction((panel) => [...document.querySelectorAll(`#${panel} img[src]`)]
        .filter((img) => img.offsetParent !== null).every((img) => img.complete && img.naturalWidth > 0), id);
      await fresh.screenshot({ path: join(shots, `${id}-${w}x${h}.png`) });
    }
    await fresh.close();
  }
  // Every scene of the Motion panel at its middle frame, the panel's output only (scene-<problem>-<size>.png).
  for (const [w, h] of [[1440, 900], [390, 844]]) {
    const page = await browser.newPage({ viewport: { width: w, height: h } });
    await page.goto(`${server.base}/#motion`);
    await page.locator('#server-state[data-ok="true"]').waitFor();
    for (const [problem, tEnd] of SCENES) {
      await page.locator('#motion select[name="problem"]').selectOption(problem);
      await page.locator('#motion input[name="t_end"]').fill(tEnd);
      const ms = await clickToComplete(page, 'motion');
      const frames = Number(await page.locator('#motion-figure').getAttribute('data-frames'));
      await page.locator('#motion-figure-slider').fill(String(Math.floor(frames / 2)));
      await page.locator('#motion .output').screenshot({ path: join(shots, `scene-${problem}-${w}x${h}.png`) });
      console.log(`motion scene ${problem}, t_end ${tEnd}, at ${w}x${h}: ${ms.toFixed(0)} ms click to complete`);
    }
    await page.close();
  }
}
await stopAll();
process.exit(0);
