// Rotation frames of an SO(3) run (a solve's iterates or an integration's states) with a slider that steps
// through them. The server draws frames 0..k (render/frames with upto = k, frame k bold) from the run's own
// request, so the page holds no matrices: only the request and one line of numbers per step, no more than
// the picture needs. Images are GETs, so a step already seen comes from the browser cache (ETag, 304).
import { el } from './dom.js';
import { fillSelect } from './form.js';
import { imageWidth, onWidthChange } from './image_width.js';

// Square pictures as wide as their figure, at most MAX_SIZE pixels.
const MAX_SIZE = 512;

// A GET query of a JSON request: arrays and objects as JSON text, which the server's query reader parses.
export function framesUrl(request, upto, size) {
  const query = new URLSearchParams();
  for (const [key, v] of Object.entries({ ...request, width: size, height: size, upto })) {
    if (v === undefined || v === null || v === '') continue;
    query.set(key, typeof v === 'object' ? JSON.stringify(v) : String(v));
  }
  return `/api/v1/render/frames?${query}`;
}

// id names the figure; the image is `${id}-img`, the slider `${id}-slider`, the readout `${id}-readout`.
// sliderLabel names what a step is ("Iterate n", "Time step").
export function frameStepper(id, sliderLabel, caption) {
  const img = el('img', { id: `${id}-img`, alt: '' });
  const slider = el('input', { type: 'range', id: `${id}-slider`, min: 0, max: 0, step: 1, value: 0 });
  const readout = el('output', { id: `${id}-readout`, for: slider.id, class: 'frame-readout' });
  const note = el('figcaption', {}, caption);
  const figure = el('figure', { class: 'frames', id, hidden: true },
    el('div', { class: 'frame-slider' }, el('label', { for: slider.id }, sliderLabel), slider), readout, img, note);
  let run = null; // { request, describe(k) }
  let drawnSize = 0;

  function showStep() {
    const k = Number(slider.value);
    const words = run.describe(k);
    readout.textContent = words;
    slider.setAttribute('aria-valuetext', words);
    img.alt = `Rotation frames 0 to ${k}, frame ${k} bold: ${words}`;
    figure.dataset.step = String(k);
    note.textContent = caption;
    const size = Math.min(MAX_SIZE, imageWidth(figure));
    drawnSize = size;
    img.width = size;
    img.height = size;
    img.src = framesUrl(run.request, k, size);
  }
  onWidthChange(figure, (width) => run && Math.min(MAX_SIZE, width) !== drawnSize && showStep());
  slider.addEventListener('input', showStep);
  // A failed picture says why: the GET's JSON error, fetched again to read its message.
  img.addEventListener('error', async () => {
    const src = img.getAttribute('src');
    if (!src) return;
    let why = 'the server sent no picture';
    try { why = (await (await fetch(src)).json()).error?.message ?? why; } catch { /* keep the generic reason */ }
    if (img.getAttribute('src') === src) note.textContent = `Frames unavailable: ${why}`;
  });

  return {
    element: figure,
    // count steps 0..count-1; the slider starts at the last (the whole run).
    show(request, count, describe) {
      run = { request, describe };
      slider.max = String(Math.max(0, count - 1));
      slider.value = slider.max;
      figure.hidden = false;
      showStep();
    },
    hide() {
      figure.hidden = true;
      run = null;
      img.removeAttribute('src');
    },
  };
}

// Several runs, one shown at a time: a select of the runs above one stepper. show() takes
// [{ label, request, count, describe(k) }]; the picker is `${id}-run`.
export function runFrames(id, heading, sliderLabel, caption) {
  const stepper = frameStepper(id, sliderLabel, caption);
  const picker = el('select', { id: `${id}-run` });
  const section = el('section', { class: 'run-frames', hidden: true },
    el('h3', {}, heading),
    el('div', { class: 'field' }, el('label', { for: picker.id }, 'Run'), picker), stepper.element);
  let runs = [];
  const draw = () => {
    const run = runs[Number(picker.value)];
    stepper.show(run.request, run.count, run.describe);
  };
  picker.addEventListener('change', draw);
  return {
    element: section,
    show(list) {
      runs = list;
      fillSelect(picker, runs.map((run, i) => [String(i), run.label]), '0');
      section.hidden = false;
      draw();
    },
    hide() {
      section.hidden = true;
      stepper.hide();
    },
  };
}
