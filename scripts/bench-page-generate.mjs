// Issue 61's first figure: the page's own sample job from Generate to a drawn result, in the
// built page (www/index.html, headless Chromium), at 1280 × 800 and 1920 × 1080, three runs
// each after a first that warms the engine; and where the time goes: the engine's stages as
// the progress line names them (planning each operation in the workers, simulating,
// verifying), the result's way into the page (the engine's answer to the result handed over),
// and the drawing (the result handed over to the view drawn). The page's worst frame meanwhile
// from Chromium's long-animation-frame entries.
//
// With `--mould`, the other job instead: ten operations (face, two z-level roughings,
// raster and waterline finishing, spot, two drills, bore, chamfer;
// examples/mould-core/mould-core.json) on a generated 100 mm mould core (scripts/mould-core.py,
// built here by the Python scripts/solid-venv.sh makes, as scripts/rough-speed.sh builds its plate).
//
//   bash scripts/build-wasm.sh && node scripts/bench-page-generate.mjs [RUNS] [--mould]
import { execFileSync } from 'node:child_process';
import path from 'node:path';
import { chromium } from 'playwright-core';
import { serveWww } from './serve-www.mjs';

const args = process.argv.slice(2);
const mould = args.includes('--mould');
const runs = Number(args.find((a) => a !== '--mould') ?? 3);
const root = path.resolve(path.dirname(new URL(import.meta.url).pathname), '..');
let part = null;
if (mould) {
  const python = execFileSync('bash', [path.join(root, 'scripts/solid-venv.sh')], { stdio: ['ignore', 'pipe', 'inherit'] }).toString().trim();
  part = path.join(root, 'target/mould-core.stl');
  execFileSync(python, [path.join(root, 'scripts/mould-core.py'), part], { stdio: 'inherit' });
}
const { server, base } = await serveWww();
const browser = await chromium.launch({ executablePath: process.env.CHROMIUM || '/usr/bin/chromium', headless: true, args: ['--no-sandbox', '--disable-dev-shm-usage'] });
try {
  for (const [width, height] of [[1280, 800], [1920, 1080]]) {
    const context = await browser.newContext({ viewport: { width, height } });
    const page = await context.newPage();
    await page.goto(base);
    await page.waitForSelector('body[data-ready="true"]');
    if (part) {
      const parts = Number(await page.evaluate(() => document.body.dataset.parts));
      await page.setInputFiles('#file', part);
      await page.waitForFunction((n) => Number(document.body.dataset.parts) > n, parts);
      await page.setInputFiles('#load-job', path.join(root, 'examples/mould-core/mould-core.json'));
      await page.waitForFunction(() => /Loaded the job/.test(document.getElementById('message').textContent));
    }
    await page.evaluate(() => {
      window.bench = { stages: [], frames: [] };
      const stage = document.getElementById('stage');
      new MutationObserver(() => window.bench.stages.push([performance.now(), stage.textContent])).observe(stage, { childList: true, characterData: true, subtree: true });
      new PerformanceObserver((list) => { for (const e of list.getEntries()) window.bench.frames.push(e.duration); }).observe({ type: 'long-animation-frame' });
    });
    const rows = [];
    for (let k = 0; k <= runs; k++) {
      await page.evaluate(() => { window.bench.stages = []; window.bench.frames = []; window.bench.t0 = performance.now(); document.getElementById('generate').click(); });
      await page.waitForFunction(() => ['ok', 'error', 'cancelled'].includes(document.body.dataset.generated), null, { timeout: 600000, polling: 50 });
      // Drawn: two frames after the result is on show.
      const r = await page.evaluate(() => new Promise((resolve) => requestAnimationFrame(() => requestAnimationFrame(() => {
        const b = window.bench, end = performance.now();
        const computed = window.swarf?.summary?.computed ?? NaN;
        // Each stage's time, the progress line's texts run together by their first words.
        const spans = {};
        b.stages.forEach(([t, text], i) => {
          const next = i + 1 < b.stages.length ? b.stages[i + 1][0] : b.t0 + computed * 1000;
          const name = text.replace(/\s*\d+(\.\d+)?\s*%.*$/, '').trim() || '(none)';
          spans[name] = (spans[name] ?? 0) + Math.max(0, next - t);
        });
        resolve({ state: document.body.dataset.generated, total: (end - b.t0) / 1000, computed, spans, worst: Math.max(0, ...b.frames), moves: window.swarf?.summary?.s?.moves });
      }))));
      if (r.state !== 'ok') throw new Error(`Generate ended ${r.state}: ${await page.textContent('#message')}`);
      if (k > 0) rows.push(r);
    }
    const best = rows.reduce((a, b) => (b.total < a.total ? b : a));
    console.log(`\n${width} × ${height}: Generate to drawn ${rows.map((r) => r.total.toFixed(2)).join(', ')} s (best ${best.total.toFixed(2)} s; ${best.moves} moves); engine ${best.computed.toFixed(2)} s, into the page and drawn ${(best.total - best.computed).toFixed(2)} s; worst frame ${Math.max(...rows.map((r) => r.worst)).toFixed(0)} ms`);
    console.log('| stage (best run) | s |\n|---|---|');
    for (const [name, ms] of Object.entries(best.spans).sort((a, b) => b[1] - a[1])) console.log(`| ${name} | ${(ms / 1000).toFixed(2)} |`);
    await context.close();
  }
} finally {
  await browser.close();
  server.close();
}
