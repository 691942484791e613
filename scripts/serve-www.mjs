// A static server of www/ on a free local port for the scripts and tests that drive the page,
// with `extra` paths (such as '/die.stl') served from memory, and a bare page, /bare.html.
import http from 'node:http';
import fs from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

const root = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '../www');
const types = { '.html': 'text/html', '.js': 'text/javascript', '.css': 'text/css', '.wasm': 'application/wasm' };

/** Resolves with `{ server, base }` (`base`: the URL of www/, ending in '/'). */
export async function serveWww(extra = {}) {
  const server = http.createServer((req, res) => {
    const url = decodeURIComponent(new URL(req.url, 'http://x').pathname);
    if (extra[url]) { res.writeHead(200); res.end(extra[url]); return; }
    // A page with nothing on it beside swarf.js, for benchmarks: embed.html starts an engine
    // (and its warm-up) of its own.
    if (url === '/bare.html') { res.writeHead(200, { 'content-type': 'text/html' }); res.end('<!doctype html><title>swarf bench</title>'); return; }
    const file = path.join(root, url === '/' ? 'index.html' : url);
    if (!file.startsWith(root) || !fs.existsSync(file) || fs.statSync(file).isDirectory()) { res.writeHead(404); res.end(); return; }
    res.writeHead(200, { 'content-type': types[path.extname(file)] || 'application/octet-stream' });
    fs.createReadStream(file).pipe(res);
  });
  await new Promise((resolve) => server.listen(0, '127.0.0.1', resolve));
  return { server, base: `http://127.0.0.1:${server.address().port}/` };
}
