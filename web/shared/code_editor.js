// The program editor: a textarea with a gutter of line numbers beside it, scrolled with it, and an error marker
// on the line a program's error names (the server's line and column): the line's number is flagged, the text
// under the message says where, and the caret is put at the reported column. No library: a gutter and a textarea.
import { el } from './dom.js';

export function codeEditor(textarea) {
  const gutter = el('pre', { class: 'code-gutter', 'aria-hidden': 'true' });
  const wrap = el('div', { class: 'code-editor' }, gutter, textarea);
  let errorLine = 0;
  const lines = () => Math.max(1, textarea.value.split('\n').length);
  const draw = () => {
    const n = lines();
    textarea.rows = Math.min(16, Math.max(4, n + 1));
    gutter.replaceChildren(...Array.from({ length: Math.max(n, textarea.rows) }, (_, i) => el('span', {
      class: i + 1 === errorLine ? 'line error' : 'line', dataset: { line: String(i + 1) } }, i < n ? String(i + 1) : ' ')));
    gutter.scrollTop = textarea.scrollTop;
  };
  textarea.addEventListener('input', () => { mark(0); });
  textarea.addEventListener('scroll', () => { gutter.scrollTop = textarea.scrollTop; });
  // line 0: no error. The caret goes to the column, so the fault is where one starts typing.
  function mark(line, column = 1) {
    errorLine = line;
    wrap.dataset.errorLine = String(line);
    wrap.classList.toggle('has-error', line > 0);
    draw();
    if (line > 0) {
      const before = textarea.value.split('\n').slice(0, line - 1).reduce((a, l) => a + l.length + 1, 0);
      const at = Math.min(textarea.value.length, before + Math.max(0, column - 1));
      textarea.focus();
      textarea.setSelectionRange(at, at);
      if (column < 40) textarea.scrollLeft = 0;  // the start of the flagged line in view, not the end of the last
    }
  }
  draw();
  return { element: wrap, mark, refresh: draw };
}
