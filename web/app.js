// Entry point: builds the six panels and the tab bar. Tabs follow the ARIA tabs pattern (arrow keys,
// Home/End) and the URL: the hash names the panel, the query its settings (?n=8&h=2#solve), so a panel and its
// form can be linked to and survive a reload.
import { createBasinsPanel } from './panels/basins.js';
import { createComparePanel } from './panels/compare.js';
import { createMotionPanel } from './panels/motion.js';
import { createSolvePanel } from './panels/solve.js';
import { createSpeedPanel } from './panels/speed.js';
import { createStabilityPanel } from './panels/stability.js';
import { el } from './shared/dom.js';
import { liveResult } from './shared/live.js';
import { PRESETS, presetHref } from './shared/presets.js';

const tabs = [...document.querySelectorAll('[role="tab"]')];

function select(tab, focus = true) {
  for (const t of tabs) {
    const on = t === tab;
    t.setAttribute('aria-selected', String(on));
    t.tabIndex = on ? 0 : -1;
    document.getElementById(t.getAttribute('aria-controls')).hidden = !on;
  }
  if (focus) tab.focus();
  keepInUrl(tab.getAttribute('aria-controls'));
}

// The shown panel's settings that differ from its defaults, in the query string; run=1 while the panel shows
// the result of those settings, so that the address opens with it.
function keepInUrl(id) {
  const params = panels[id]?.share.params() ?? new URLSearchParams();
  if (results[id]?.fresh()) params.set('run', '1');
  const q = params.toString();
  history.replaceState(null, '', `${location.pathname}${q ? `?${q}` : ''}#${id}`);
}

document.querySelector('[role="tablist"]').addEventListener('keydown', (e) => {
  const i = tabs.indexOf(document.activeElement);
  if (i < 0) return;
  const next = { ArrowRight: i + 1, ArrowLeft: i - 1, Home: 0, End: tabs.length - 1 }[e.key];
  if (next === undefined) return;
  e.preventDefault();
  select(tabs[(next + tabs.length) % tabs.length]);
});
for (const t of tabs) t.addEventListener('click', () => select(t));
// The skip link (first Tab stop) moves focus to the selected tab, from where the arrows switch panels.
document.querySelector('.skip-link').addEventListener('click', (e) => {
  e.preventDefault();
  tabs.find((t) => t.getAttribute('aria-selected') === 'true').focus();
});

const body = (id) => document.querySelector(`#${id} .panel-body`);
const openSolve = (request) => {
  select(tabs[0]);
  panels.solve.open(request);
};
const panels = {
  solve: createSolvePanel(body('solve')),
  compare: createComparePanel(body('compare')),
  stability: createStabilityPanel(body('stability'), { openSolve }),
  basins: createBasinsPanel(body('basins'), { openSolve }),
  speed: createSpeedPanel(body('speed')),
  motion: createMotionPanel(body('motion')),
};

const results = Object.fromEntries(Object.keys(panels).map((id) => [id, liveResult(document.querySelector(`#${id} form`),
  document.querySelector(`#${id} .output`), () => { if (!document.getElementById(id).hidden) keepInUrl(id); })]));

document.querySelector('#presets ul').append(...PRESETS.map((p) => el('li', {},
  el('a', { href: presetHref(p), dataset: { preset: p.id } }, p.title), ` \u2014 ${p.what}`)));

const fromHash = () => tabs.find((t) => `#${t.getAttribute('aria-controls')}` === location.hash);
// The settings in the address belong to the panel it names.
const opened = fromHash() ?? tabs[0];
const openedQuery = new URLSearchParams(location.search);
panels[opened.getAttribute('aria-controls')].share.apply(openedQuery);
for (const id of Object.keys(panels)) {
  const form = document.querySelector(`#${id} form`);
  const follow = () => { if (!document.getElementById(id).hidden) keepInUrl(id); };
  form.addEventListener('input', follow);
  form.addEventListener('change', follow);
}
select(opened, false);
// A #panel address picks the tab; the page still opens at the top (header and tab bar in view on a phone),
// and the fragment is not where Tab starts: focusing the body makes the skip link the first Tab stop.
function toTop() {
  window.scrollTo(0, 0);
  document.body.tabIndex = -1;
  document.body.focus({ preventScroll: true });
  document.body.removeAttribute('tabindex');
}
toTop();
// An address that asks for its result (a preset, a copied link of a result) runs once, as Run would.
if (openedQuery.get('run') === '1') document.querySelector(`#${opened.getAttribute('aria-controls')} form`).requestSubmit();
window.addEventListener('hashchange', () => {
  const t = fromHash();
  if (t) { select(t, false); toTop(); }
});

// A small liveness light in the header: the dashboard is static, the numbers come from the service.
const light = document.getElementById('server-state');
fetch('/readyz').then((r) => {
  light.textContent = r.ok ? 'service ready' : `service not ready (HTTP ${r.status})`;
  light.dataset.ok = String(r.ok);
}).catch(() => {
  light.textContent = 'service unreachable';
  light.dataset.ok = 'false';
});
