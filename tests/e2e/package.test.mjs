// swarf as an npm package (issue 41): the tarball scripts/build-package.sh makes (from the wasm
// scripts/build-wasm.sh built) installed into a scratch project, bundled by esbuild with no
// configuration, opened in Chromium: a job run on a part, one cancelled, the next run, the
// G-code read by LinuxCNC's rs274; a strict TypeScript portal compiled against the installed
// types; the tarball's contents and size.
import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import fs from 'node:fs';
import http from 'node:http';
import os from 'node:os';
import path from 'node:path';
import { execFileSync } from 'node:child_process';
import { root, browser, PATIENCE, toolTable } from './harness.mjs';

const repo = path.resolve(root, '..');
const bin = (name) => path.join(repo, 'node_modules/.bin', name);
/** The most the tarball may weigh (bytes), as the package's README says. */
const MOST = 2.5e6;
let tarball, scratch, server, base;

before(() => {
  execFileSync('bash', ['scripts/build-package.sh', '--no-wasm'], { cwd: repo, stdio: 'pipe' });
  const dir = path.join(repo, 'target/package');
  tarball = path.join(dir, fs.readdirSync(dir).find((f) => /^swarf-.*\.tgz$/.test(f)));
  // A portal's project: nothing but the tarball installed, and its own code.
  scratch = fs.mkdtempSync(path.join(os.tmpdir(), 'swarf-portal-'));
  fs.writeFileSync(path.join(scratch, 'package.json'), JSON.stringify({ name: 'portal', private: true, type: 'module' }));
  execFileSync('npm', ['install', '--offline', '--no-audit', '--no-fund', tarball], { cwd: scratch, stdio: 'pipe' });
});

after(() => server?.close());

test('the tarball holds the engine, its worker, wasm, types, README and licences, and no test data, source maps or machine paths, under its stated size', () => {
  const files = execFileSync('tar', ['tzf', tarball], { encoding: 'utf8' }).trim().split('\n').map((f) => f.replace(/^package\//, ''));
  for (const f of ['package.json', 'index.js', 'index.d.ts', 'core.js', 'engine.js', 'engine.d.ts', 'worker.js', 'pkg/swarf.js', 'pkg/swarf_bg.wasm', 'types/swarf-types.d.ts', 'README.md', 'THIRD-PARTY.md', 'LICENSE-MIT', 'LICENSE-APACHE']) assert.ok(files.includes(f), `${f} is missing from ${files.join(', ')}`);
  assert.deepEqual(files.filter((f) => /\.(map|stl|obj|gltf|glb|dxf|svg|ngc|nc|tap|tsv)$/i.test(f) || /^(tests?|data|src)\//.test(f)), []);
  const size = fs.statSync(tarball).size;
  assert.ok(size < MOST, `the tarball is ${size} bytes`);
  const readme = fs.readFileSync(path.join(scratch, 'node_modules/swarf/README.md'), 'utf8');
  assert.match(readme, /stays under 2\.5 MB/);
  assert.match(readme, /npm install \.\/swarf-/);
  // No path of the machine that built it: neither this checkout nor the crates' sources.
  const installed = path.join(scratch, 'node_modules/swarf');
  const home = os.homedir();
  for (const f of files) {
    const text = fs.readFileSync(path.join(installed, f)).toString('latin1');
    for (const p of [repo, home, path.join(home, '.cargo')]) assert.ok(!text.includes(p), `${f} holds ${p}`);
  }
  const pkg = JSON.parse(fs.readFileSync(path.join(installed, 'package.json'), 'utf8'));
  const cargo = fs.readFileSync(path.join(repo, 'Cargo.toml'), 'utf8').match(/^version\s*=\s*"([^"]*)"/m)[1];
  assert.equal(pkg.version, cargo);
  assert.equal(pkg.type, 'module');
  assert.equal(pkg.sideEffects, false);
  assert.equal(pkg.exports['.'].types, './index.d.ts');
  assert.match(fs.readFileSync(path.join(installed, 'THIRD-PARTY.md'), 'utf8'), /\| glam \| [\d.]+ \| MIT OR Apache-2\.0 \|/);
  assert.deepEqual(pkg.engines, { node: '>=18' });
  // Every licence the crates inside carry is named in the README's licence paragraph.
  const third = fs.readFileSync(path.join(installed, 'THIRD-PARTY.md'), 'utf8');
  const licences = new Set([...third.matchAll(/^\| [^|]+ \| [^|]+ \| ([^|]+) \|$/gm)].slice(1).flatMap((m) => m[1].split(/ OR | AND |\/|[()]/).map((l) => l.trim()).filter(Boolean)));
  for (const l of licences) assert.ok(readme.includes(l), `the README's licences leave out ${l}`);
});

test('a strict TypeScript portal compiles against the installed package\'s types, and a wrong field does not', () => {
  const ts = `import { createEngine, CancelledError, UnsafeProgramError, JobError, FileError, type JobInput, type RunResult, type Engine, type Tool, type Operation, type Setup, type Holder, type RoughAdaptive } from 'swarf';
// The package README's progress and cancel, as it stands there.
declare const cancelButton: HTMLButtonElement, bar: HTMLProgressElement, label: HTMLElement;
declare function markField(path: string, message: string): void;
declare function showError(message: string): void;
export async function cancellable(engine: Engine, job: JobInput, bytes: Uint8Array): Promise<void> {
  const controller = new AbortController();
  cancelButton.onclick = () => controller.abort();
  try {
    const r = await engine.run(job, bytes, 'part.stl', {
      signal: controller.signal,
      onProgress: (fraction, stage) => { bar.value = fraction; label.textContent = stage; },
    });
    void r;
  } catch (e) {
    if (e instanceof CancelledError) { /* cancelled */ }
    else if (e instanceof JobError) markField(e.path, e.message);
    else if (e instanceof FileError) showError(e.message);
    else throw e;
  }
}
import { createEngine as fromFiles } from 'swarf/files';
export async function portal(bytes: Uint8Array, signal: AbortSignal): Promise<string> {
  const engine: Engine = await createEngine({ workers: 2, warmUp: false });
  const job: JobInput = { tools: [{ number: 1, shape: 'flat', diameter: 6 }], operations: [{ kind: 'roughZlevel', tool: 1, stepdown: 2 }], post: { dialect: 'grbl' } };
  const problems = await engine.checkJob(job);
  if (problems.length) throw new Error(problems.map((p) => p.message).join('; '));
  const r: RunResult = await engine.run(job, bytes, 'part.stl', { signal, onProgress: (f: number, stage: string) => console.log(f, stage) });
  const seconds: number = r.summary.cycle.seconds;
  // The README's download: a Blob of the program's bytes, in strict TypeScript.
  const blob = new Blob([r.gcodeBytes], { type: 'text/plain' });
  // The default job takes operations written as inputs.
  const own = engine.defaultJob();
  own.operations.push({ kind: 'drill', tool: 1 });
  try {
    await engine.run(own, bytes, 'part.stl');
  } catch (e) {
    if (e instanceof UnsafeProgramError) console.log(e.problem, e.result.summary.moves);
  }
  const anyway: RunResult = await engine.run(own, bytes, 'part.stl', { allowUnsafe: true });
  engine.close();
  void fromFiles;
  void CancelledError;
  void blob;
  void anyway;
  // Every job type by name, as the README names them.
  const named: [Tool | null, Operation | null, Setup | null, Holder | null, RoughAdaptive | null] = [null, null, null, null, null];
  void named;
  return \`\${r.gcode.length} \${seconds}\`;
}
`;
  fs.writeFileSync(path.join(scratch, 'portal.ts'), ts);
  // As a bundler resolves modules, and as Node does (nodenext, with skipLibCheck: an import
  // of the generated types without its .js once made every type silently \`any\` there).
  // By the newest TypeScript and by 5.0, the oldest the types are for (typed arrays became
  // generic in 5.7: the program's bytes are typed for both).
  for (const typescript of ['typescript', 'typescript-5.0']) {
    for (const resolution of [['--module', 'esnext', '--moduleResolution', 'bundler'], ['--module', 'nodenext', '--moduleResolution', 'nodenext', '--skipLibCheck']]) {
      const tsc = (file) => execFileSync(process.execPath, [path.join(repo, 'node_modules', typescript, 'bin/tsc'), '--strict', '--noEmit', '--target', 'es2022', ...resolution, '--lib', 'es2022,dom', file], { cwd: scratch, encoding: 'utf8', stdio: 'pipe' });
      try {
        tsc('portal.ts');
      } catch (e) {
        assert.fail(`${typescript} ${resolution.join(' ')}: ${e.stdout}`);
      }
      // The types say what a job may hold: a misspelt field fails the compile.
      fs.writeFileSync(path.join(scratch, 'wrong.ts'), ts.replace('stepdown: 2', 'stepDown: 2'));
      assert.throws(() => tsc('wrong.ts'), (e) => /stepDown/.test(String(e.stdout)), `${typescript} ${resolution.join(' ')}`);
    }
  }
});

test('installed and bundled by esbuild with no configuration, the portal runs a job, cancels one, runs again, and rs274 reads its G-code', async () => {
  const portal = `import { createEngine } from 'swarf';
const engine = await createEngine({ workers: 2 });
window.portal = {
  engine,
  // A run on the sample part: its program, or how it ended.
  async run(cancelAfterProgress) {
    const job = engine.defaultJob();
    job.operations = job.operations.filter((op) => op.kind === 'finishRaster').slice(0, 1);
    job.operations[0].stepover = cancelAfterProgress ? 0.2 : 1.5;
    const controller = new AbortController();
    let progress = 0;
    try {
      const r = await engine.run(job, engine.sample, 'sample.stl', {
        signal: controller.signal,
        onProgress: () => { progress++; if (cancelAfterProgress && progress === 2) controller.abort(); },
      });
      return { ok: true, gcode: r.gcode, moves: r.summary.moves, tools: job.tools, progress };
    } catch (e) {
      return { ok: false, name: e.name, message: e.message, progress };
    }
  },
};
document.body.dataset.ready = 'true';
`;
  fs.writeFileSync(path.join(scratch, 'portal.js'), portal);
  const dist = path.join(scratch, 'dist');
  fs.mkdirSync(dist, { recursive: true });
  execFileSync(bin('esbuild'), ['portal.js', '--bundle', '--format=esm', '--outfile=dist/portal.js'], { cwd: scratch, stdio: 'pipe' });
  fs.writeFileSync(path.join(dist, 'index.html'), '<!doctype html><meta charset="utf-8"><title>portal</title><link rel="icon" href="data:,"><script type="module" src="portal.js"></script>');
  // The bundle is the only script served: no worker.js or wasm beside it.
  assert.deepEqual(fs.readdirSync(dist).sort(), ['index.html', 'portal.js']);
  // The bundle's folder at /, and the installed package's files as they are at /swarf/ (for
  // the `swarf/files` entry, imported unbundled).
  const installed = path.join(scratch, 'node_modules/swarf');
  const types = { '.js': 'text/javascript', '.html': 'text/html', '.wasm': 'application/wasm' };
  server = http.createServer((req, res) => {
    const name = decodeURIComponent(new URL(req.url, 'http://x').pathname);
    const [dir, rest] = name.startsWith('/swarf/') ? [installed, name.slice('/swarf'.length)] : [dist, name === '/' ? '/index.html' : name];
    const file = path.join(dir, rest);
    if (!file.startsWith(dir) || !fs.existsSync(file) || fs.statSync(file).isDirectory()) { res.writeHead(404); res.end(); return; }
    res.writeHead(200, { 'content-type': types[path.extname(file)] ?? 'application/octet-stream' });
    fs.createReadStream(file).pipe(res);
  });
  await new Promise((resolve) => server.listen(0, '127.0.0.1', resolve));
  base = `http://127.0.0.1:${server.address().port}/`;
  const context = await browser.newContext();
  context.setDefaultTimeout(PATIENCE);
  const page = await context.newPage();
  const errors = [];
  const asked = [];
  page.on('pageerror', (e) => errors.push(String(e)));
  page.on('request', (r) => asked.push(r.url()));
  await page.goto(base);
  await page.waitForFunction(() => document.body?.dataset.ready === 'true');
  assert.equal(await page.evaluate(() => window.portal.engine.workers), 2);
  const first = await page.evaluate(() => window.portal.run(false));
  assert.ok(first.ok, first.message);
  assert.ok(first.moves > 1000, `${first.moves} moves`);
  const cancelled = await page.evaluate(() => window.portal.run(true));
  assert.equal(cancelled.ok, false);
  assert.equal(cancelled.name, 'AbortError', cancelled.message);
  const again = await page.evaluate(() => window.portal.run(false));
  assert.ok(again.ok, again.message);
  assert.equal(again.gcode, first.gcode);
  // What the page asked for: the page and the bundle, nothing else (no worker or wasm file).
  assert.deepEqual([...new Set(asked.filter((u) => !u.startsWith('blob:')))].sort(), [base, `${base}portal.js`].sort());
  const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'swarf-portal-gcode-'));
  const program = path.join(dir, 'portal.ngc');
  fs.writeFileSync(program, first.gcode);
  fs.writeFileSync(path.join(dir, 'tool.tbl'), toolTable(first.tools));
  const canon = execFileSync('rs274', ['-g', '-t', path.join(dir, 'tool.tbl'), program], { cwd: dir, env: { ...process.env, HOME: dir }, encoding: 'utf8', maxBuffer: 1 << 28 });
  assert.ok(canon.split('\n').filter((l) => l.includes('STRAIGHT_FEED(')).length > 1000);
  // The files entry, unbundled: its worker and wasm found beside its module.
  fs.writeFileSync(path.join(dist, 'files.html'), `<!doctype html><meta charset="utf-8"><title>files</title><link rel="icon" href="data:,"><script type="module">
import { createEngine } from '/swarf/engine.js';
const engine = await createEngine({ workers: 1, warmUp: false });
const job = engine.defaultJob('drawing');
const r = await engine.run(job, engine.sampleDrawing, 'sample.dxf');
document.body.dataset.moves = String(r.summary.moves);
</script>`);
  asked.length = 0;
  await page.goto(`${base}files.html`);
  await page.waitForFunction(() => Number(document.body?.dataset.moves) > 0);
  const files = asked.map((u) => new URL(u).pathname);
  for (const f of ['/swarf/engine.js', '/swarf/worker.js', '/swarf/pkg/swarf.js', '/swarf/pkg/swarf_bg.wasm']) assert.ok(files.includes(f), `${f} not asked for: ${files.join(', ')}`);
  assert.deepEqual(errors, []);
  await context.close();
});

test('under Node, both entries run a job in worker_threads: importing is safe and createEngine works, as the compared packages do', () => {
  const script = (entry) => `import { createEngine } from '${entry}';
const engine = await createEngine({ warmUp: false });
const job = engine.defaultJob();
job.operations = job.operations.filter((op) => op.kind === 'finishRaster').slice(0, 1);
const r = await engine.run(job, engine.sample, 'sample.stl');
console.log(JSON.stringify({ workers: engine.workers, moves: r.summary.moves, lines: r.gcode.split('\\n').length, problem: r.summary.problem ?? null }));
engine.close();
`;
  const said = {};
  for (const entry of ['swarf', 'swarf/files']) {
    const file = path.join(scratch, `node-${entry.replace('/', '-')}.mjs`);
    fs.writeFileSync(file, script(entry));
    // It ends by itself once the engine is closed (no worker left running).
    const out = execFileSync(process.execPath, [file], { cwd: scratch, encoding: 'utf8', timeout: PATIENCE });
    said[entry] = JSON.parse(out.trim().split('\n').at(-1));
    assert.ok(said[entry].moves > 1000 && said[entry].lines > 1000 && said[entry].problem === null, `${entry}: ${out}`);
    assert.ok(said[entry].workers >= 1);
  }
  assert.equal(said.swarf.moves, said['swarf/files'].moves);
});

test('Vite and webpack production builds of both entries run a job under a strict Content-Security-Policy, with no configuration', async () => {
  const app = (entry) => `import { createEngine } from '${entry}';
(async () => {
  const engine = await createEngine({ workers: 1, warmUp: false });
  const r = await engine.run(engine.defaultJob('drawing'), engine.sampleDrawing, 'sample.dxf');
  document.body.dataset.moves = String(r.summary.moves);
})().catch((e) => { document.body.dataset.error = e.message; });
`;
  // What each entry needs of a page's policy (the package README's table).
  const policy = {
    swarf: "default-src 'none'; script-src 'self' 'wasm-unsafe-eval'; worker-src blob:",
    'swarf/files': "default-src 'none'; script-src 'self' 'wasm-unsafe-eval'; worker-src 'self'; connect-src 'self'",
  };
  const types = { '.js': 'text/javascript', '.html': 'text/html', '.wasm': 'application/wasm' };
  const builds = [];
  for (const entry of ['swarf', 'swarf/files']) {
    const dir = fs.mkdtempSync(path.join(scratch, 'bundle-'));
    fs.writeFileSync(path.join(dir, 'app.js'), app(entry));
    fs.writeFileSync(path.join(dir, 'index.html'), '<!doctype html><meta charset="utf-8"><title>portal</title><link rel="icon" href="data:,"><script type="module" src="/app.js"></script>');
    // Vite: its own defaults, from the project's folder (node_modules/swarf found from there).
    execFileSync(bin('vite'), ['build', dir, '--outDir', path.join(dir, 'vite'), '--logLevel', 'error'], { cwd: scratch, stdio: 'pipe' });
    builds.push({ entry, dist: path.join(dir, 'vite'), by: 'Vite' });
    // webpack: production mode, nothing but the entry; it warns of nothing but the wasm's size.
    const out = execFileSync(bin('webpack'), ['--mode', 'production', '--entry', path.join(dir, 'app.js'), '--output-path', path.join(dir, 'webpack')], { cwd: scratch, encoding: 'utf8', stdio: 'pipe' });
    const warnings = out.split('\n').filter((l) => /^WARNING in/.test(l) && !/asset size limit|entrypoint size limit|webpack performance/.test(l));
    assert.deepEqual(warnings, [], `webpack warned: ${out}`);
    fs.writeFileSync(path.join(dir, 'webpack/index.html'), '<!doctype html><meta charset="utf-8"><title>portal</title><link rel="icon" href="data:,"><script src="main.js"></script>');
    builds.push({ entry, dist: path.join(dir, 'webpack'), by: 'webpack' });
  }
  // The default entry's bundle ships no wasm or worker file beside it: it has its own inside
  // (once 4.7 MB deployed for the 1.7 MB it used).
  for (const { dist, by } of builds.filter((b) => b.entry === 'swarf')) {
    const shipped = fs.readdirSync(dist, { recursive: true }).map(String);
    assert.deepEqual(shipped.filter((f) => /\.wasm$|worker/i.test(f)), [], `${by} shipped with the default entry: ${shipped.join(', ')}`);
  }
  const context = await browser.newContext();
  context.setDefaultTimeout(PATIENCE);
  for (const { entry, dist, by } of builds) {
    const site = http.createServer((req, res) => {
      const name = decodeURIComponent(new URL(req.url, 'http://x').pathname);
      const file = path.join(dist, name === '/' ? 'index.html' : name);
      if (!file.startsWith(dist) || !fs.existsSync(file) || fs.statSync(file).isDirectory()) { res.writeHead(404); res.end(); return; }
      res.writeHead(200, { 'content-type': types[path.extname(file)] ?? 'application/octet-stream', 'content-security-policy': policy[entry] });
      fs.createReadStream(file).pipe(res);
    });
    await new Promise((resolve) => site.listen(0, '127.0.0.1', resolve));
    const page = await context.newPage();
    const errors = [];
    page.on('pageerror', (e) => errors.push(String(e)));
    await page.goto(`http://127.0.0.1:${site.address().port}/`);
    await page.waitForFunction(() => document.body?.dataset.moves || document.body?.dataset.error);
    const said = await page.evaluate(() => ({ ...document.body.dataset }));
    assert.ok(Number(said.moves) > 100, `${by}, ${entry}: ${JSON.stringify(said)}`);
    assert.deepEqual(errors, [], `${by}, ${entry}`);
    await page.close();
    site.close();
  }
  await context.close();
});

test('a portal gets typed errors (a bad job names its field, a bad file its name), abort(reason) rejects with the reason, and a Node script that never closes the engine still ends', () => {
  const script = `import { createEngine, JobError, FileError, CancelledError } from 'swarf';
const engine = await createEngine({ workers: 1, warmUp: false });
const out = {};
const catching = async (key, work) => { try { await work(); out[key] = 'resolved'; } catch (e) { out[key] = { cls: e.constructor.name, job: e instanceof JobError, file: e instanceof FileError, cancelled: e instanceof CancelledError, path: e.path ?? null, name: e.file ?? null, message: e.message }; } };
await catching('field', () => { const j = engine.defaultJob(); j.operations[0].stepdown = -1; return engine.run(j, engine.sample, 'sample.stl'); });
await catching('typo', () => { const j = engine.defaultJob(); j.tools[0].diamter = 3; return engine.run(j, engine.sample, 'sample.stl'); });
await catching('setups', () => { const j = engine.defaultJob(); j.setups = [{ name: 'a', operations: [] }]; return engine.run(j, engine.sample, 'sample.stl'); });
await catching('file', () => engine.run(engine.defaultJob(), new Uint8Array([1, 2, 3]), 'broken.stl'));
const why = new Error('the customer left the page');
const c = new AbortController();
await catching('reason', () => engine.run(engine.defaultJob(), engine.sample, 'sample.stl', { signal: c.signal, onProgress: () => c.abort(why) }));
out.reasonIsIt = out.reason?.message === why.message;
const bare = new AbortController();
await catching('abort', () => engine.run(engine.defaultJob(), engine.sample, 'sample.stl', { signal: bare.signal, onProgress: () => bare.abort() }));
console.log(JSON.stringify(out));
// No close(): the idle workers keep nothing alive.
`;
  const file = path.join(scratch, 'node-errors.mjs');
  fs.writeFileSync(file, script);
  const out = JSON.parse(execFileSync(process.execPath, [file], { cwd: scratch, encoding: 'utf8', timeout: PATIENCE }).trim().split('\n').at(-1));
  assert.deepEqual([out.field.cls, out.field.job, out.field.path], ['JobError', true, 'operations[0].stepdown'], JSON.stringify(out.field));
  assert.deepEqual([out.typo.cls, out.typo.path], ['JobError', 'tools[0].diamter'], JSON.stringify(out.typo));
  assert.deepEqual([out.setups.cls, out.setups.path], ['JobError', 'setups'], JSON.stringify(out.setups));
  assert.deepEqual([out.file.cls, out.file.file, out.file.name], ['FileError', true, 'broken.stl'], JSON.stringify(out.file));
  assert.ok(out.reasonIsIt && !out.reason.cancelled, JSON.stringify(out.reason));
  assert.deepEqual([out.abort.cls, out.abort.cancelled], ['CancelledError', true], JSON.stringify(out.abort));
});
