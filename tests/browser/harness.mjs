// Starts the real lienewton server on a free loopback port and a headless Debian Chromium driven by
// playwright-core (no browser download). Everything started here is stopped by stopAll(), also on failure.
import { spawn } from 'node:child_process';
import { existsSync, mkdirSync } from 'node:fs';
import { resolve } from 'node:path';
import net from 'node:net';

const started = [];

async function loadPlaywright() {
  try {
    return await import('playwright-core');
  } catch (err) {
    throw new Error(`playwright-core is not installed (${err.code ?? err.message}). Run \`npm ci\` at the ` +
      'repository root (scripts/deps.sh test does it).');
  }
}

// The OS picks a free port for a throwaway listener; the server gets that number.
function freePort() {
  return new Promise((resolve, reject) => {
    const probe = net.createServer();
    probe.once('error', reject);
    probe.listen(0, '127.0.0.1', () => {
      const { port } = probe.address();
      probe.close(() => resolve(port));
    });
  });
}

// flags: more of the server's flags (its limits), e.g. ['--sweep-timeout', '2'].
export async function startServer(binary, webRoot, { timeoutMs = 20000, flags = [] } = {}) {
  if (!existsSync(binary)) throw new Error(`server binary not found: ${binary}`);
  const port = await freePort();
  const child = spawn(binary, ['--host', '127.0.0.1', '--port', String(port), '--web-root', webRoot, ...flags],
    { stdio: ['ignore', 'pipe', 'pipe'] });
  started.push(() => child.exitCode === null && child.kill('SIGKILL'));
  process.on('exit', () => child.exitCode === null && child.kill('SIGKILL'));
  let output = '';
  child.stdout.on('data', (d) => { output += d; });
  child.stderr.on('data', (d) => { output += d; });
  const base = `http://127.0.0.1:${port}`;
  const deadline = Date.now() + timeoutMs;
  while (Date.now() < deadline) {
    if (child.exitCode !== null) throw new Error(`server exited with ${child.exitCode}:\n${output}`);
    try {
      if ((await fetch(`${base}/livez`)).ok) return { base, child, output: () => output };
    } catch { /* not listening yet */ }
    await new Promise((r) => setTimeout(r, 100));
  }
  throw new Error(`server did not answer /livez within ${timeoutMs} ms:\n${output}`);
}

// Debian's Chromium driven by playwright-core (from the lockfile; no browser download).
export async function launchChromium() {
  const { chromium } = await loadPlaywright();
  const executablePath = ['/usr/lib/chromium/chromium', '/usr/bin/chromium'].find(existsSync);
  if (!executablePath) throw new Error('Debian chromium is not installed (apt-get install chromium).');
  const browser = await chromium.launch({ executablePath, args: ['--no-sandbox', '--disable-gpu',
    '--disable-background-networking', '--disable-component-update', '--no-first-run', '--disable-sync'] });
  started.push(() => browser.close());
  return browser;
}

export async function stopAll() {
  while (started.length) {
    try { await started.pop()(); } catch { /* already gone */ }
  }
}

// A hard stop if anything hangs, so a CTest run never leaves a server behind.
export function watchdog(ms) {
  setTimeout(async () => {
    console.error(`browser test: exceeded ${ms} ms, stopping`);
    await stopAll();
    process.exit(1);
  }, ms).unref();
  for (const signal of ['SIGINT', 'SIGTERM']) process.on(signal, async () => { await stopAll(); process.exit(1); });
}

// The test's arguments (server binary, web root, screenshot directory), resolved, with the screenshot directory
// made; a missing one ends the process with the test's usage.
export function testArguments(script) {
  const [binary, webRoot, shots] = process.argv.slice(2).map((a) => a && resolve(a));
  if (!binary || !webRoot || !shots) {
    console.error(`usage: node ${script} <server-binary> <web-root> <screenshot-dir>`);
    process.exit(2);
  }
  mkdirSync(shots, { recursive: true });
  return { binary, webRoot, shots };
}

// The motion player `id` (web/shared/motion_player.js) shows, at the frame it is on, exactly the still the API
// draws of that frame: render/motion as a PNG of the request the player sent (its view and size) at upto = the
// frame. Returns the frame compared.
export async function sameMotionFrame(page, id, sentBody) {
  const result = await page.evaluate(async ({ id, body }) => {
    const canvas = document.querySelector(`#${id}-canvas`);
    const upto = Number(document.querySelector(`#${id}`).dataset.frame);
    const res = await fetch('/api/v1/render/motion', { method: 'POST', headers: { 'Content-Type': 'application/json' },
      body: JSON.stringify({ ...body, format: 'png', upto }) });
    if (!res.ok) return { error: await res.text() };
    const still = await createImageBitmap(await res.blob());
    if (still.width !== canvas.width || still.height !== canvas.height) {
      return { error: `still ${still.width}x${still.height}, canvas ${canvas.width}x${canvas.height}` };
    }
    const other = new OffscreenCanvas(canvas.width, canvas.height);
    other.getContext('2d').drawImage(still, 0, 0);
    const a = canvas.getContext('2d').getImageData(0, 0, canvas.width, canvas.height).data;
    const b = other.getContext('2d').getImageData(0, 0, canvas.width, canvas.height).data;
    let differing = 0;
    for (let i = 0; i < a.length; ++i) differing += a[i] !== b[i];
    return { differing, upto };
  }, { id, body: sentBody });
  if (result.error) throw new Error(`#${id}: ${result.error}`);
  if (result.differing) throw new Error(`#${id} frame ${result.upto}: ${result.differing} values differ from the API's still`);
  return result.upto;
}

// A page whose uncaught exceptions and console errors are pushed onto errors (each test asserts none, or only
// those it caused). timeoutMs: the locators' default wait, long because a sanitizer build beside a parallel ctest
// is slow, not wrong. console: false leaves console errors to the caller (which filters the expected ones).
export async function openPage(browser, viewport, errors, { timeoutMs = 60_000, console = true, ...options } = {}) {
  const page = await browser.newPage({ viewport, ...options });
  page.setDefaultTimeout(timeoutMs);
  page.on('pageerror', (e) => errors.push(e.stack ?? String(e)));
  if (console) page.on('console', (m) => m.type() === 'error' && errors.push(m.text()));
  return page;
}
