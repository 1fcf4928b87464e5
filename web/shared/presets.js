// The dashboard's presets: links to a panel with its settings and run=1, so that each opens with its result
// (app.js runs a panel whose address asks for it). Only what differs from the panel's defaults is named.
export const PRESETS = [
  { id: 'figure-5-1', title: 'Figure 5.1', panel: 'stability', params: { problem: 'paper-linear', tol: '1e-13' },
    what: 'the paper\u2019s linear g: iterations of each method over N = 2\u202615 and h = 2\u207b\u00b9\u2070\u20262\u00b9\u2070, tol 10\u207b\u00b9\u00b3' },
  { id: 'figure-5-2', title: 'Figure 5.2', panel: 'stability', params: { problem: 'paper-sine', tol: '1e-13' },
    what: 'the same grid for the paper\u2019s sine g' },
  { id: 'newton-vs-fixed-point', title: 'Newton vs fixed point at h = 4', panel: 'compare', params: { h: '4' },
    what: 'at h = 4 the fixed point does not converge and Newton does (at the default h = 0.5 both do)' },
  { id: 'heavy-top', title: 'The heavy-top benchmark', panel: 'speed', params: { problem: 'heavy-top' },
    what: 'work against precision of the integrators on the spinning top under gravity' },
  // Steps 2^-8 ... 2^-3, far above the spring's period: where implicit methods earn their cost (the problem's own
  // time scale would ask for more steps than the server runs in one request).
  { id: 'stiff-body', title: 'The stiff body', panel: 'speed', params: { problem: 'stiff-body', k_lo: '-8', k_hi: '-3' },
    what: 'work against precision on the sprung, damped and forced body (k = 10\u2074), h = 2\u207b\u2078\u20262\u207b\u00b3' },
];

export function presetHref({ panel, params }) {
  return `?${new URLSearchParams({ ...params, run: '1' })}#${panel}`;
}
