// A motion played in the page: a solve's iterates or an integration's states, drawn by the server as a scene of
// bodies (render/motion) in one animated WebP whose XMP names each frame's time. The page decodes every frame
// (ImageDecoder), so Play/Pause and the slider step through them with no new request; a drag on the picture turns
// the camera, and the server draws the new view on release, at the same frame.
import { postBlob } from './api.js';
import { catalog } from './catalog.js';
import { el } from './dom.js';
import { fillSelect } from './form.js';
import { imageWidth } from './image_width.js';
import { groupOf } from './request.js';

// Square pictures as wide as their figure, at most MAX_SIZE pixels.
const MAX_SIZE = 512;
const DEFAULT_FRAME_MS = 50;

// The animation's own account of its frames: { name: 't' or 'n', times: [...] } from its XMP chunk, or null.
// A WebP is RIFF: a 12-byte header, then chunks of a 4-byte tag, a 4-byte little-endian size and the payload,
// padded to an even length.
export function frameTimes(bytes) {
  const view = new DataView(bytes.buffer, bytes.byteOffset, bytes.byteLength);
  const tag = (at) => String.fromCharCode(...bytes.subarray(at, at + 4));
  for (let at = 12; at + 8 <= bytes.length;) {
    const size = view.getUint32(at + 4, true);
    if (tag(at) === 'XMP ') {
      const xmp = new TextDecoder().decode(bytes.subarray(at + 8, at + 8 + size));
      const attribute = (name) => xmp.match(new RegExp(`lienewton:${name}="([^"]*)"`))?.[1];
      const times = attribute('frameTimes');
      return times === undefined ? null : { name: attribute('timeName') ?? 't', times: times.split(' ').map(Number) };
    }
    at += 8 + size + (size & 1);
  }
  return null;
}

// Whether a solve's iterates can be drawn as bodies, as the server's catalog says of the request's group (SO(N):
// only at N = 3, the rotations of space): asking where it cannot would only log a failed request. A group the
// catalog does not list is asked for, and the server says why not.
export function drawsBodies(request) {
  const name = groupOf(request);
  const bodies = catalog.groups?.find((g) => g.value === name)?.bodies_n ?? 'any';
  return bodies === 'any' || bodies.includes(request.n);
}

// A time as the slider names it: n as it is, t to six significant digits (0.30000000000000004 is 0.3).
function timeText(name, t) {
  return `${name} = ${name === 'n' ? t : Number(t.toPrecision(6))}`;
}

// id names the figure; its parts are `${id}-canvas`, `${id}-play`, `${id}-slider` and `${id}-readout`.
// at: 'first' or 'last', the frame shown on load.
export function motionPlayer(id, { caption, at = 'first' } = {}) {
  const canvas = el('canvas', { id: `${id}-canvas`, width: MAX_SIZE, height: MAX_SIZE, tabindex: 0,
    'aria-label': 'The motion; drag or use the arrow keys to turn the view' });
  const play = el('button', { type: 'button', id: `${id}-play`, disabled: true }, 'Play');
  const slider = el('input', { type: 'range', id: `${id}-slider`, min: 0, max: 0, step: 1, value: 0, disabled: true,
    'aria-label': 'Frame' });
  const readout = el('output', { id: `${id}-readout`, for: slider.id, class: 'frame-readout' });
  const note = el('figcaption', {}, caption);
  const figure = el('figure', { class: 'frames motion', id, hidden: true },
    el('div', { class: 'frame-slider' }, play, slider), readout, canvas, note);
  const view = { azimuth_deg: 35, elevation_deg: 20 };
  let shown = null;   // { request, frameMs, describe } of the motion on show
  let frames = [];    // ImageBitmaps, or none (the <img> fallback plays the file by itself)
  let times = null;   // { name, times } from the file
  let timer = null;
  let redraw = null;  // the AbortController of a new view being drawn

  function show(k) {
    slider.value = String(k);
    const t = times?.times[k];
    const words = t === undefined ? `frame ${k} of ${frames.length - 1}` :
      (shown.describe?.(k, t) ?? `${timeText(times.name, t)} (frame ${k} of ${frames.length - 1})`);
    readout.textContent = words;
    slider.setAttribute('aria-valuetext', words);
    figure.dataset.frame = String(k);
    if (t !== undefined) figure.dataset.time = String(t);
    if (frames[k]) canvas.getContext('2d').drawImage(frames[k], 0, 0, canvas.width, canvas.height);
  }
  function pause() {
    clearInterval(timer);
    timer = null;
    play.textContent = 'Play';
    figure.dataset.playing = 'false';
  }
  play.addEventListener('click', () => {
    if (timer) return pause();
    play.textContent = 'Pause';
    figure.dataset.playing = 'true';
    timer = setInterval(() => show((Number(slider.value) + 1) % frames.length), shown.frameMs);
  });
  slider.addEventListener('input', () => { pause(); show(Number(slider.value)); });

  // Fetches and decodes the motion at the current view; resolves once every frame is decoded.
  async function fetchFrames(signal) {
    const size = Math.min(MAX_SIZE, imageWidth(figure));
    const blob = await postBlob('/api/v1/render/motion', { ...shown.request, ...view, width: size, height: size,
      frame_ms: shown.frameMs }, 'image/webp', { signal });
    const bytes = new Uint8Array(await blob.arrayBuffer());
    if (typeof ImageDecoder === 'undefined') {
      commit([], bytes, size);
      const img = el('img', { src: URL.createObjectURL(blob), alt: 'The motion, animated', width: size, height: size });
      canvas.replaceWith(img);
      return;
    }
    // Decoded aside and shown only if no newer motion was asked for meanwhile (the signal says): two runs or
    // views in quick succession never mix their frames.
    const decoded = [];
    const decoder = new ImageDecoder({ data: bytes, type: 'image/webp' });
    try {
      await decoder.tracks.ready;
      const count = decoder.tracks.selectedTrack.frameCount;
      for (let i = 0; i < count; ++i) {
        signal?.throwIfAborted();
        const { image } = await decoder.decode({ frameIndex: i });
        decoded.push(await createImageBitmap(image));
        image.close();  // a decoded VideoFrame holds its memory until closed, not until collected
      }
      signal?.throwIfAborted();
    } catch (e) {
      for (const frame of decoded) frame.close();
      throw e;
    } finally {
      decoder.close();
    }
    commit(decoded, bytes, size);
  }

  // The decoded frames become the ones shown.
  function commit(decoded, bytes, size) {
    pause();
    for (const frame of frames) frame.close();
    frames = decoded;
    times = frameTimes(bytes);
    canvas.width = size;
    canvas.height = size;
    slider.max = String(Math.max(0, frames.length - 1));
    slider.disabled = !frames.length;
    play.disabled = !frames.length;
    figure.dataset.frames = String(frames.length);
  }

  // Drag: 0.4 degrees per pixel, the elevation kept within +-89; the new view is drawn on release.
  let drag = null;
  canvas.addEventListener('pointerdown', (e) => { drag = { x: e.clientX, y: e.clientY, ...view }; canvas.setPointerCapture(e.pointerId); });
  canvas.addEventListener('pointermove', (e) => {
    if (!drag) return;
    view.azimuth_deg = Math.round((drag.azimuth_deg - 0.4 * (e.clientX - drag.x)) % 360);
    view.elevation_deg = Math.round(Math.max(-89, Math.min(89, drag.elevation_deg + 0.4 * (e.clientY - drag.y))));
    note.textContent = `View: azimuth ${view.azimuth_deg}\u00b0, elevation ${view.elevation_deg}\u00b0 (release to draw)`;
  });
  canvas.addEventListener('pointerup', () => {
    if (!drag) return;
    const moved = drag.azimuth_deg !== view.azimuth_deg || drag.elevation_deg !== view.elevation_deg;
    drag = null;
    if (moved) drawView();
  });
  // The keyboard's way to turn it: arrows by 15 degrees, drawn at once.
  const KEY_TURNS = { ArrowLeft: [15, 0], ArrowRight: [-15, 0], ArrowUp: [0, 15], ArrowDown: [0, -15] };
  canvas.addEventListener('keydown', (e) => {
    const turn = KEY_TURNS[e.key];
    if (!turn || !shown) return;
    e.preventDefault();
    view.azimuth_deg = (view.azimuth_deg + turn[0]) % 360;
    view.elevation_deg = Math.max(-89, Math.min(89, view.elevation_deg + turn[1]));
    drawView();
  });

  // The motion drawn again from the current view, at the frame shown.
  async function drawView() {
    if (!shown) return;
    const k = Number(slider.value);
    redraw?.abort();
    redraw = new AbortController();
    note.textContent = `View: azimuth ${view.azimuth_deg}\u00b0, elevation ${view.elevation_deg}\u00b0 (drawing\u2026)`;
    try {
      await fetchFrames(redraw.signal);
    } catch (e) {
      if (e.name !== 'AbortError') note.textContent = `The new view failed: ${e.message}`;
      return;
    }
    show(Math.min(k, frames.length - 1));
    note.textContent = `View: azimuth ${view.azimuth_deg}\u00b0, elevation ${view.elevation_deg}\u00b0`;
    figure.dataset.azimuth = String(view.azimuth_deg);
  }

  return {
    element: figure,
    get frameCount() { return frames.length; },
    // Draws the motion of request (a render/motion request without the view); throws the server's error.
    // describe(k, t) says what frame k, at time (or iterate) t, shows (default: its t or n and the frame).
    async load(request, { signal, frameMs = DEFAULT_FRAME_MS, describe = null } = {}) {
      redraw?.abort();
      const mine = shown = { request, frameMs, describe };
      delete figure.dataset.frames;
      figure.hidden = false;  // measured for the picture's width
      note.textContent = caption;
      try {
        await fetchFrames(signal);
      } catch (e) {
        if (shown === mine) figure.hidden = true;  // not a newer load's figure
        throw e;
      }
      show(at === 'last' ? frames.length - 1 : 0);
    },
    hide() {
      pause();
      redraw?.abort();
      figure.hidden = true;
      shown = null;
    },
  };
}

// Several runs, one played at a time: a select of the runs above one player. show() takes
// [{ label, request, describe(k, t) }] and plays the chosen one; the picker is `${id}-run`.
export function runMotions(id, heading, options) {
  const runs = [];
  const player = motionPlayer(id, options);
  const picker = el('select', { id: `${id}-run` });
  const status = el('p', { class: 'hint', hidden: true });
  const section = el('section', { class: 'run-frames', hidden: true },
    el('h3', {}, heading),
    el('div', { class: 'field' }, el('label', { for: picker.id }, 'Run'), picker), status, player.element);
  let current = null;
  async function draw() {
    const run = runs[Number(picker.value)];
    current?.abort();
    const controller = current = new AbortController();
    status.hidden = true;
    try {
      await player.load(run.request, { signal: controller.signal, describe: run.describe });
    } catch (e) {
      if (e.name === 'AbortError') return;
      status.textContent = `No motion to show: ${e.message}`;
      status.hidden = false;
    }
  }
  picker.addEventListener('change', draw);
  return {
    element: section,
    show(list) {
      runs.splice(0, runs.length, ...list);
      fillSelect(picker, runs.map((run, i) => [String(i), run.label]), '0');
      section.hidden = false;
      return draw();
    },
    hide() {
      current?.abort();
      section.hidden = true;
      player.hide();
    },
  };
}
