// An interactive stability map for one method: a CSS grid of cells (x = log2 h ascending, y = N with the
// largest at the top) coloured from the sweep JSON. It is keyboard navigable as an ARIA grid with a single
// tab stop: arrows move, Enter opens the cell in the Solve panel; hover or focus shows the numbers.
import { cellColor, isOutlier } from '../shared/colormap.js';
import { el } from '../shared/dom.js';
import { METHODS, STATUSES, label } from '../shared/labels.js';

export function createGrid({ method, ns, hs, onShow, onOpen }) {
  const cells = new Map(); // `${n}|${hIndex}` -> element
  const rowsTopDown = [...ns].reverse();
  const grid = el('div', { role: 'grid', class: 'cells', 'aria-label': `Stability map, ${label(METHODS, method)}`,
    style: `grid-template-columns: 2.2em repeat(${hs.length}, minmax(0, 1fr))` });
  for (const n of rowsTopDown) {
    const row = el('div', { role: 'row', class: 'row' }, el('div', { role: 'rowheader', class: 'row-head' }, String(n)));
    hs.forEach((h, j) => {
      const c = el('div', { role: 'gridcell', class: 'cell pending', tabindex: -1,
        dataset: { method, n: String(n), h: String(h) }, 'aria-label': `N ${n}, h 2^${Math.log2(h)}: pending` });
      cells.set(`${n}|${j}`, c);
      row.append(c);
    });
    grid.append(row);
  }
  const axis = el('div', { role: 'row', class: 'row axis' }, el('div', { role: 'columnheader', class: 'corner' }, 'N'),
    hs.map((h, j) => el('div', { role: 'columnheader', class: 'col-head' },
      j % 2 === 0 || hs.length < 12 ? String(Math.log2(h)) : '')));
  grid.append(axis);
  // Cells stay at most ~1.75rem wide however few columns a sweep has.
  const figure = el('figure', { class: 'map', style: `max-width: calc(2.2em + ${hs.length * 1.75}rem)` }, el('figcaption', { title: label(METHODS, method) }, label(METHODS, method)), grid,
    el('p', { class: 'axis-title' }, 'log\u2082 h \u2192'));

  const data = new WeakMap(); // element -> sweep cell
  let current = cells.get(`${rowsTopDown[0]}|0`);
  current.tabIndex = 0;
  const move = (target) => {
    if (!target) return;
    current.tabIndex = -1;
    current = target;
    current.tabIndex = 0;
    current.focus();
  };
  const at = (el0, dr, dc) => {
    const i = rowsTopDown.indexOf(Number(el0.dataset.n)) + dr;
    const j = hs.indexOf(Number(el0.dataset.h)) + dc;
    return i >= 0 && i < rowsTopDown.length ? cells.get(`${rowsTopDown[i]}|${j}`) : undefined;
  };
  grid.addEventListener('keydown', (e) => {
    const steps = { ArrowUp: [-1, 0], ArrowDown: [1, 0], ArrowLeft: [0, -1], ArrowRight: [0, 1] };
    if (steps[e.key]) { e.preventDefault(); move(at(current, ...steps[e.key])); }
    else if ((e.key === 'Enter' || e.key === ' ') && data.has(current)) { e.preventDefault(); onOpen(data.get(current)); }
  });
  const cellOf = (e) => e.target.closest?.('.cell');
  grid.addEventListener('mouseover', (e) => { const c = cellOf(e); if (c && data.has(c)) onShow(data.get(c)); });
  grid.addEventListener('focusin', (e) => {
    const c = cellOf(e);
    if (!c) return;
    current.tabIndex = -1; // focus by mouse or script moves the single tab stop too
    current = c;
    current.tabIndex = 0;
    if (data.has(c)) onShow(data.get(c));
  });
  // A touch screen has no hover: the first tap on a cell shows its numbers, a second tap opens it.
  // (Focus moves on pointerdown, so whether the cell was already current is read there.)
  let wasCurrent = false;
  grid.addEventListener('pointerdown', (e) => { wasCurrent = cellOf(e) === current; });
  grid.addEventListener('click', (e) => {
    const c = cellOf(e);
    if (!c || !data.has(c)) return;
    const firstTap = e.pointerType === 'touch' && !wasCurrent;
    move(c);
    if (firstTap) onShow(data.get(c), true);  // the card, brought into view
    else onOpen(data.get(c));
  });

  return {
    element: figure,
    // Places one sweep cell coloured for metric over scale; false if the cell belongs to another grid.
    set(cell, metric, scale) {
      const j = hs.findIndex((h) => Math.abs(h - cell.h) <= 1e-12 * h);
      const c = cells.get(`${cell.n}|${j}`);
      if (!c || cell.method !== method) return false;
      data.set(c, cell);
      c.classList.remove('pending');
      c.dataset.status = cell.status;
      c.style.background = cellColor(cell, metric, scale, STATUSES);
      c.classList.toggle('outlier', isOutlier(cell, metric));
      c.setAttribute('aria-label', `N ${cell.n}, h 2^${Math.log2(cell.h)}: ${cell.status.replace(/_/g, ' ')}, ${cell.iterations} iterations`);
      return true;
    },
  };
}
