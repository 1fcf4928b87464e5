// Timings at the microsecond scale are noise in one shot: a run is repeated and reported, as BenchmarkTools
// does, by its median and range; two runs whose ranges overlap cannot be ordered by their times.
import { fmtSeconds } from './labels.js';

export const REPEATS = 5;

// Of ascending times: the middle one (the mean of the two middle ones for an even count).
export function median(sorted) {
  const m = sorted.length >> 1;
  return sorted.length % 2 ? sorted[m] : (sorted[m - 1] + sorted[m]) / 2;
}

// "1.20 ms (1.10–1.40 ms)": median (range) of ascending times.
export function spreadText(sorted) {
  return `${fmtSeconds(median(sorted))} (${fmtSeconds(sorted[0])}\u2013${fmtSeconds(sorted.at(-1))})`;
}

// Whether two ascending lists of times overlap: their order is noise, not a finding.
export const withinNoise = (a, b) => a[0] <= b.at(-1) && b[0] <= a.at(-1);
