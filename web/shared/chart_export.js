// "PNG" and "SVG" under every chart the page draws: the chart as a picture for a slide (the canvas uPlot drew,
// on the page's background, with its legend drawn under it) or as vectors for a paper (axes, ticks, grid, every
// series' line and markers and the legend, written from the same scales and data as the canvas).
import { el } from './dom.js';
import { download } from './share.js';

const SVG_MARKERS = {
  circle: (x, y, r) => `M${x + r},${y}A${r},${r} 0 1 0 ${x - r},${y}A${r},${r} 0 1 0 ${x + r},${y}Z`,
  square: (x, y, r) => `M${x - r},${y - r}h${2 * r}v${2 * r}h${-2 * r}Z`,
  'triangle-up': (x, y, r) => `M${x},${y - r}L${x + r},${y + r}L${x - r},${y + r}Z`,
  'triangle-down': (x, y, r) => `M${x},${y + r}L${x + r},${y - r}L${x - r},${y - r}Z`,
  diamond: (x, y, r) => `M${x},${y - r}L${x + r},${y}L${x},${y + r}L${x - r},${y}Z`,
  cross: (x, y, r) => `M${x - r},${y - r}L${x + r},${y + r}M${x + r},${y - r}L${x - r},${y + r}`,
};

const esc = (s) => String(s).replace(/&/g, '&amp;').replace(/</g, '&lt;').replace(/>/g, '&gt;').replace(/"/g, '&quot;');
const num = (v) => Number(v.toFixed(2));
const LEGEND_ROW = 18;

// The series a legend lists: every shown one with a label.
const legendOf = (u) => u.series.slice(1).map((s, k) => ({ s, i: k + 1 })).filter(({ s }) => s.show && s.label);

// The page's colours, so that a dark-theme chart's white text stays readable on its own background.
function colours(u) {
  const css = getComputedStyle(u.root);
  return { bg: css.getPropertyValue('--card').trim() || '#ffffff', fg: css.color || '#000000' };
}

export function chartSvg(u) {
  const dpr = devicePixelRatio;
  const left = u.bbox.left / dpr; const top = u.bbox.top / dpr;
  const w = u.bbox.width / dpr; const h = u.bbox.height / dpr;
  const legend = legendOf(u);
  const height = u.height + legend.length * LEGEND_ROW + 8;
  const { bg, fg } = colours(u);
  const out = [`<svg xmlns="http://www.w3.org/2000/svg" width="${u.width}" height="${height}" viewBox="0 0 ${u.width} ${height}" font-family="sans-serif" font-size="11">`,
    `<rect width="100%" height="100%" fill="${esc(bg)}"/>`,
    `<defs><clipPath id="plot"><rect x="${num(left)}" y="${num(top)}" width="${num(w)}" height="${num(h)}"/></clipPath></defs>`,
    `<rect x="${num(left)}" y="${num(top)}" width="${num(w)}" height="${num(h)}" fill="none" stroke="${esc(fg)}" stroke-opacity="0.4"/>`];
  // Axes: the ticks and labels uPlot drew (its splits and their texts), a grid line at each tick.
  u.axes.forEach((axis, k) => {
    if (axis.show === false) return;
    const vertical = axis.side % 2 === 1;
    // The ticks the canvas shows: its axis filter (whole decades on a long log axis) applied to the splits.
    const raw = axis._splits ?? [];
    const splits = typeof axis.filter === 'function' ? axis.filter(u, raw, k, axis._space, axis._incr) : raw;
    const values = axis._values ?? [];
    splits.forEach((v, j) => {
      if (v == null) return;
      const p = u.valToPos(v, axis.scale);
      if (!Number.isFinite(p)) return;
      const text = values[j] ?? '';
      if (vertical) {
        const y = num(top + p);
        out.push(`<line x1="${num(left)}" x2="${num(left + w)}" y1="${y}" y2="${y}" stroke="${esc(fg)}" stroke-opacity="0.12"/>`);
        if (text !== '') out.push(`<text x="${num(left - 6)}" y="${y}" text-anchor="end" dominant-baseline="middle" fill="${esc(fg)}">${esc(text)}</text>`);
      } else {
        const x = num(left + p);
        out.push(`<line x1="${x}" x2="${x}" y1="${num(top)}" y2="${num(top + h)}" stroke="${esc(fg)}" stroke-opacity="0.12"/>`);
        if (text !== '') out.push(`<text x="${x}" y="${num(top + h + 14)}" text-anchor="middle" fill="${esc(fg)}">${esc(text)}</text>`);
      }
    });
    if (axis.label) {
      out.push(vertical
        ? `<text transform="translate(12 ${num(top + h / 2)}) rotate(-90)" text-anchor="middle" fill="${esc(fg)}" font-size="12">${esc(axis.label)}</text>`
        : `<text x="${num(left + w / 2)}" y="${num(top + h + 34)}" text-anchor="middle" fill="${esc(fg)}" font-size="12">${esc(axis.label)}</text>`);
    }
  });
  // Series: one polyline per unbroken run of points, then the markers.
  out.push('<g clip-path="url(#plot)" fill="none">');
  u.series.forEach((s, i) => {
    if (i === 0 || !s.show) return;
    const [xs, ys] = u.mode === 2 ? u.data[i] : [u.data[0], u.data[i]];
    const color = esc(s._color ?? s.stroke ?? fg);
    const dash = Array.isArray(s.dash) && s.dash.length ? ` stroke-dasharray="${s.dash.join(' ')}"` : '';
    const pts = [];
    const flush = () => {
      if (pts.length > 1) out.push(`<polyline data-series="${i}" points="${pts.join(' ')}" stroke="${color}" stroke-width="${s.width ?? 2}"${dash}/>`);
      pts.length = 0;
    };
    const marks = [];
    for (let j = 0; j < (xs?.length ?? 0); j++) {
      if (ys[j] == null || xs[j] == null) { flush(); continue; }
      const x = num(left + u.valToPos(xs[j], 'x')); const y = num(top + u.valToPos(ys[j], 'y'));
      if (!Number.isFinite(x) || !Number.isFinite(y)) { flush(); continue; }
      pts.push(`${x},${y}`);
      marks.push([x, y, Boolean(s._excluded?.[j])]);
    }
    flush();
    const shape = SVG_MARKERS[s._marker];
    if (shape) {
      const r = 6 - 0.8 * ((i - 1) % 4);
      for (const grey of [false, true]) {
        const d = marks.filter((m) => m[2] === grey).map(([x, y]) => shape(x, y, r)).join('');
        if (d) out.push(`<path d="${d}" stroke="${grey ? '#9a9a9a' : color}" stroke-width="1.5"/>`);
      }
    }
  });
  out.push('</g>');
  legend.forEach(({ s }, k) => {
    const y = u.height + 4 + k * LEGEND_ROW + LEGEND_ROW / 2;
    const color = esc(s._color ?? s.stroke ?? fg);
    const dash = Array.isArray(s.dash) && s.dash.length ? ` stroke-dasharray="${s.dash.join(' ')}"` : '';
    out.push(`<line x1="${num(left)}" x2="${num(left + 24)}" y1="${y}" y2="${y}" stroke="${color}" stroke-width="2"${dash}/>`,
      `<text x="${num(left + 30)}" y="${y}" dominant-baseline="middle" fill="${esc(fg)}">${esc(s.label)}</text>`);
  });
  out.push('</svg>');
  return `${out.join('\n')}\n`;
}

// The canvas uPlot drew (transparent where nothing is drawn) on the page's background, the legend under it.
export function chartPng(u) {
  const dpr = devicePixelRatio;
  const legend = legendOf(u);
  const src = u.ctx.canvas;
  const canvas = document.createElement('canvas');
  canvas.width = src.width;
  canvas.height = src.height + Math.round((legend.length * LEGEND_ROW + 8) * dpr);
  const c = canvas.getContext('2d');
  const { bg, fg } = colours(u);
  c.fillStyle = bg;
  c.fillRect(0, 0, canvas.width, canvas.height);
  c.drawImage(src, 0, 0);
  c.font = `${11 * dpr}px sans-serif`;
  c.textBaseline = 'middle';
  const left = u.bbox.left;
  legend.forEach(({ s }, k) => {
    const y = src.height + (4 + k * LEGEND_ROW + LEGEND_ROW / 2) * dpr;
    c.strokeStyle = s._color ?? s.stroke ?? fg;
    c.lineWidth = 2 * dpr;
    c.setLineDash(Array.isArray(s.dash) ? s.dash.map((d) => d * dpr) : []);
    c.beginPath();
    c.moveTo(left, y);
    c.lineTo(left + 24 * dpr, y);
    c.stroke();
    c.fillStyle = fg;
    c.fillText(s.label, left + 30 * dpr, y);
  });
  return new Promise((resolve, reject) => canvas.toBlob((b) => (b ? resolve(b) : reject(new Error('PNG encoding failed'))), 'image/png'));
}

// The two buttons under a chart; plot() is the chart shown now (a redraw replaces it).
export function exportBar(container, plot) {
  const name = container.id || 'chart';
  const button = (text, kind, onclick) => el('button', { type: 'button', class: 'chart-export-button', dataset: { export: kind },
    'aria-label': `Save the chart as ${text}`, onclick }, text);
  return el('div', { class: 'chart-export', role: 'group', 'aria-label': 'Save this chart' },
    el('span', { class: 'hint' }, 'Save chart:'),
    button('PNG', 'png', async () => download(`${name}.png`, 'image/png', await chartPng(plot()))),
    button('SVG', 'svg', () => download(`${name}.svg`, 'image/svg+xml', chartSvg(plot()))));
}
