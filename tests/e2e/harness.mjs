// The harness of the page's end-to-end tests: the page served from www/ on 127.0.0.1 to a
// headless Chromium (Debian's, driven by playwright-core) for each test file that imports it,
// and what the tests share: waiting on the page's own signals, its tabs, pixels of the view,
// LinuxCNC's rs274 and GRBL's own parser on the programs it downloads, parts made here.
import { before, after } from 'node:test';
import assert from 'node:assert/strict';
import http from 'node:http';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { execFileSync } from 'node:child_process';
import { fileURLToPath, pathToFileURL } from 'node:url';
import { chromium } from 'playwright-core';

export const root = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '../../www');
const types = { '.html': 'text/html', '.js': 'text/javascript', '.mjs': 'text/javascript', '.css': 'text/css', '.wasm': 'application/wasm' };
export const shots = path.resolve(root, '../target/e2e');
fs.mkdirSync(shots, { recursive: true });

let server;
export let browser, base;
export const offsite = [];

before(async () => {
  server = http.createServer((req, res) => {
    const url = new URL(req.url, 'http://x');
    const file = path.join(root, url.pathname === '/' ? 'index.html' : decodeURIComponent(url.pathname));
    if (!file.startsWith(root) || !fs.existsSync(file) || fs.statSync(file).isDirectory()) { res.writeHead(404); res.end(); return; }
    res.writeHead(200, { 'content-type': types[path.extname(file)] || 'application/octet-stream' });
    fs.createReadStream(file).pipe(res);
  });
  await new Promise((resolve) => server.listen(0, '127.0.0.1', resolve));
  base = `http://127.0.0.1:${server.address().port}/`;
  browser = await chromium.launch({
    executablePath: process.env.CHROMIUM || '/usr/bin/chromium',
    headless: true,
    args: ['--no-sandbox', '--disable-background-networking', '--disable-component-update', '--no-first-run', '--disable-sync', '--disable-dev-shm-usage'],
  });
});

after(async () => {
  await browser?.close();
  server?.close();
});

// Waits are bounded by what the page itself signals, not by short fixed timeouts: a Generate is
// awaited until the page says it ended (body[data-generated]), failing only if its progress bar
// and stage stand still for two minutes; other waits get five minutes, so that a machine busy
// with other builds passes too.
export const PATIENCE = Number(process.env.PATIENCE ?? 300000);

export async function waitForGenerated(page) {
  let last = null, since = Date.now();
  for (;;) {
    const now = await page.evaluate(() => ({ state: document.body.dataset.generated, progress: document.getElementById('progress').value, stage: document.getElementById('stage').textContent }));
    if (now.state && now.state !== 'running') return now.state;
    const key = `${now.progress} ${now.stage}`;
    if (key !== last) { last = key; since = Date.now(); }
    else if (Date.now() - since > 120000) throw new Error(`Generate stalled at ${key}`);
    await page.waitForTimeout(250);
  }
}

export async function generated(page) {
  const state = await waitForGenerated(page);
  assert.equal(state, 'ok', await page.textContent('#message'));
  await frame(page);
}

// The settings' tab `name` (part, stock, tools, ops, post): a field is filled where it shows.
export async function tab(page, name) {
  await page.click(`#tabs [data-tab="${name}"]`);
}

// Two frames of the page: the view draws at the next frame after a change.
export async function frame(page) {
  await page.evaluate(() => new Promise((resolve) => requestAnimationFrame(() => requestAnimationFrame(resolve))));
}

// GRBL 1.1h's own parser on a program (../shared/tools/grbl/grblcheck), where the shared tools
// are beside this checkout: null where they are not, else what it said.
export const grblcheckTool = path.resolve(root, '../../shared/tools/grbl/grblcheck');
export function grblcheck(file) {
  if (!fs.existsSync(grblcheckTool)) { console.log(`skipping GRBL's own parser: ${grblcheckTool} is absent`); return null; }
  try {
    // One at a time over every process (flock, as tests/common does): a first call builds the
    // validator into a folder it empties first, and two at once emptied each other's build.
    return { ok: true, said: execFileSync('flock', [path.join(os.tmpdir(), 'swarf-grblcheck.lock'), 'bash', grblcheckTool, file], { encoding: 'utf8' }) };
  } catch (e) {
    return { ok: false, said: `${e.stdout}${e.stderr}` };
  }
}

export async function openPage() {
  const context = await browser.newContext({ acceptDownloads: true, viewport: { width: 1280, height: 800 } });
  context.setDefaultTimeout(PATIENCE);
  const page = await context.newPage();
  const errors = [];
  page.on('pageerror', (e) => errors.push(String(e)));
  page.on('request', (r) => { if (!r.url().startsWith(base) && !r.url().startsWith('blob:') && !r.url().startsWith('data:')) offsite.push(r.url()); });
  await page.goto(base);
  await page.waitForSelector('body[data-ready="true"]');
  await page.waitForFunction(() => !document.getElementById('generate').disabled);
  return { page, context, errors };
}

// The sample part's job is the mould job (rough, raster shallow, waterline steep); tests that
// look at one raster finish keep only that operation, selected, on the whole part.
export async function onlyRaster(page) {
  await tab(page, 'ops');
  await page.click('#op-list li:nth-child(3) .op-remove');
  await page.click('#op-list li:nth-child(1) .op-remove');
  assert.equal(await page.locator('#op-list li').count(), 1);
  assert.match(await page.textContent('#op-list li'), /finish shallow/);
  await page.fill('input[name=op-slopeMax]', '');
}

// The operations tab, the job's operations cleared and one of `kind` added and selected, with
// the tool numbered `tool` where one is given.
export async function soleOperation(page, kind, tool = null) {
  await tab(page, 'ops');
  await page.evaluate(() => { window.swarf.jobs[window.swarf.kind].operations = []; });
  await page.selectOption('#op-kind', kind);
  await page.click('#op-add');
  if (tool != null) await page.selectOption('select[name=op-tool]', String(tool));
}

// The operations tab, the sample job's roughing kept and an operation of `kind` added after it
// (in place of the finishes), on the tool numbered `tool`.
export async function afterRoughing(page, kind, tool) {
  await tab(page, 'ops');
  await page.evaluate(() => { const job = window.swarf.jobs[window.swarf.kind]; job.operations = job.operations.slice(0, 1); });
  await page.selectOption('#op-kind', kind);
  await page.click('#op-add');
  await page.selectOption('select[name=op-tool]', String(tool));
}

// Downloads the program into a folder of its own (named after `name`) with the page's tool
// table, and has LinuxCNC's rs274 run it (throwing where it refuses); returns its path.
export async function downloadThroughRs274(page, name) {
  const [download] = await Promise.all([page.waitForEvent('download'), page.click('#download')]);
  const dir = fs.mkdtempSync(path.join(os.tmpdir(), `swarf-e2e-${name}-`));
  const program = path.join(dir, download.suggestedFilename());
  await download.saveAs(program);
  fs.writeFileSync(path.join(dir, 'tool.tbl'), toolTable(await page.evaluate(() => window.swarf.tools)));
  execFileSync('rs274', ['-g', '-t', path.join(dir, 'tool.tbl'), program], { cwd: dir, env: { ...process.env, HOME: dir }, encoding: 'utf8', maxBuffer: 1 << 28 });
  return program;
}

// Adds a tool to the library in the tool form (the tools tab open): its shape, diameter and
// flute length; returns its number.
export async function addTool(page, shape, diameter, flutes) {
  await page.click('#tool-add');
  await page.selectOption('select[name=shape]', shape);
  await page.fill('input[name=diameter]', String(diameter));
  await page.fill('input[name=fluteLength]', String(flutes));
  return Number(await page.inputValue('input[name=toolNumber]'));
}

export const toolTable = (tools) => tools.map((t) => `T${t.number} P${t.number} Z0.000 D${t.diameter.toFixed(3)} ;${t.shape}\n`).join('');

// Counts canvas pixels by colour: the path's blue (the first operation's cutting moves are drawn
// in rgb(27, 116, 209)), the second operation's purple (rgb(158, 51, 191)),
// the simulated stock's tan, gouge red and rest-material blue, and the drawing's outline green (rgb(31, 140, 61)) and hole orange (rgb(217, 115, 13)).
export async function pixelCounts(page) {
  await frame(page);
  return page.evaluate(() => {
    const c = document.getElementById('view');
    const gl = c.getContext('webgl2');
    const px = new Uint8Array(c.width * c.height * 4);
    gl.readPixels(0, 0, c.width, c.height, gl.RGBA, gl.UNSIGNED_BYTE, px);
    const n = { path: 0, purple: 0, teal: 0, tan: 0, red: 0, blue: 0, green: 0, orange: 0 };
    for (let i = 0; i < px.length; i += 4) {
      const [r, g, b] = [px[i], px[i + 1], px[i + 2]];
      if (b > 150 && r < 90 && g > 80 && g < 160) n.path++;
      if (r > 120 && b > 150 && g < 90) n.purple++;
      if (r < 60 && g > 110 && b > 100 && Math.abs(g - b) < 50) n.teal++;
      if (r > 90 && r > b + 25 && g > b + 5 && g < r) n.tan++;
      if (r > 120 && g < 50 && b < 50) n.red++;
      if (b > r + 60 && b > 120) n.blue++;
      // Lines drawn over the background may be blended into it: outlines and holes by their hue.
      if (g > r + 30 && g > b + 25 && r < 150) n.green++;
      if (r > g + 30 && g > b + 30 && r > 180) n.orange++;
    }
    return n;
  });
}

// Counts canvas pixels in each of the given tools' colours (as the viewer's `toolColor` gives
// them: octree roughing draws a chosen tool's path and octants in it).
export async function toolPixels(page, numbers) {
  await frame(page);
  return page.evaluate(async (list) => {
    const { toolColor } = await import('./viewer.js');
    const c = document.getElementById('view');
    const gl = c.getContext('webgl2');
    const px = new Uint8Array(c.width * c.height * 4);
    gl.readPixels(0, 0, c.width, c.height, gl.RGBA, gl.UNSIGNED_BYTE, px);
    const out = {};
    for (const n of list) {
      const [r, g, b] = toolColor(n).map((v) => Math.round(v * 255));
      let k = 0;
      for (let i = 0; i < px.length; i += 4) if (Math.abs(px[i] - r) < 25 && Math.abs(px[i + 1] - g) < 25 && Math.abs(px[i + 2] - b) < 25) k++;
      out[n] = k;
    }
    return out;
  }, numbers);
}

export const pathPixels = async (page) => (await pixelCounts(page)).path;

// A box as a binary STL (12 triangles), `size` = [x, y, z] from the origin.
export function boxStl([x, y, z], [x0, y0, z0] = [0, 0, 0]) {
  const v = (i) => [x0 + (i & 1) * x, y0 + ((i >> 1) & 1) * y, z0 + ((i >> 2) & 1) * z];
  const faces = [[0, 2, 3], [0, 3, 1], [4, 5, 7], [4, 7, 6], [0, 1, 5], [0, 5, 4], [2, 6, 7], [2, 7, 3], [0, 4, 6], [0, 6, 2], [1, 3, 7], [1, 7, 5]];
  const buf = Buffer.alloc(84 + faces.length * 50);
  buf.writeUInt32LE(faces.length, 80);
  faces.forEach((f, k) => {
    const o = 84 + k * 50 + 12;
    f.forEach((i, j) => v(i).forEach((c, a) => buf.writeFloatLE(c, o + j * 12 + a * 4)));
  });
  return buf;
}


// A box as a glTF file (its coordinates in the file's unit), one triangle list in a data URI.
export function boxGltf([x, y, z]) {
  const stl = boxStl([x, y, z]);
  const floats = [];
  for (let f = 0; f < 12; f++) for (let k = 0; k < 9; k++) floats.push(stl.readFloatLE(84 + f * 50 + 12 + k * 4));
  const bin = Buffer.from(new Float32Array(floats).buffer);
  return Buffer.from(JSON.stringify({
    asset: { version: '2.0' }, scene: 0, scenes: [{ nodes: [0] }], nodes: [{ mesh: 0 }],
    meshes: [{ primitives: [{ attributes: { POSITION: 0 } }] }],
    accessors: [{ bufferView: 0, componentType: 5126, count: 36, type: 'VEC3', min: [0, 0, 0], max: [x, y, z] }],
    bufferViews: [{ buffer: 0, byteLength: bin.length }],
    buffers: [{ byteLength: bin.length, uri: `data:application/octet-stream;base64,${bin.toString('base64')}` }],
  }));
}

// A plate `w` × `h` × `t` (top at z = t) with round holes (`holes`: [x, y, diameter] through,
// [x, y, diameter, depth] blind with a flat floor; each at the centre of a square tile of side `tile` that tiles the plate), as a binary STL:
// each hole a 48-sided cylinder, its tile's top and bottom fanned from the circle to the
// tile's square (tiles meet at T-junctions, as many exported parts do).
export function plateStl(w, h, t, tile, holes) {
  const tris = [], push = facing(tris);
  const n = 48, half = tile / 2;
  for (let i = 0; i < w / tile; i++) {
    for (let j = 0; j < h / tile; j++) {
      const cx = (i + 0.5) * tile, cy = (j + 0.5) * tile;
      const hole = holes.find(([x, y]) => Math.abs(x - cx) < 1e-9 && Math.abs(y - cy) < 1e-9);
      // A hole's fourth figure: its depth, a blind hole with a flat floor (none: through).
      const floor = hole?.[3] != null ? t - hole[3] : 0;
      for (const [z, up] of [[t, 1], [0, -1]]) {
        if (!hole || (z === 0 && floor > 0)) {
          const q = [[cx - half, cy - half, z], [cx + half, cy - half, z], [cx + half, cy + half, z], [cx - half, cy + half, z]];
          push(q[0], q[1], q[2], [0, 0, up]);
          push(q[0], q[2], q[3], [0, 0, up]);
          continue;
        }
        const r = hole[2] / 2;
        const at = (k) => { const a = (2 * Math.PI * k) / n; return [cx + r * Math.cos(a), cy + r * Math.sin(a), z]; };
        const sq = (a) => { const c = Math.cos(a), s = Math.sin(a), m = half / Math.max(Math.abs(c), Math.abs(s)); return [cx + c * m, cy + s * m, z]; };
        for (let k = 0; k < n; k++) {
          const a0 = (2 * Math.PI * k) / n, a1 = (2 * Math.PI * (k + 1)) / n;
          const outer = [sq(a0)];
          for (let q = 0; q < 4; q++) {
            const corner = Math.PI / 4 + (q * Math.PI) / 2;
            if (corner > a0 && corner < a1) outer.push([cx + half * Math.sign(Math.cos(corner)), cy + half * Math.sign(Math.sin(corner)), z]);
          }
          outer.push(sq(a1));
          push(at(k + 1), at(k), outer[0], [0, 0, up]);
          for (let m = 0; m + 1 < outer.length; m++) push(at(k + 1), outer[m], outer[m + 1], [0, 0, up]);
        }
      }
      if (hole) {
        const r = hole[2] / 2;
        for (let k = 0; k < n; k++) {
          const a0 = (2 * Math.PI * k) / n, a1 = (2 * Math.PI * (k + 1)) / n;
          const p = (a, z) => [cx + r * Math.cos(a), cy + r * Math.sin(a), z];
          const inward = [-Math.cos((a0 + a1) / 2), -Math.sin((a0 + a1) / 2), 0];
          push(p(a0, t), p(a1, t), p(a1, floor), inward);
          push(p(a0, t), p(a1, floor), p(a0, floor), inward);
          if (floor > 0) push([cx, cy, floor], p(a0, floor), p(a1, floor), [0, 0, 1]);
        }
      }
    }
  }
  const c = [[0, 0], [w, 0], [w, h], [0, h]];
  for (let k = 0; k < 4; k++) {
    const [a, b] = [c[k], c[(k + 1) % 4]], out = [b[1] - a[1], a[0] - b[0], 0];
    push([a[0], a[1], t], [b[0], b[1], t], [b[0], b[1], 0], out);
    push([a[0], a[1], t], [b[0], b[1], 0], [a[0], a[1], 0], out);
  }
  return binaryStl(tris);
}

// Adds triangles to `tris`, each wound so its normal points along `hint`.
function facing(tris) {
  return (a, b, c, hint) => {
    const u = [b[0] - a[0], b[1] - a[1], b[2] - a[2]], v = [c[0] - a[0], c[1] - a[1], c[2] - a[2]];
    const n = [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]];
    tris.push(n[0] * hint[0] + n[1] * hint[1] + n[2] * hint[2] < 0 ? [a, c, b] : [a, b, c]);
  };
}

function binaryStl(tris) {
  const buf = Buffer.alloc(84 + tris.length * 50);
  buf.writeUInt32LE(tris.length, 80);
  tris.forEach((f, k) => f.forEach((p, j) => p.forEach((v, a) => buf.writeFloatLE(v, 84 + k * 50 + 12 + j * 12 + a * 4))));
  return buf;
}

// A square plate `side` across and `t` thick, its corner at the origin, with a round stud
// (φ`d`, `height` tall, `n` sides) standing on its middle: a boss for an external thread.
// Watertight: the plate's walls and bottom meet its top at the same points.
export function studStl(side, t, d, height, n = 64) {
  const tris = [], push = facing(tris), c = side / 2, r = d / 2, top = t + height;
  const rim = (k, z) => { const a = (2 * Math.PI * k) / n; return [c + r * Math.cos(a), c + r * Math.sin(a), z]; };
  const sq = (k) => { const a = (2 * Math.PI * k) / n, x = Math.cos(a), y = Math.sin(a), m = c / Math.max(Math.abs(x), Math.abs(y)); return [c + x * m, c + y * m, t]; };
  const outline = [];
  for (let k = 0; k < n; k++) {
    // The plate's top, the ring between the square and the stud (corners added where they fall).
    const a0 = (2 * Math.PI * k) / n, a1 = (2 * Math.PI * (k + 1)) / n, outer = [sq(k)];
    for (let q = 0; q < 4; q++) {
      const corner = Math.PI / 4 + (q * Math.PI) / 2;
      if (corner > a0 && corner < a1) outer.push([c + c * Math.sign(Math.cos(corner)), c + c * Math.sign(Math.sin(corner)), t]);
    }
    outer.push(sq(k + 1));
    push(rim(k + 1, t), rim(k, t), outer[0], [0, 0, 1]);
    for (let m = 0; m + 1 < outer.length; m++) push(rim(k + 1, t), outer[m], outer[m + 1], [0, 0, 1]);
    outline.push(...outer.slice(0, -1));
    // The stud's wall and its top.
    const out = [Math.cos((a0 + a1) / 2), Math.sin((a0 + a1) / 2), 0];
    push(rim(k, t), rim(k + 1, t), rim(k + 1, top), out);
    push(rim(k, t), rim(k + 1, top), rim(k, top), out);
    push([c, c, top], rim(k, top), rim(k + 1, top), [0, 0, 1]);
  }
  // The plate's walls through the top's outline points, and its bottom a fan from the middle.
  outline.forEach((p, i) => {
    const q = outline[(i + 1) % outline.length], out = [q[1] - p[1], p[0] - q[0], 0];
    push(p, q, [q[0], q[1], 0], out);
    push(p, [q[0], q[1], 0], [p[0], p[1], 0], out);
    push([c, c, 0], [p[0], p[1], 0], [q[0], q[1], 0], [0, 0, -1]);
  });
  return binaryStl(tris);
}

// The operations' names on the removal-rate plot, as drawn (`{ name, text, row, x0, x1 }` in
// CSS pixels): checked never to overlap in a row, each its operation's name or the start of it
// with an ellipsis.
export async function mrrLabels(page) {
  await frame(page);
  const labels = await page.evaluate(() => JSON.parse(document.getElementById('mrr').dataset.labels ?? '[]'));
  for (const row of [0, 1]) {
    const on = labels.filter((l) => l.row === row).sort((a, b) => a.x0 - b.x0);
    for (let k = 1; k < on.length; k++) assert.ok(on[k - 1].x1 + 1 <= on[k].x0, `"${on[k - 1].text}" and "${on[k].text}" overlap on the removal-rate plot`);
  }
  for (const l of labels) assert.ok(l.text === l.name || (l.text.endsWith('…') && l.name.startsWith(l.text.slice(0, -1))), `${l.text} for ${l.name}`);
  return labels;
}

// Screenshots of the page as it stands at 1280×720 and 1920×1080 (target/e2e/NAME-WxH.png),
// the viewport put back after.
export async function shoot(page, name) {
  const was = page.viewportSize();
  for (const [width, height] of [[1280, 720], [1920, 1080]]) {
    await page.setViewportSize({ width, height });
    await frame(page);
    await page.screenshot({ path: path.join(shots, `${name}-${width}x${height}.png`) });
  }
  await page.setViewportSize(was);
  await frame(page);
}
