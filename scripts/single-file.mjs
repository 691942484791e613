// Builds www/dist/swarf.html: the page as one file (styles, scripts, the worker and the wasm
// inlined) that works opened straight from disk (file://), for shops without a server. Run
// after scripts/build-wasm.sh (which calls it). Each module keeps its own scope: it becomes a
// function returning what it exports, and an import becomes a lookup of those.
import fs from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { workerSource } from './worker-source.mjs';

const www = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '../www');
const read = (f) => fs.readFileSync(path.join(www, f), 'utf8');

// A module as an expression giving its exports (`export const|let|class|function|async function`).
function scoped(file) {
  let src = read(file);
  const names = [...src.matchAll(/^export (?:const|let|class|function|async function) ([\w$]+)/gm)].map((m) => m[1]);
  src = src.replace(/^export (const|let|class|function|async function) /gm, '$1 ');
  if (/^export /m.test(src)) throw new Error(`${file}: an export this build does not know`);
  return { src, names };
}

// Imports of sibling modules become lookups of their scopes.
function linked(src, modules) {
  return src.replace(/^import (\{[^}]*\}|\* as [\w$]+) from '\.\/([\w-]+)\.js';$/gm, (_, names, file) => {
    if (!modules.includes(file)) throw new Error(`an import of ${file}.js this build does not inline`);
    const bound = names.startsWith('*') ? names.slice(5) : names.replace(/ as /g, ': ');
    return `const ${bound} = __${file.replace(/-/g, '_')};`;
  });
}

// The worker as one classic script, made from a Blob.
const worker = workerSource(www);

// The page's modules, in order of use.
const modules = ['viewer', 'swarf', 'units', 'state', 'forms', 'gcode', 'simulation', 'zip', 'tools', 'operations', 'setups', 'part', 'results'];
let script = '';
for (const m of modules) {
  const { src, names } = scoped(`${m}.js`);
  script += `const __${m} = (() => {\n${linked(src, modules)}\nreturn { ${names.join(', ')} };\n})();\n`;
}
const wasm = fs.readFileSync(path.join(www, 'pkg/swarf_bg.wasm')).toString('base64');
script += `
const WORKER_SOURCE = ${JSON.stringify(worker)};
const WASM_BASE64 = '${wasm}';
window.SWARF_ENGINE_OPTIONS = {
  worker: () => new Worker(URL.createObjectURL(new Blob([WORKER_SOURCE], { type: 'text/javascript' }))),
  wasm: Uint8Array.from(atob(WASM_BASE64), (c) => c.charCodeAt(0)),
};
`;
script += linked(read('app.js'), modules);

let html = read('index.html');
const css = '<link rel="stylesheet" href="style.css">';
const app = '<script type="module" src="app.js"></script>';
if (!html.includes(css) || !html.includes(app)) throw new Error('index.html: its stylesheet or script tag changed');
// A script's text may not hold "</script"; the page's code never needs it escaped otherwise.
const safe = (s) => s.replace(/<\/script/gi, '<\\/script');
html = html.replace(css, () => `<style>\n${read('style.css')}\n</style>`).replace(app, () => `<script type="module">\n${safe(script)}\n</script>`);
fs.mkdirSync(path.join(www, 'dist'), { recursive: true });
fs.writeFileSync(path.join(www, 'dist/swarf.html'), html);
console.log(`www/dist/swarf.html: ${(html.length / 1e6).toFixed(1)} MB`);
