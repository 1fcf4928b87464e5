// The result summary and the status badge, shared by Solve and Compare.
import { el } from './dom.js';
import { STATUSES, fmtExp, fmtRate, fmtSeconds, mathText } from './labels.js';

export function statusBadge(status) {
  const color = STATUSES[status]?.color ?? '#777';
  return el('span', { class: 'badge', style: `--badge:${color}`, dataset: { status } }, status.replace(/_/g, ' '));
}

// A <dl> whose <dd>s carry data-result=<field> so tests read what a person reads.
export function resultList(result) {
  const row = (key, term, value) => [el('dt', {}, term), el('dd', { dataset: { result: key } }, value)];
  return el('dl', { class: 'summary' },
    row('status', 'Status', statusBadge(result.status)),
    row('reason', 'Why', mathText(result.reason || STATUSES[result.status]?.text)),
    row('branch', 'Which root', branchText(result)),
    row('iterations', 'Iterations', String(result.iterations)),
    row('rate', 'Rate r', rateText(result)),
    row('residual', 'Final \u2016f(y)\u2016', fmtExp(result.residual)),
    row('orthogonality_error', '\u2016y\u1d40y \u2212 I\u2016', fmtExp(result.orthogonality_error)),
    row('cpu_seconds', 'Solver CPU time', fmtSeconds(result.cpu_seconds)),
    row('seconds', 'Wall time (server)', fmtSeconds(result.seconds)));
}

// Which root y is, and what found it: the words of the server's catalog, plus the fold or the seeded start.
function branchText({ branch, found_by: foundBy, fold_h: foldH, multistart_start: start }) {
  if (!branch) return '\u2014';
  const words = { continued: 'z\u2019s root, continued from h = 0', other: 'another root', unchecked: 'unchecked' };
  const by = foundBy === 'multistart' ? ` (multistart start ${start})` : foundBy === 'continuation' ? ' (continuation)' : '';
  const fold = foldH !== undefined && foldH !== null ? `; z\u2019s branch folds at h = ${foldH.toPrecision(4)}` : '';
  return `${words[branch] ?? branch}${by}${fold}`;
}

// r needs three iterations; a longer run without one has no measurable rate (e.g. it never settled).
function rateText({ rate, iterations }) {
  if (rate !== null && rate !== undefined) return fmtRate(rate);
  return iterations < 3 ? '\u2014 (needs 3 iterations)' : '\u2014 (not measurable)';
}
