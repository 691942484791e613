// The engine's worker as one classic script (wasm-bindgen's glue, then worker.js with its import
// of the glue bound), for a worker made from a Blob: the single-file page (single-file.mjs) and
// the npm package's self-contained entry (package.mjs) both inline it with the wasm's bytes.
import fs from 'node:fs';
import path from 'node:path';

export function workerSource(www) {
  const read = (f) => fs.readFileSync(path.join(www, f), 'utf8');
  let glue = read('pkg/swarf.js');
  glue = glue.replace(/^export (function|class|async function) /gm, '$1 ').replace(/^export \{[^}]*\};?\s*$/m, '').replace(/import\.meta\.url/g, 'self.location.href');
  if (/^export /m.test(glue)) throw new Error('pkg/swarf.js: an export this build does not know');
  let worker = read('worker.js');
  const imported = /^import init, \{([^}]*)\} from '\.\/pkg\/swarf\.js';$/m;
  if (!imported.test(worker)) throw new Error('worker.js: its import of the glue changed');
  worker = worker.replace(imported, 'const init = __wbg_init;');
  return `${glue}\n${worker}`;
}
