// The result summary and the status badge, shared by Solve and Compare.
import { el } from './dom.js';
import { STATUSES, fmtExp, fmtRate, fmtSeconds, mathText } from './labels.js';

export function statusBadge(status) {
  const color = STATUSES[status]?.color ?? '#777';
  return el('span', { class: 'badge', style: `--badge:${color}`, dataset: { status } }, status.replace(/_/g, ' '));
}

// An integration's warnings (IntegrateResult.warnings) beside its status: its stages converged, but the answer may
// not be the solution's. The code is the badge's text, the message its tooltip.
export function warningBadges(warnings = []) {
  // One badge per code (two drifting invariants are one "invariant drift"), every message in its tooltip.
  const byCode = new Map();
  for (const w of warnings) byCode.set(w.code, [...(byCode.get(w.code) ?? []), w.message]);
  return [...byCode].map(([code, messages]) => el('span', { class: 'badge warning', title: messages.join('\n'),
    dataset: { warning: code } }, `\u26a0 ${code.replace(/_/g, ' ')}${messages.length > 1 ? ` (${messages.length})` : ''}`));
}

// A <dl> whose <dd>s carry data-result=<field> so tests read what a person reads.
export function resultList(result) {
  const row = (key, term, value, note = null) => [el('dt', {}, term), el('dd', { dataset: { result: key } }, value), note && el('dd', { class: 'note' }, note)];
  return el('dl', { class: 'summary' },
    row('status', 'Status', statusBadge(result.status)),
    row('reason', 'Why', mathText(result.reason || STATUSES[result.status]?.text)),
    row('branch', 'Which root', branchText(result)),
    row('iterations', 'Iterations', String(result.iterations)),
    row('rate', 'Rate r', rateText(result), el('small', { class: 'hint', dataset: { explains: 'rate' } }, RATE_WORDS)),
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

// What r is: the paper's estimate (section 5) from the three residuals before the last, so it reads the order
// where the iteration was before reaching rounding level (often well under 2 on a short quadratic run).
export const RATE_WORDS = 'Rate r is the paper\u2019s \u00a75 estimate from three residuals before the last: '
  + 'r = log(\u2016f(y\u209a\u208b\u2081)\u2016 / \u2016f(y\u209a\u208b\u2082)\u2016) / log(\u2016f(y\u209a\u208b\u2082)\u2016 / \u2016f(y\u209a\u208b\u2083)\u2016), p the iterations; '
  + '1 is linear, 2 quadratic. It leaves out the last iterate (which may sit at rounding), so a short quadratic run can read well under 2.';

// r needs three iterations; a longer run without one has no measurable rate (e.g. it never settled).
function rateText({ rate, iterations }) {
  if (rate !== null && rate !== undefined) return fmtRate(rate);
  return iterations < 3 ? '\u2014 (needs 3 iterations)' : '\u2014 (not measurable)';
}
