// Makes swarf's npm package folder, target/package/swarf/, from what scripts/build-wasm.sh
// built in www/ (scripts/build-package.sh runs both, then `npm pack`). Two entries:
//   swarf        index.js: the engine with its worker and wasm inside the module (a Blob worker,
//                the wasm's bytes), so any bundler (esbuild, Vite, webpack, Rollup) or none
//                takes it with no configuration;
//   swarf/files  engine.js: the same engine finding worker.js and pkg/swarf_bg.wasm beside it
//                (`new URL('./worker.js', import.meta.url)`), for pages that serve the package's
//                files as they are (smaller, and no `blob:` worker for a strict CSP).
// The types: swarf.d.ts and the types generated from the Rust serde types, for both entries.
import fs from 'node:fs';
import zlib from 'node:zlib';
import path from 'node:path';
import { execFileSync } from 'node:child_process';
import { fileURLToPath } from 'node:url';
import { workerSource } from './worker-source.mjs';

const repo = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '..');
const www = path.join(repo, 'www');
const out = path.join(repo, 'target/package/swarf');
fs.rmSync(out, { recursive: true, force: true });
fs.mkdirSync(path.join(out, 'pkg'), { recursive: true });
fs.mkdirSync(path.join(out, 'types'), { recursive: true });

const cargo = fs.readFileSync(path.join(repo, 'Cargo.toml'), 'utf8');
const field = (name) => cargo.match(new RegExp(`^${name}\\s*=\\s*"([^"]*)"`, 'm'))?.[1];
const version = field('version');
const license = field('license');
if (!version || !license) throw new Error('Cargo.toml: no version or license');

const copy = (from, to = from) => fs.copyFileSync(path.join(www, from), path.join(out, to));
// The files entry: the page's own module, worker and wasm, as the page serves them.
// The engine itself (core.js) names no worker: a bundler that meets
// `new URL('./worker.js', import.meta.url)` ships the worker and its 3 MB wasm with the bundle,
// which the default entry (its own inside) never loads. The files entry (engine.js) adds it.
const engineSource = fs.readFileSync(path.join(www, 'swarf.js'), 'utf8');
const ownWorker = "return new Worker(new URL('./worker.js', import.meta.url), { type: 'module' });";
if (!engineSource.includes(ownWorker)) throw new Error('www/swarf.js no longer makes its worker as package.mjs expects');
fs.writeFileSync(
  path.join(out, 'core.js'),
  `// Generated from swarf's www/swarf.js: the engine, its worker given by the entry importing it.\n${engineSource.replace(ownWorker, "throw new Error('no worker: give createEngine a worker or a workerUrl');")}`,
);
fs.writeFileSync(
  path.join(out, 'engine.js'),
  `// swarf's files entry (\`swarf/files\`): the engine (core.js) with its worker and wasm found beside
// this module, as a page serves the package's files or a bundler follows them.
import { createEngine as createFrom } from './core.js';

export * from './core.js';

/** Starts an engine (see engine.d.ts): its workers run worker.js beside this module. */
export async function createEngine(options = {}) {
  if (options.worker || options.workerUrl || typeof Worker === 'undefined') return createFrom(options);
  // Written as bundlers look for it (Vite, webpack, Parcel, Rollup's plugins): the worker and
  // the wasm it loads beside it are followed and emitted with the bundle.
  return createFrom({ ...options, worker: () => new Worker(new URL('./worker.js', import.meta.url), { type: 'module' }) });
}
`,
);
copy('worker.js');
copy('node-worker.js');
copy('pkg/swarf.js');
copy('pkg/swarf_bg.wasm');
copy('types/swarf-types.d.ts');
copy('swarf.d.ts', 'engine.d.ts');

// The smallest gzip of `file`: zopfli's (Debian's `zopfli`, which scripts/setup.sh installs:
// 4 % smaller than zlib's best on the wasm, and any gzip reader reads it), else zlib's best.
function gzipFile(file) {
  try {
    return execFileSync('zopfli', ['--i5', '-c', file], { maxBuffer: 1 << 28 });
  } catch {
    return zlib.gzipSync(fs.readFileSync(file), { level: 9 });
  }
}

// The self-contained entry: the worker as one classic script and the wasm gzipped as base64,
// inside (gzipped first, it costs the package a third of what base64 of the bare wasm does).
const inline = `// The engine's worker (wasm-bindgen's glue and worker.js as one script) and its wasm (gzipped,
// as base64), kept inside the module so that a bundler needs no configuration to ship them.
// Generated.
export const WORKER_SOURCE = ${JSON.stringify(workerSource(www))};
export const WASM_GZIP_BASE64 = '${gzipFile(path.join(www, 'pkg/swarf_bg.wasm')).toString('base64')}';
`;
fs.writeFileSync(path.join(out, 'inline.js'), inline);
fs.writeFileSync(
  path.join(out, 'index.js'),
  `// swarf's engine, its worker and wasm inside this module: \`import { createEngine } from 'swarf'\`.
// Options as engine.js takes them (see index.d.ts); a \`worker\` or \`workerUrl\` given is used
// instead of the one inside (then \`wasm\` defaults to pkg/swarf_bg.wasm beside that worker).
import { createEngine as createFrom } from './core.js';
import { WORKER_SOURCE, WASM_GZIP_BASE64 } from './inline.js';

export * from './core.js';

let workerUrl = null;
let wasm = null;

function inlineWorker() {
  workerUrl ??= URL.createObjectURL(new Blob([WORKER_SOURCE], { type: 'text/javascript' }));
  return new Worker(workerUrl);
}

// The wasm inside this module, unpacked once by the platform's own DecompressionStream
// (browsers and Node alike).
function inlineWasm() {
  wasm ??= (async () => {
    const text = atob(WASM_GZIP_BASE64);
    const packed = new Uint8Array(text.length);
    for (let i = 0; i < text.length; i++) packed[i] = text.charCodeAt(i);
    const unpacked = new Blob([packed]).stream().pipeThrough(new DecompressionStream('gzip'));
    return new Uint8Array(await new Response(unpacked).arrayBuffer());
  })();
  return wasm;
}

/** Starts an engine (see engine.js): its workers made from the worker inside this module. */
export async function createEngine(options = {}) {
  if (options.worker || options.workerUrl) return createFrom(options);
  // Under Node (no Web Worker): worker_threads running node-worker.js beside engine.js, with
  // the wasm inside this module.
  if (typeof Worker === 'undefined') return createFrom({ ...options, wasm: options.wasm ?? (await inlineWasm()) });
  return createFrom({ ...options, worker: inlineWorker, wasm: options.wasm ?? (await inlineWasm()) });
}
`,
);
fs.writeFileSync(path.join(out, 'index.d.ts'), "// swarf's engine with its worker and wasm inside the module; the API is engine.d.ts's.\nexport * from './engine.js';\n");

// The licences: swarf's, and those of the crates built into the wasm (from cargo's own tree).
for (const f of ['LICENSE-MIT', 'LICENSE-APACHE']) fs.copyFileSync(path.join(repo, f), path.join(out, f));
const tree = execFileSync('cargo', ['tree', '--target', 'wasm32-unknown-unknown', '-e', 'normal', '--prefix', 'none', '--format', '{p}|{l}'], { cwd: repo, encoding: 'utf8' });
const crates = [...new Set(tree.split('\n').filter((l) => l.includes('|')).map((l) => l.replace(/ \((\*|proc-macro|\/[^)]*)\)/g, '').trim()))]
  .filter((l) => !l.startsWith('swarf '))
  .sort();
fs.writeFileSync(
  path.join(out, 'THIRD-PARTY.md'),
  `# The crates inside swarf_bg.wasm\n\nswarf ${version} is ${license}. The wasm is built from these Rust crates (and the procedural macros that generate some of their code), each under the licence crates.io gives:\n\n| crate | version | licence |\n|---|---|---|\n${crates
    .map((l) => {
      const [p, lic] = l.split('|');
      const [name, v] = p.split(' ');
      return `| ${name} | ${v.replace(/^v/, '')} | ${lic} |`;
    })
    .join('\n')}\n`,
);

fs.copyFileSync(path.join(repo, 'package/README.md'), path.join(out, 'README.md'));
const pkg = {
  name: 'swarf',
  version,
  description: 'CAM in the browser: parts (STL, glTF, OBJ) and drawings (DXF, SVG) in, gouge-free tool paths and G-code out, in a Web Worker.',
  license,
  type: 'module',
  main: './index.js',
  module: './index.js',
  types: './index.d.ts',
  exports: {
    '.': { types: './index.d.ts', default: './index.js' },
    './files': { types: './engine.d.ts', default: './engine.js' },
    // The files entry's worker and wasm, for a page or bundler that places them itself.
    './worker.js': './worker.js',
    './pkg/swarf.js': './pkg/swarf.js',
    './swarf_bg.wasm': './pkg/swarf_bg.wasm',
    './pkg/swarf_bg.wasm': './pkg/swarf_bg.wasm',
    './package.json': './package.json',
  },
  files: ['index.js', 'index.d.ts', 'inline.js', 'core.js', 'engine.js', 'engine.d.ts', 'worker.js', 'node-worker.js', 'pkg/swarf.js', 'pkg/swarf_bg.wasm', 'types/swarf-types.d.ts', 'README.md', 'THIRD-PARTY.md', 'LICENSE-MIT', 'LICENSE-APACHE'],
  sideEffects: false,
  // Node 18 is the oldest the package is tried on (tests/e2e/package.test.mjs runs it on the
  // machine's Node; the issue's trial ran 18 and 20).
  engines: { node: '>=18' },
  keywords: ['cam', 'cnc', 'g-code', 'gcode', 'toolpath', 'milling', 'wasm', 'stl', 'dxf'],
};
fs.writeFileSync(path.join(out, 'package.json'), `${JSON.stringify(pkg, null, 2)}\n`);
console.log(`target/package/swarf: swarf ${version}`);
