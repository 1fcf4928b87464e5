// Plans for long work: before Run, a quick probe (a few of the request's own cells or pixels, solved by the
// server) gives the cost of the full request; while it runs, its pace gives cells/s and the time left.
import { catalog } from './catalog.js';
import { el } from './dom.js';

// A probe that takes longer than this is stopped: its request is a long one, and saying so is the plan.
const PROBE_SECONDS = 3;
// Above this, the plan warns before Run.
const WARN_SECONDS = 60;
// The server's caps, as this server was started (its flags): seconds a sweep or basin map may run.
export const SWEEP_SECONDS = catalog.output_limits.sweep_seconds;

// The first, middle and last of a list (fewer when it is shorter): where the probe samples an axis.
export function probePoints(list) {
  return [...new Set([list[0], list[list.length >> 1], list[list.length - 1]])].filter((v) => v !== undefined);
}

// Seconds of a whole sweep from probes of some of its rows: each probe is the request at one N (and a few h),
// timed by the server (its wall time, so its threads count as they will in the full sweep). The time per cell
// at each probed N, interpolated between them as a power of N (a solve costs a power of N), times the cells
// of every N of the grid.
export function sweepEstimate(request, probes) {
  const points = probes.map(({ n, answer }) => [n, Math.max(answer.seconds, 1e-7) / Math.max(answer.cells.length, 1)])
    .sort((a, b) => a[0] - b[0]);
  if (!points.length) return null;
  const perN = request.methods.length * request.h.length;
  return { cells: perN * request.n.length,
    seconds: request.n.reduce((sum, n) => sum + perN * powerInterpolate(points, n), 0) };
}

// y at x on the broken line through points [x, y] in log-log coordinates; constant beyond the ends.
function powerInterpolate(points, x) {
  if (x <= points[0][0]) return points[0][1];
  for (let i = 1; i < points.length; i += 1) {
    const [x0, y0] = points[i - 1];
    const [x1, y1] = points[i];
    if (x <= x1) return Math.exp(Math.log(y0) + (Math.log(y1 / y0) * Math.log(x / x0)) / Math.log(x1 / x0));
  }
  return points[points.length - 1][1];
}

// "about 12 s", "about 3 min"
export function duration(seconds) {
  if (seconds < 1) return 'under a second';
  if (seconds < 90) return `about ${Math.ceil(seconds)} s`;
  return `about ${Math.round(seconds / 60)} min`;
}

// The sentence shown before Run: how many units of work, how long, and a warning above a minute or beyond
// the server's time limit.
export function planText({ count, unit, seconds, probe }) {
  let text = `${count} ${unit} to solve, ${duration(seconds)} (estimated from a ${probe})`;
  if (seconds > SWEEP_SECONDS) {
    text += `. \u26a0 Over the server\u2019s limit of ${SWEEP_SECONDS} s: it would stop the run (504); make it smaller`;
  } else if (seconds > WARN_SECONDS) {
    text += '. \u26a0 Over a minute: try a smaller one first?';
  }
  return `${text}.`;
}

// The plan in short beside the Run button (in view on every screen, a phone's too): "882 cells · about 17 s",
// with a warning sign where the full sentence warns. Shown to the eye only: the status line says it in full.
export function planBadge(form) {
  const badge = el('span', { class: 'plan', 'aria-hidden': 'true' });
  form.querySelector('.actions button[data-role="cancel"]').after(badge);
  return {
    say({ count, unit, seconds }) {
      badge.textContent = `${count} ${unit} \u00b7 ${seconds === null ? 'long' : duration(seconds)}` +
        (seconds === null || seconds > Math.min(WARN_SECONDS, SWEEP_SECONDS) ? ' \u26a0' : '');
    },
    clear() { badge.textContent = ''; },
  };
}

// While running: how far, how fast, how long still.
export function paceText(done, total, unit, began) {
  const seconds = (performance.now() - began) / 1e3;
  const rate = done / Math.max(seconds, 1e-3);
  return `${done} of ${total} ${unit} solved, ${rate < 10 ? rate.toFixed(1) : rate.toFixed(0)} ${unit}/s, ` +
    `${duration((total - done) / Math.max(rate, 1e-9))} left\u2026`;
}

// The sentence for a probe that did not finish: stopped here after PROBE_SECONDS, or by the server's own time
// limit (504), which the whole request, a superset of the probe, would then pass too.
export function tooLongText({ count, unit, probe, byServer }) {
  return `${count} ${unit} to solve. \u26a0 ` + (byServer
    ? `A ${probe} already ran over the server\u2019s limit of ${SWEEP_SECONDS} s: the server would stop the run (504); make it smaller.`
    : `A ${probe} took over ${PROBE_SECONDS} s: this takes minutes; try a smaller one first?`);
}

// Runs probe(signal) at most PROBE_SECONDS; a newer call aborts the older one. Resolves with its answer, or
// { timedOut: true, byServer } (byServer: the server's time limit stopped it), or null when a newer call or the
// caller's signal stopped it.
// run.cancel() stops the current one (a Run makes the plan of the form it came from moot).
export function prober() {
  let current = null;
  const run = async (probe, outer) => {
    current?.abort();
    const controller = new AbortController();
    current = controller;
    const stop = () => controller.abort();
    outer?.addEventListener('abort', stop);
    let timedOut = false;
    const timer = setTimeout(() => { timedOut = true; controller.abort(); }, PROBE_SECONDS * 1e3);
    try {
      return await probe(controller.signal);
    } catch (err) {
      if (timedOut || err.status === 504) return { timedOut: true, byServer: !timedOut };
      if (controller.signal.aborted) return null;
      throw err;
    } finally {
      clearTimeout(timer);
      outer?.removeEventListener('abort', stop);
    }
  };
  run.cancel = () => current?.abort();
  return run;
}
