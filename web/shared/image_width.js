// Server PNGs are drawn at the width they are shown at, in CSS pixels: a picture drawn wider and shrunk to fit
// a phone shrinks its 13-pixel labels with it until they cannot be read. (On a high-density screen the browser
// scales the picture up by devicePixelRatio: a little soft, but the text keeps its size.)
const MIN = 64;   // the renderer's limits
const MAX = 4096;

// The content width of box less the image's 1px border on each side, within the renderer's limits.
export function imageWidth(box) {
  const style = getComputedStyle(box);
  // The exact (fractional) width: clientWidth rounds, and one pixel too many scales the picture down.
  const content = box.getBoundingClientRect().width - ['borderLeftWidth', 'borderRightWidth', 'paddingLeft', 'paddingRight']
    .reduce((sum, side) => sum + parseFloat(style[side]), 0);
  return Math.max(MIN, Math.min(MAX, Math.floor(content) - 2));
}

// Calls redraw(width) when box is shown and its size has settled after a change (rotation, window resize, the
// box shown), at most every 250 ms; the caller redraws only if width is not what it drew.
export function onWidthChange(box, redraw) {
  let timer = null;
  new ResizeObserver(() => {
    clearTimeout(timer);
    timer = setTimeout(() => box.offsetParent !== null && redraw(imageWidth(box)), 250);
  }).observe(box);
}
