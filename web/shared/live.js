// A panel's result kept honest and, where it is cheap, live. Every panel's form is watched the same way, from
// outside the panel: the runner (form.js) marks a run with aria-busy, so its length and end are seen here.
// - A cheap panel (its last run took under CHEAP_MS, click to result) runs again as a slider or a number box
//   moves, a moment after the last move: the chart follows h.
// - Otherwise a result whose settings changed since its run is marked stale (dimmed, a note saying so) until Run.
// - fresh() says whether the panel shows the result of its form as it is: the page's address then asks for it
//   (run=1), so that a copied link opens with the result, not at "Press Run".
import { el } from './dom.js';

// Solve, Compare and Speed at their defaults take 0.1-0.4 s; a map takes seconds and waits for Run.
export const CHEAP_MS = 1000;
const SETTLE_MS = 150;  // after the last move of a slider: one run per pause, not one per pixel

export function liveResult(form, output, onChange = () => {}) {
  let began = 0;
  let lastMs = Infinity;  // nothing run yet: nothing is cheap
  let hasResult = false;
  let stale = false;
  let timer = 0;
  const note = el('p', { class: 'stale-note', role: 'status', hidden: true },
    'Settings changed since this result: press Run to update it.');
  output.prepend(note);
  const mark = (on) => {
    stale = on;
    note.hidden = !on;
    output.classList.toggle('stale', on);
    output.dataset.stale = String(on);
    onChange();
  };
  new MutationObserver(() => {
    if (form.getAttribute('aria-busy') === 'true') {
      began = performance.now();
      return;
    }
    // A run refused on a field (a bad range, a server 400) or cancelled shows no result and says nothing of
    // what the next one costs: only a finished run makes the panel cheap.
    const failed = Boolean(form.querySelector('.form-error')?.textContent)
      || [...form.querySelectorAll('.field-error')].some((slot) => slot.textContent.trim());
    hasResult = !failed;
    if (!failed) lastMs = performance.now() - began;
    output.dataset.runMs = String(Math.round(performance.now() - began));
    delete form.dataset.live;
    mark(false);
  }).observe(form, { attributes: true, attributeFilter: ['aria-busy'] });

  const changed = (e) => {
    if (!hasResult) return;
    const control = e.target;
    // A slider or a number box: a step of the same run. A select (another problem, method) may cost far more.
    const movable = control.type === 'range' || control.type === 'number' || control.dataset.type === 'number';
    if (movable && lastMs < CHEAP_MS) {
      clearTimeout(timer);
      timer = setTimeout(() => {
        if (form.getAttribute('aria-busy') === 'true') return;
        form.dataset.live = 'true';  // the runner does not scroll to the output for a live run
        form.requestSubmit();
      }, SETTLE_MS);
    }
    if (!stale) mark(true);
  };
  form.addEventListener('input', changed);
  form.addEventListener('change', changed);
  return { fresh: () => hasResult && !stale };
}
