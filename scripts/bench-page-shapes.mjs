// Issue 15's cutter shapes in the page: the sample part's mould job (z-level rough with a φ6
// flat end, raster shallow, waterline steep) through swarf.js's engine (the wasm in its worker,
// as the page runs it) in headless Chromium, with the finishing tool a ball, a bull nose (r1)
// and a flat end of 6 mm; best of two runs each. The native rows: `cargo bench --bench
// cutter_shapes`. (wasm-bindgen-test cannot time this: its runner loses a page that computes
// for more than 30 s in one call.)
//
//   bash scripts/build-wasm.sh && node scripts/bench-page-shapes.mjs
//
// WORKERS=1 runs the engine with one worker instead of its default pool (one per core).
import { chromium } from 'playwright-core';
import { serveWww } from './serve-www.mjs';

const { server, base } = await serveWww();
const browser = await chromium.launch({ executablePath: process.env.CHROMIUM || '/usr/bin/chromium', headless: true, args: ['--no-sandbox', '--disable-dev-shm-usage'] });
try {
  const page = await (await browser.newContext()).newPage();
  await page.goto(`${base}bare.html`);
  const seconds = await page.evaluate(async (workers) => {
    const { createEngine } = await import('./swarf.js');
    const engine = await createEngine(workers ? { workers } : {});
    const out = {};
    for (const [shape, cornerRadius] of [['ball', 0], ['bullNose', 1], ['flat', 0]]) {
      for (let run = 0; run < 2; run++) {
        const job = engine.defaultJob();
        Object.assign(job.tools[1], { shape, cornerRadius, fluteLength: 30 });
        const start = performance.now();
        await engine.run(job, engine.sample, 'sample.stl');
        out[shape] = Math.min(out[shape] ?? Infinity, (performance.now() - start) / 1000);
      }
    }
    return out;
  }, Number(process.env.WORKERS) || 0);
  const fastest = Math.min(...Object.values(seconds));
  for (const [shape, t] of Object.entries(seconds)) console.log(`page (Chromium)  ${shape.padEnd(9)} ${t.toFixed(2).padStart(7)} s  ${(t / seconds.ball).toFixed(2)} × ball  ${(t / fastest).toFixed(2)} × fastest`);
  console.log(`page (Chromium)  largest ratio between two shapes: ${(Math.max(...Object.values(seconds)) / fastest).toFixed(2)}`);
} finally {
  await browser.close();
  server.close();
}
