// Talks to the lienewton HTTP API. Every failure becomes an ApiError so that panels can put the server's
// message next to the field it names (error.field) instead of guessing.

export class ApiError extends Error {
  constructor(message, { status = 0, code = 'error', field = null } = {}) {
    super(message);
    this.name = 'ApiError';
    this.status = status;
    this.code = code;
    this.field = field;
  }
}

function fromBody(status, body) {
  const e = body && body.error;
  if (e && typeof e.message === 'string') {
    const where = Number.isInteger(e.line) ? `line ${e.line}, column ${e.column}: ` : '';  // a program's fault
    const err = new ApiError(where + e.message, { status, code: e.code, field: e.field });
    if (where) Object.assign(err, { line: e.line, column: e.column });  // for the editor's error marker
    return err;
  }
  return new ApiError(`The server answered HTTP ${status}.`, { status });
}

async function failure(res) {
  let body = null;
  try { body = await res.json(); } catch { /* not JSON: fall back to the status line */ }
  return fromBody(res.status, body);
}

async function post(path, body, accept, signal) {
  let res;
  try {
    res = await fetch(path, {
      method: 'POST',
      headers: { 'Content-Type': 'application/json', Accept: accept },
      body: JSON.stringify(body),
      signal,
    });
  } catch (err) {
    if (err.name === 'AbortError') throw err;
    throw new ApiError(`Cannot reach the server (${err.message}).`);
  }
  if (!res.ok) throw await failure(res);
  return res;
}

export async function postJSON(path, body, { signal } = {}) {
  const res = await post(path, body, 'application/json', signal);
  return res.json();
}

// The answer's bytes as a Blob of the asked type (an animation: image/webp).
export async function postBlob(path, body, accept, { signal } = {}) {
  const res = await post(path, body, accept, signal);
  return res.blob();
}

// Resolves to an object URL of the PNG; the caller revokes it when the image is replaced.
export async function postImage(path, body, { signal } = {}) {
  const res = await post(path, body, 'image/png', signal);
  return URL.createObjectURL(await res.blob());
}

// The same picture as SVG text (format svg), for a paper.
export async function postSvg(path, body, { signal } = {}) {
  const res = await post(path, { ...body, format: 'svg' }, 'image/svg+xml', signal);
  return res.text();
}

// Streams NDJSON: calls onRecord for every non-terminal line as it arrives and resolves to the terminal
// {"type":"result"} record. A terminal {"type":"error"} line is thrown like an HTTP error.
export async function stream(path, body, { signal, onRecord = () => {} } = {}) {
  const res = await post(path, body, 'application/x-ndjson', signal);
  const reader = res.body.pipeThrough(new TextDecoderStream()).getReader();
  let pending = '';
  for (;;) {
    const { value, done } = await reader.read();
    if (value) pending += value;
    const lines = pending.split('\n');
    pending = done ? '' : lines.pop();
    for (const line of lines) {
      if (!line.trim()) continue;
      const record = JSON.parse(line);
      if (record.type === 'result') return record;
      if (record.type === 'error') throw fromBody(res.status, record);
      onRecord(record);
    }
    if (done) throw new ApiError('The server closed the stream before sending a result.');
  }
}
