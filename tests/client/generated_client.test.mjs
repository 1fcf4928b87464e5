// A client generated from the live /openapi.json calls solve: openapi-typescript turns the document into types,
// openapi-fetch is the runtime, tsc (strict) checks the calling code against the types and emits the JavaScript
// that node runs against a test server. A call the document forbids (h as a string) must not type-check, so the
// types are the document's and not `any`.
//   node tests/client/generated_client.test.mjs path/to/lienewton-server
// Needs the root node_modules (`npm ci`, run by scripts/deps.sh test); NODE_MODULES names another one.
import { spawn, execFileSync } from 'node:child_process';
import { mkdtempSync, writeFileSync, symlinkSync, rmSync, existsSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { dirname, join, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';
import { createServer } from 'node:net';
import assert from 'node:assert/strict';
import { test, after } from 'node:test';

const root = resolve(dirname(fileURLToPath(import.meta.url)), '../..');
const modules = resolve(process.env.NODE_MODULES ?? join(root, 'node_modules'));
const serverBin = resolve(process.argv[2] ?? 'build/bin/lienewton-server');
for (const pkg of ['openapi-typescript', 'openapi-fetch', 'typescript']) {
  if (!existsSync(join(modules, pkg))) throw new Error(`${pkg} is missing in ${modules}: run npm ci (scripts/deps.sh test)`);
}
const { default: openapiTS, astToString } = await import(join(modules, 'openapi-typescript/dist/index.mjs'));

const freePort = () => new Promise((ok) => {
  const s = createServer().listen(0, '127.0.0.1', () => { const { port } = s.address(); s.close(() => ok(port)); });
});
const port = await freePort();
const base = `http://127.0.0.1:${port}`;
const server = spawn(serverBin, ['--host', '127.0.0.1', '--port', String(port), '--web-root', join(root, 'web')],
  { stdio: 'ignore' });
const work = mkdtempSync(join(tmpdir(), 'lienewton-client-'));
after(() => { server.kill(); rmSync(work, { recursive: true, force: true }); });
for (let i = 0; ; ++i) {
  try { if ((await fetch(`${base}/livez`)).ok) break; } catch { /* not up yet */ }
  if (i > 100) throw new Error('the server did not start');
  await new Promise((ok) => setTimeout(ok, 100));
}

const tsconfig = (files) => JSON.stringify({
  compilerOptions: { strict: true, target: 'es2022', module: 'es2022', moduleResolution: 'bundler',
    lib: ['es2022', 'dom'], outDir: 'out', skipLibCheck: true, noEmitOnError: true },
  files });
const tsc = (config) => {
  try {
    return execFileSync(process.execPath, [join(modules, 'typescript/bin/tsc'), '-p', config],
      { cwd: work, encoding: 'utf8', stdio: 'pipe' });
  } catch (e) {
    throw Object.assign(new Error(`tsc -p ${config}:\n${e.stdout}`), { stdout: e.stdout });
  }
};

test('generated client calls solve and integrate', async () => {
  const doc = await (await fetch(`${base}/openapi.json`)).json();
  // The generator at its defaults (as `npx openapi-typescript URL -o schema.d.ts` runs it): a request field with a
  // default is optional because the document writes each request body's schema out in full.
  writeFileSync(join(work, 'schema.d.ts'), astToString(await openapiTS(doc)));
  symlinkSync(modules, join(work, 'node_modules'));
  // tsc emits ES modules; Node 18 (Debian 12's) runs a .js file as one only under a package.json that says so.
  writeFileSync(join(work, 'package.json'), JSON.stringify({ type: 'module' }));
  writeFileSync(join(work, 'client.ts'), `
import createClient from 'openapi-fetch';
import type { paths, components } from './schema';
declare const process: { argv: string[] };
const client = createClient<paths, 'application/json'>({ baseUrl: process.argv[2] });
const { data, error } = await client.POST('/api/v1/solve', {
  body: { problem: 'paper-linear', n: 3, h: 0.5, method: 'newton-group', differential: 'exact', seed: 1 } });
if (error || !data) throw new Error(JSON.stringify(error));
const status: components['schemas']['SolveResult']['status'] = data.status;
const integration = await client.POST('/api/v1/integrate', {
  body: { problem: 'heavy-top', integrator: 'rkmk-gauss2', h: 0.01, t_end: 0.1 } });
if (integration.error || !integration.data) throw new Error(JSON.stringify(integration.error));
const globalError: number | null | undefined = integration.data.global_error;
const bad = await client.POST('/api/v1/solve', { body: { n: 3, h: -1 } });
const version = await client.GET('/api/v1/version');
console.log(JSON.stringify({ status, iterations: data.iterations, residual: data.residual, globalError,
  steps: integration.data.steps?.length,
  code: bad.error?.error.code, field: bad.error?.error.field, http: bad.response.status,
  version: version.data?.version }));
`);
  writeFileSync(join(work, 'tsconfig.json'), tsconfig(['client.ts', 'schema.d.ts']));
  tsc('tsconfig.json');
  const out = JSON.parse(execFileSync(process.execPath, [join(work, 'out/client.js'), base], { encoding: 'utf8' }));
  assert.equal(out.status, 'converged');
  assert.ok(out.iterations > 0 && out.residual < 1e-10, JSON.stringify(out));
  assert.deepEqual([out.http, out.code, out.field], [400, 'invalid_field', 'h']);
  assert.equal(out.version, doc.info.version);
  assert.equal(out.steps, 10);
  assert.ok(Number.isFinite(out.globalError), JSON.stringify(out));

  // The types are the document's: h as a string does not compile.
  writeFileSync(join(work, 'wrong.ts'), `
import createClient from 'openapi-fetch';
import type { paths } from './schema';
await createClient<paths, 'application/json'>({}).POST('/api/v1/solve', { body: { h: 'big' } });
`);
  writeFileSync(join(work, 'tsconfig.wrong.json'), tsconfig(['wrong.ts', 'schema.d.ts']));
  assert.throws(() => tsc('tsconfig.wrong.json'), (e) => /wrong\.ts.*TS2322|Type 'string' is not assignable/s.test(e.stdout));
});
