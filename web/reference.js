// The API reference page: /openapi.json rendered as HTML by the browser, from the document alone (no network
// beyond this server, nothing copied): operations by tag with their parameters, request examples and responses,
// then every schema with its fields, defaults, enums and the stream records' discriminator.
const esc = (text) => String(text ?? '').replace(/[&<>"']/g, (c) => `&#${c.charCodeAt(0)};`);
const refName = (ref) => ref.split('/').pop();
const anchor = (name) => `schema-${name}`;
const link = (name) => `<a href="#${anchor(name)}">${esc(name)}</a>`;

// A schema's type in a line: a link for a named schema, T[] for arrays, a|b for enums, "?" for nullable.
export function typeText(s) {
  if (!s) return '';
  if (s.$ref) return link(refName(s.$ref));
  if (s.title) return link(s.title);  // a schema written out in full (a request body) names the one it copies
  let t;
  if (s.oneOf || s.anyOf) t = (s.oneOf || s.anyOf).map(typeText).join(' | ');
  else if (s.type === 'array') t = `${typeText(s.items)}[]`;
  else if (s.enum) t = s.enum.map((v) => `<code>${esc(v)}</code>`).join(' | ');
  else if (s.type === 'object' && s.additionalProperties && typeof s.additionalProperties === 'object')
    t = `{name: ${typeText(s.additionalProperties)}}`;
  else t = esc(s.type ?? 'any');
  if (s.pattern) t += ` (pattern <code>${esc(s.pattern)}</code>)`;
  return s.nullable ? `${t} or null` : t;
}

function bounds(s) {
  const x = s.type === 'array' ? s.items ?? {} : s;
  const parts = [];
  if (x.minimum !== undefined) parts.push(`${x.exclusiveMinimum ? '>' : '≥'} ${x.minimum}`);
  if (x.maximum !== undefined) parts.push(`≤ ${x.maximum}`);
  return parts.join(', ');
}

function defaultText(s) {
  const d = s.default ?? (s.type === 'array' ? s.items?.default : undefined);
  return d === undefined ? '' : `<code>${esc(JSON.stringify(d))}</code>`;
}

// One row per field; an inline object's (or array of objects') fields follow as name.field (name[].field).
function fieldRows(properties, required = [], prefix = '') {
  return Object.entries(properties ?? {}).map(([name, s]) => {
    const inner = s.type === 'array' ? s.items ?? {} : s;
    const nested = inner.properties ? fieldRows(inner.properties, inner.required, `${prefix}${name}${s.type === 'array' ? '[]' : ''}.`) : '';
    return `<tr${s.deprecated ? ' class="deprecated"' : ''}>
    <td><code>${esc(prefix + name)}</code>${required.includes(name) ? ' <span class="req">required</span>' : ''}${s.deprecated ? ' <span class="dep">deprecated</span>' : ''}</td>
    <td>${typeText(s)}</td><td>${defaultText(s)}</td><td>${esc(bounds(s))}</td><td>${esc(s.description ?? s.items?.description ?? '')}</td></tr>${nested}`;
  }).join('');
}

const fieldTable = (rows) => rows ? `<table><thead><tr><th>field</th><th>type</th><th>default</th><th>bounds</th><th>description</th></tr></thead><tbody>${rows}</tbody></table>` : '';

function operationHtml(path, method, op) {
  const params = (op.parameters ?? []).map((p) => {
    const s = p.schema ?? p.content?.['application/json']?.schema ?? {};
    return `<tr><td><code>${esc(p.name)}</code></td><td>${typeText(s)}${p.content ? ' (JSON text)' : ''}${p.explode === false ? ' (comma-separated)' : ''}</td><td>${defaultText(s)}</td><td>${esc(bounds(s))}</td><td>${esc(p.description)}</td></tr>`;
  }).join('');
  const body = op.requestBody?.content?.['application/json'];
  const examples = Object.entries(body?.examples ?? {}).map(([name, e]) => `<figure class="example">
    <figcaption><b>${esc(name)}</b>: ${esc(e.summary)}</figcaption>
    <pre>curl -s ${esc(`{server}${path}`)} -d '${esc(JSON.stringify(e.value))}'</pre></figure>`).join('');
  const responses = Object.entries(op.responses ?? {}).map(([status, r]) => `<tr><td>${esc(status)}</td><td>${esc(r.description)}</td>
    <td>${Object.entries(r.content ?? {}).map(([type, m]) => `<code>${esc(type)}</code> ${typeText(m.schema)}`).join('<br>')}</td></tr>`).join('');
  return `<section class="operation" id="op-${esc(op.operationId)}">
    <h3><span class="method method-${method}">${method.toUpperCase()}</span> <code>${esc(path)}</code> <small>${esc(op.operationId)}</small></h3>
    <p>${esc(op.summary)}</p>
    ${params ? `<h4>Query parameters</h4><table><thead><tr><th>name</th><th>type</th><th>default</th><th>bounds</th><th>description</th></tr></thead><tbody>${params}</tbody></table>` : ''}
    ${body ? `<h4>Request body</h4><p>${typeText(body.schema)}</p>${examples}` : ''}
    <h4>Responses</h4><table><thead><tr><th>status</th><th>meaning</th><th>content</th></tr></thead><tbody>${responses}</tbody></table>
  </section>`;
}

function schemaHtml(name, s) {
  let inner = '';
  if (s.oneOf) {
    const mapping = s.discriminator?.mapping ?? {};
    // In the stream's order (oneOf's), each with the type value that selects it.
    const valueOf = (ref) => Object.keys(mapping).find((v) => mapping[v] === ref);
    inner = `<p>One of, told apart by <code>${esc(s.discriminator?.propertyName ?? '')}</code>:</p><ul>${
      s.oneOf.map((one) => `<li>${valueOf(one.$ref) ? `<code>${esc(valueOf(one.$ref))}</code>: ` : ''}${typeText(one)}</li>`).join('')}</ul>`;
  } else if (s.properties) {
    inner = fieldTable(fieldRows(s.properties, s.required));
  } else {
    inner = `<p>${typeText(s)}</p>`;
  }
  return `<section class="schema" id="${anchor(name)}"><h3>${esc(name)}</h3>${s.description ? `<p>${esc(s.description)}</p>` : ''}${inner}</section>`;
}

// The whole reference as HTML, from the document.
export function referenceHtml(doc) {
  const ops = [];
  for (const [path, item] of Object.entries(doc.paths)) for (const [method, op] of Object.entries(item)) ops.push({ path, method, op });
  const tags = doc.tags ?? [];
  const byTag = tags.map((t) => `<section class="tag" id="tag-${esc(t.name)}"><h2>${esc(t.name)}</h2><p>${esc(t.description)}</p>${
    ops.filter(({ op }) => (op.tags ?? []).includes(t.name)).map(({ path, method, op }) => operationHtml(path, method, op)).join('')}</section>`).join('');
  const toc = tags.map((t) => `<li><a href="#tag-${esc(t.name)}">${esc(t.name)}</a><ul>${
    ops.filter(({ op }) => (op.tags ?? []).includes(t.name)).map(({ path, method, op }) =>
      `<li><a href="#op-${esc(op.operationId)}">${method.toUpperCase()} ${esc(path)}</a></li>`).join('')}</ul></li>`).join('');
  const servers = (doc.servers ?? []).map((s) => `<code>${esc(s.url)}</code> ${esc(s.description)}`).join('; ');
  const schemas = Object.entries(doc.components?.schemas ?? {}).map(([n, s]) => schemaHtml(n, s)).join('');
  return `<header><h1>${esc(doc.info.title)} API ${esc(doc.info.version)}</h1><p>${esc(doc.info.description)}</p>
    <p>OpenAPI ${esc(doc.openapi)} · <a href="/openapi.json">the document</a> · servers: ${servers} · <a href="/">dashboard</a></p></header>
    <nav><ol>${toc}<li><a href="#schemas">schemas</a></li></ol></nav>
    <main>${byTag}<section id="schemas"><h2>schemas</h2>${schemas}</section></main>`;
}

if (typeof document !== 'undefined') {
  const root = document.getElementById('reference');
  fetch('/openapi.json')
    .then((r) => (r.ok ? r.json() : Promise.reject(new Error(`GET /openapi.json: ${r.status}`))))
    .then((doc) => {
      root.innerHTML = referenceHtml(doc).replaceAll('{server}', esc(location.origin));
      if (location.hash) document.getElementById(location.hash.slice(1))?.scrollIntoView();
    })
    .catch((e) => { root.textContent = `The API document could not be loaded: ${e.message}`; });
}
