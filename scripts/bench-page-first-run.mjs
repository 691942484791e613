// Issue 13's compute target in the page as a user meets it: the pocket test's zigzag roughing
// (issue 12's settings, the load held by extra path) through swarf.js's engine in headless
// Chromium, each case in a browser of its own (nothing compiled before) on a bare page: the
// first run and the one after it, with one worker and with the pool, started at once when the
// engine is ready or after a pause of 1 or 3 s (a user choosing settings), and when the engine's
// warm-up was done. A function is compiled when first called and runs in baseline code until
// it is optimised; the warm-up (a small job in a worker of its own) does that before the user's
// first run. WARMUP=0: engines without it.
//
//   bash scripts/build-wasm.sh && [JOB=job.json] node scripts/bench-page-first-run.mjs [PART.stl]
//
// The part defaults to ../shared/data/meshes/kiri_pocket-test.stl; JOB, a job file run in place
// of the zigzag roughing (issue 59's adaptive clearing: a job of scripts/bench-adaptive-peers.sh
// with its verification off).
import fs from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { chromium } from 'playwright-core';
import { serveWww } from './serve-www.mjs';

const repo = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '..');
const partFile = process.argv[2] ?? path.join(repo, '../shared/data/meshes/kiri_pocket-test.stl');
const job = process.env.JOB ? JSON.parse(fs.readFileSync(process.env.JOB, 'utf8')) : {
  part: { placement: 'keep' },
  stock: { marginXy: 0, marginTop: 0, marginBottom: 0 },
  post: { rapidRate: 5000 },
  simulation: { verify: false },
  tools: [{ number: 1, shape: 'flat', diameter: 6, fluteLength: 50, feedRate: 1000, plungeRate: 250 }],
  operations: [{ kind: 'roughZigzag', stepdown: 2, stepover: 0.4, allowance: 0, leaveStock: 0, grid: 0.5, load: 'path' }],
};
const { server, base } = await serveWww({ '/part': fs.readFileSync(partFile) });

async function fresh(options, pause) {
  const browser = await chromium.launch({ executablePath: process.env.CHROMIUM || '/usr/bin/chromium', headless: true, args: ['--no-sandbox', '--disable-dev-shm-usage', ...(process.env.JS_FLAGS ? [`--js-flags=${process.env.JS_FLAGS}`] : [])] });
  try {
    const page = await (await browser.newContext()).newPage();
    await page.goto(`${base}bare.html`);
    return await page.evaluate(async ({ text, options, pause }) => {
      const { createEngine } = await import('./swarf.js');
      const ready = performance.now();
      const engine = await createEngine(options);
      // How long the engine's warm-up keeps the workers busy from when the engine is ready.
      const warm = engine.warmedUp.then(() => (performance.now() - ready) / 1000);
      await new Promise((done) => setTimeout(done, pause * 1000));
      const part = new Uint8Array(await (await fetch('/part')).arrayBuffer());
      const job = await engine.readJob(text);
      const runs = [];
      for (let run = 0; run < 2; run++) {
        const start = performance.now();
        const r = await engine.run(job, part, 'part.stl');
        runs.push({ seconds: (performance.now() - start) / 1000, bytes: r.gcode.length });
      }
      return { workers: engine.workers, runs, warm: await warm };
    }, { text: JSON.stringify(job), options, pause });
  } finally {
    await browser.close();
  }
}

try {
  for (const workers of process.env.WORKERS ? [Number(process.env.WORKERS)] : [1, undefined]) {
    for (const pause of [0, 1, 3]) {
      const r = await fresh({ workers, warmUp: process.env.WARMUP !== '0' }, pause);
      const [first, second] = r.runs;
      console.log(`page (Chromium)  ${r.workers} worker(s)  warm-up ${process.env.WARMUP === '0' ? 'off' : `done at ${r.warm.toFixed(3)} s`}  pause ${pause} s  first run ${first.seconds.toFixed(3)} s  second ${second.seconds.toFixed(3)} s  (${first.bytes} bytes of G-code, the same both runs: ${first.bytes === second.bytes})`);
    }
  }
} finally {
  server.close();
}
