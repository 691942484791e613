// Issue 15's pool of workers, its memory: every worker prepares its own copy of the job and the
// part, so memory grows with the pool. The die job of bench-page-pool.mjs (seed 001's die as a
// 500,000-triangle STL, φ10 ball raster, grid 0.8, exact CL z-map, verified) run in the page's
// engine with pools of 1, 2, 4 and 8 workers; the browser's processes (every process this
// script started) are sampled every 50 ms and the peak of their summed resident memory is
// printed, less what they held with the page loaded and no engine made. The programs are
// compared across the pools.
//
//   bash scripts/build-wasm.sh && node scripts/bench-page-memory.mjs
import fs from 'node:fs';
import { chromium } from 'playwright-core';
import { serveWww } from './serve-www.mjs';
import { dieStl } from './die-stl.mjs';

/** Resident memory (MB) of every process descended from this one. */
function residentMb() {
  const parent = new Map();
  const rss = new Map();
  for (const pid of fs.readdirSync('/proc').filter((d) => /^\d+$/.test(d))) {
    try {
      const status = fs.readFileSync(`/proc/${pid}/status`, 'utf8');
      parent.set(pid, status.match(/^PPid:\s+(\d+)/m)?.[1]);
      rss.set(pid, Number(status.match(/^VmRSS:\s+(\d+)/m)?.[1] ?? 0));
    } catch {
      // The process ended while being read.
    }
  }
  const mine = String(process.pid);
  const descends = (pid) => {
    for (let p = parent.get(pid), hops = 0; p && hops < 64; p = parent.get(p), hops++) if (p === mine) return true;
    return false;
  };
  let kb = 0;
  for (const [pid, value] of rss) if (descends(pid)) kb += value;
  return kb / 1024;
}

const die = dieStl(580, 430);
const { server, base } = await serveWww({ '/die.stl': die });
const browser = await chromium.launch({ executablePath: process.env.CHROMIUM || '/usr/bin/chromium', headless: true, args: ['--no-sandbox', '--disable-dev-shm-usage'] });
try {
  const page = await (await browser.newContext()).newPage();
  await page.goto(`${base}bare.html`);
  await page.evaluate(async () => {
    const { createEngine } = await import('./swarf.js');
    globalThis.bench = { createEngine, die: new Uint8Array(await (await fetch('/die.stl')).arrayBuffer()) };
  });
  const idle = residentMb();
  const rows = [];
  for (const workers of [1, 2, 4, 8]) {
    let peak = 0;
    const timer = setInterval(() => { peak = Math.max(peak, residentMb()); }, 50);
    const r = await page.evaluate(async (workers) => {
      const { createEngine, die } = globalThis.bench;
      const engine = await createEngine({ workers });
      const job = engine.defaultJob();
      const raster = structuredClone(engine.defaults.operations.find((o) => o.kind === 'finishRaster'));
      job.tools = [{ ...job.tools[1], number: 1, shape: 'ball', diameter: 10, cornerRadius: 0, fluteLength: 200 }];
      job.operations = [{ ...raster, tool: 1, grid: 0.8, stepover: 2, builder: 'exact' }];
      const start = performance.now();
      const out = await engine.run(job, die, 'die.stl');
      const seconds = (performance.now() - start) / 1000;
      engine.close();
      return { seconds, gcode: out.gcode };
    }, workers);
    clearInterval(timer);
    peak = Math.max(peak, residentMb());
    rows.push({ ...r, workers, peak });
    // Let the closed engine's workers go before the next pool.
    await page.waitForTimeout(1500);
  }
  const same = rows.every((r) => r.gcode === rows[0].gcode) ? 'same program in every pool' : 'PROGRAMS DIFFER';
  console.log(`browser with the page loaded: ${idle.toFixed(0)} MB resident; ${same}`);
  for (const r of rows) {
    console.log(`die, ${r.workers} worker${r.workers > 1 ? 's' : ''}: peak ${r.peak.toFixed(0)} MB resident (${(r.peak - idle).toFixed(0)} MB over the idle page, ${((r.peak - idle) / r.workers).toFixed(0)} MB a worker), ${r.seconds.toFixed(2)} s`);
  }
} finally {
  await browser.close();
  server.close();
}
