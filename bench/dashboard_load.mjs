// Dashboard load on loopback: first contentful paint, time until the Solve form can be used (server answered,
// Run button present and enabled), and bytes on the wire, for a cold load (empty cache) and warm reloads (the
// browser revalidates its cached files: 304s carry headers only).
//   node bench/dashboard_load.mjs <server-binary> <web-root> [repetitions=7]
import { resolve } from 'node:path';
import { launchChromium, startServer, stopAll, watchdog } from '../tests/browser/harness.mjs';

const [binary, webRoot, reps = '7'] = process.argv.slice(2);
if (!binary || !webRoot) {
  console.error('usage: node bench/dashboard_load.mjs <server-binary> <web-root> [repetitions]');
  process.exit(2);
}
watchdog(300_000);
const median = (xs) => [...xs].sort((a, b) => a - b)[Math.floor(xs.length / 2)];

async function load(page, cdp, url) {
  let bytes = 0; let requests = 0; const statuses = {};
  const onResponse = (e) => {
    statuses[e.response.status] = (statuses[e.response.status] ?? 0) + 1;
    if (process.env.SHOW_URLS) console.log(e.response.status, e.response.url);
  };
  const onFinished = (e) => { bytes += e.encodedDataLength; requests += 1; };
  cdp.on('Network.responseReceived', onResponse);
  cdp.on('Network.loadingFinished', onFinished);
  await page.goto(url, { waitUntil: 'commit' });
  const usable = await page.waitForFunction(() => {
    const ok = document.querySelector('#server-state[data-ok="true"]');
    const run = document.querySelector('#solve button[type="submit"]');
    return ok && run && !run.disabled ? performance.now() : 0;
  }, null, { polling: 'raf' });
  const usableMs = await usable.jsonValue();
  await page.waitForLoadState('networkidle');
  const fcp = await page.evaluate(() => performance.getEntriesByName('first-contentful-paint')[0]?.startTime ?? NaN);
  cdp.off('Network.responseReceived', onResponse);
  cdp.off('Network.loadingFinished', onFinished);
  return { fcp, usableMs, bytes, requests, statuses };
}

const server = await startServer(resolve(binary), resolve(webRoot));
const browser = await launchChromium();
const rows = { cold: [], warm: [] };
for (let i = 0; i < Number(reps); i++) {
  const context = await browser.newContext({ viewport: { width: 1440, height: 900 } });
  const page = await context.newPage();
  const cdp = await context.newCDPSession(page);
  await cdp.send('Network.enable');
  rows.cold.push(await load(page, cdp, server.base + '/'));
  rows.warm.push(await load(page, cdp, server.base + '/'));
  await context.close();
}
for (const [kind, list] of Object.entries(rows)) {
  console.log(`${kind}: first contentful paint ${median(list.map((r) => r.fcp)).toFixed(0)} ms, ` +
    `Solve form usable ${median(list.map((r) => r.usableMs)).toFixed(0)} ms, ` +
    `${median(list.map((r) => r.bytes))} bytes in ${median(list.map((r) => r.requests))} responses ` +
    `(statuses of the last load: ${JSON.stringify(list.at(-1).statuses)}), medians of ${list.length}`);
}
await stopAll();
process.exit(0);
