// Issue 15's "every core in the browser": the same jobs in the page's engine (swarf.js, headless
// Chromium) with one worker and with a pool of one per core, against the native command line
// (`swarf run`, one thread per core) on the same job file and part; best of two runs each, and
// the programs compared byte for byte. The jobs: the sample part's mould job (the page's own,
// verified), and seed 001's die as a 500,000-triangle STL with a φ10 ball raster (grid 0.8,
// step-over 2), made once with the exact CL z-map and verified.
//
//   bash scripts/build-wasm.sh && cargo build --release && node scripts/bench-page-pool.mjs [JOB.json PART]
//
// With a job file (as `swarf run` takes it) and a part, that job on that part is timed too.
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { execFileSync } from 'node:child_process';
import { fileURLToPath } from 'node:url';
import { chromium } from 'playwright-core';
import { serveWww } from './serve-www.mjs';
import { dieStl } from './die-stl.mjs';

const repo = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '..');
const die = dieStl(580, 430);
const [jobFile, partFile] = process.argv.slice(2);
const given = jobFile ? { text: fs.readFileSync(jobFile, 'utf8'), bytes: fs.readFileSync(partFile), name: path.basename(partFile) } : null;
const { server, base } = await serveWww({ '/die.stl': die, ...(given ? { '/part': given.bytes } : {}) });
const browser = await chromium.launch({ executablePath: process.env.CHROMIUM || '/usr/bin/chromium', headless: true, args: ['--no-sandbox', '--disable-dev-shm-usage'] });
const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'swarf-pool-'));
try {
  const page = await (await browser.newContext()).newPage();
  await page.goto(`${base}bare.html`);
  const out = await page.evaluate(async (given) => {
    const { createEngine } = await import('./swarf.js');
    const cores = navigator.hardwareConcurrency;
    const die = new Uint8Array(await (await fetch('/die.stl')).arrayBuffer());
    const part = given && new Uint8Array(await (await fetch('/part')).arrayBuffer());
    const jobs = {};
    const results = { cores, rows: [] };
    for (const workers of [1, cores]) {
      const engine = await createEngine({ workers });
      const sample = engine.defaultJob();
      const raster = structuredClone(engine.defaults.operations.find((o) => o.kind === 'finishRaster'));
      const dieJob = engine.defaultJob();
      dieJob.tools = [{ ...dieJob.tools[1], number: 1, shape: 'ball', diameter: 10, cornerRadius: 0, fluteLength: 200 }];
      dieJob.operations = [{ ...raster, tool: 1, grid: 0.8, stepover: 2, builder: 'exact' }];
      Object.assign(jobs, { sample, die: dieJob });
      const runs = [['sample', sample, engine.sample, 'sample.stl'], ['die', dieJob, die, 'die.stl']];
      if (given) {
        jobs.part = await engine.readJob(given.text);
        runs.push(['part', jobs.part, part, given.name]);
      }
      for (const [name, job, bytes, file] of runs) {
        let best = Infinity, gcode = null, stages = null;
        for (let run = 0; run < 2; run++) {
          const start = performance.now();
          const seen = [];
          const onProgress = (f, stage) => { if (seen.at(-1)?.stage !== stage) seen.push({ stage, at: (performance.now() - start) / 1000 }); };
          const r = await engine.run(job, bytes, file, { onProgress });
          const t = (performance.now() - start) / 1000;
          if (t < best) [best, stages] = [t, seen];
          gcode = r.gcode;
        }
        results.rows.push({ name, workers, seconds: best, gcode, stages });
      }
      engine.close();
    }
    results.jobs = jobs;
    results.sample = Array.from(jobs.sample && (await createEngine({ workers: 1 })).sample);
    return results;
  }, given && { text: given.text, name: given.name });
  // The native command line on the same job files and parts.
  fs.writeFileSync(path.join(dir, 'die.stl'), die);
  const files = { sample: 'sample.stl', die: 'die.stl', part: `part${path.extname(partFile ?? '')}` };
  if (given) fs.writeFileSync(path.join(dir, files.part), given.bytes);
  fs.writeFileSync(path.join(dir, 'sample.stl'), Buffer.from(out.sample));
  const swarf = path.join(repo, 'target/release/swarf');
  const native = {};
  const names = given ? ['sample', 'die', 'part'] : ['sample', 'die'];
  for (const name of names) {
    fs.writeFileSync(path.join(dir, `${name}.json`), JSON.stringify(out.jobs[name]));
    let best = Infinity;
    for (let run = 0; run < 2; run++) {
      const start = performance.now();
      execFileSync(swarf, ['run', '-q', '--write-anyway', path.join(dir, `${name}.json`), path.join(dir, files[name]), '-o', path.join(dir, `${name}.nc`)], { stdio: 'pipe' });
      best = Math.min(best, (performance.now() - start) / 1000);
    }
    native[name] = { seconds: best, gcode: fs.readFileSync(path.join(dir, `${name}.nc`), 'utf8') };
  }
  console.log(`cores: ${out.cores} (native threads: ${Math.min(8, os.availableParallelism())})`);
  for (const name of names) {
    const rows = out.rows.filter((r) => r.name === name);
    const [one, pool] = [rows[0], rows[rows.length - 1]];
    const same = rows.every((r) => r.gcode === one.gcode) ? 'same program' : 'PROGRAMS DIFFER';
    const likeNative = one.gcode.split('\n').slice(1).join('\n') === native[name].gcode.split('\n').slice(1).join('\n') ? ', as native' : ' (native differs)';
    if (process.env.STAGES) for (const r of rows) console.log(`  ${r.workers} workers: ${r.stages.map((s) => `${s.at.toFixed(2)} ${s.stage}`).join(' | ')}`);
    console.log(`${name.padEnd(6)} native ${native[name].seconds.toFixed(2)} s | page, 1 worker ${one.seconds.toFixed(2)} s (${(one.seconds / native[name].seconds).toFixed(2)} × native) | page, ${pool.workers} workers ${pool.seconds.toFixed(2)} s (${(pool.seconds / native[name].seconds).toFixed(2)} × native, ${(one.seconds / pool.seconds).toFixed(2)} × faster than 1 worker) | ${same}${likeNative}`);
  }
} finally {
  await browser.close();
  server.close();
  fs.rmSync(dir, { recursive: true, force: true });
}
