// Form plumbing shared by the panels: reading typed values, showing API errors next to the field they
// name, and the Run/Cancel/progress cycle of a long request.
import { ApiError } from './api.js';

export function fillSelect(select, options, value) {
  select.replaceChildren(...options.map(([v, text]) => new Option(text, v, false, v === value)));
}

// Numbers are parsed, but text that is not a number is sent as it is: the server then names the field and
// explains what it expects, so there is one source of truth for validation.
export function typedValue(input) {
  const raw = input.value.trim();
  if (input.dataset.type !== 'number') return raw;
  const x = raw === '' ? NaN : Number(raw);
  return Number.isFinite(x) ? x : raw;
}

export function value(form, name) {
  return typedValue(form.elements.namedItem(name));
}

export function checkedValues(form, name) {
  return [...form.querySelectorAll(`input[name="${name}"]:checked`)].map((i) => i.value);
}

export function clearErrors(form) {
  for (const out of form.querySelectorAll('.field-error')) out.textContent = '';
  for (const el of form.querySelectorAll('[aria-invalid]')) el.removeAttribute('aria-invalid');
  const general = form.querySelector('.form-error');
  if (general) general.textContent = '';
}

// The whole numbers lo..hi typed in the two boxes of a range field (e.g. k_lo, k_hi of "h = 2^k"). A bad
// entry is reported against the box that holds it, in terms of the symbol the user typed.
export function wholeRange(form, loName, hiName, symbol) {
  const lo = value(form, loName);
  const hi = value(form, hiName);
  for (const [name, v, end] of [[loName, lo, 'from'], [hiName, hi, 'to']]) {
    if (!Number.isInteger(v)) throw new ApiError(`${symbol} ${end}: give a whole number (got \u201c${v}\u201d).`, { field: name });
  }
  if (lo > hi) throw new ApiError(`${symbol} from (${lo}) is above ${symbol} to (${hi}).`, { field: hiName });
  return Array.from({ length: hi - lo + 1 }, (_, i) => lo + i);
}

// "h", "n[3]", "choices[1].method" -> the field wrapper named by the leading identifier; a field that is
// itself an input's name (k_lo) flags that input.
export function showError(form, err) {
  const field = err instanceof ApiError && err.field ? String(err.field) : null;
  const name = field?.match(/^[A-Za-z_]+/)?.[0];
  const own = field && form.querySelector(`input[name="${CSS.escape(field)}"]`);
  const wrapper = own?.closest('.field') ?? (name && form.querySelector(`.field[data-field="${name}"]`));
  if (wrapper) {
    const fold = wrapper.closest('details.folded');
    if (fold) fold.open = true;
    wrapper.querySelector('.field-error').textContent = err.message;
    // A program's fault: the editor flags the line (shared/code_editor.js listens).
    if (Number.isInteger(err.line)) wrapper.dispatchEvent(new CustomEvent('program-error', { detail: { line: err.line, column: err.column } }));
    const input = own ?? wrapper.querySelector('input[name], select[name]');
    if (input) {
      input.setAttribute('aria-invalid', 'true');
      input.focus();
    }
    return;
  }
  const general = form.querySelector('.form-error');
  general.textContent = err.message;
}

// Runs one request at a time per form. The Cancel button aborts the fetch; the server notices the closed
// connection and stops computing.
// `live` is the panel's status line: it says how a run ended when that is not a result.
export function runner(form, live) {
  const run = form.querySelector('button[data-role="run"]');
  const cancel = form.querySelector('button[data-role="cancel"]');
  const progress = form.querySelector('progress');
  let controller = null;
  cancel.addEventListener('click', () => controller?.abort());
  // Esc cancels this form's run wherever focus is (clicking Run disables it and focus falls to the body),
  // as long as the form's panel is the one shown.
  document.addEventListener('keydown', (e) => {
    if (e.key === 'Escape' && controller && form.offsetParent !== null) controller.abort();
  });
  return async function start(task) {
    controller?.abort();
    const mine = (controller = new AbortController());
    clearErrors(form);
    const hadFocus = document.activeElement === run;
    run.disabled = true;
    cancel.disabled = false;
    if (hadFocus) cancel.focus();
    progress.hidden = false;
    progress.removeAttribute('value');
    form.setAttribute('aria-busy', 'true');
    // Once a run starts, a phone shows the output above the form (style.css, .ran): bring it into view.
    form.parentElement.classList.add('ran');
    // Not for a live run (shared/live.js): the slider that started it stays where the thumb is.
    if (matchMedia('(max-width: 820px)').matches && !form.dataset.live) form.nextElementSibling?.scrollIntoView({ block: 'start' });
    try {
      await task(mine.signal, progress);
      return true;
    } catch (err) {
      const cancelled = err.name === 'AbortError';
      showError(form, cancelled ? new Error('Cancelled.') : err);
      live.textContent = cancelled ? 'Cancelled.' : `Failed: ${err.message}`;
      return false;
    } finally {
      if (controller === mine) {
        controller = null;
        run.disabled = false;
        cancel.disabled = true;
        progress.hidden = true;
        form.removeAttribute('aria-busy');
      }
    }
  };
}
