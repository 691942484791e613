// Issue 15's "every core in the browser": swarf.js's engine shares a run among a pool of
// workers (CL surfaces and level maps in bands of rows, raster passes in ranges, the regions of
// z-level roughing's levels, the simulated stock in groups of bands of rows) and writes the same program and simulation as one worker; a pooled run cancels like any other, and bad input fails the
// same way.
import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import { chromium } from 'playwright-core';
import { dieStl } from '../../scripts/die-stl.mjs';
import { serveWww } from '../../scripts/serve-www.mjs';
import { execFileSync } from 'node:child_process';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

const root = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '../../www');

// A smaller die than the page's die-sized test: 120,000 triangles.
const die = dieStl(300, 200);
let server, browser, page;

before(async () => {
  let base;
  ({ server, base } = await serveWww({ '/die.stl': die }));
  browser = await chromium.launch({ executablePath: process.env.CHROMIUM || '/usr/bin/chromium', headless: true, args: ['--no-sandbox', '--disable-dev-shm-usage'] });
  const context = await browser.newContext();
  context.setDefaultTimeout(600000);
  page = await context.newPage();
  await page.goto(`${base}embed.html`);
  // Two engines: one worker, and a pool of three whatever the cores (so the test shares work on
  // any machine).
  await page.evaluate(async () => {
    const { createEngine } = await import('./swarf.js');
    const [one, pool] = await Promise.all([createEngine({ workers: 1 }), createEngine({ workers: 3 })]);
    const die = new Uint8Array(await (await fetch('/die.stl')).arrayBuffer());
    const job = one.defaultJob();
    const raster = structuredClone(one.defaults.operations.find((o) => o.kind === 'finishRaster'));
    job.tools = [{ ...job.tools[1], number: 1, shape: 'ball', diameter: 10, cornerRadius: 0, fluteLength: 200 }];
    job.operations = [{ ...raster, tool: 1, grid: 1.5, stepover: 4, builder: 'exact' }];
    job.simulation.verify = false;
    window.t = { one, pool, die, dieJob: job };
  });
});

after(async () => {
  await browser?.close();
  server?.close();
});

test('a pool of workers writes the same program as one worker, on the sample job and a die', async () => {
  const r = await page.evaluate(async () => {
    const { one, pool, die, dieJob } = window.t;
    const stages = new Set();
    const onProgress = (f, stage) => stages.add(stage.replace(/^.*: /, ''));
    const out = { workers: [one.workers, pool.workers] };
    for (const [name, job, bytes, file] of [['sample', one.defaultJob(), one.sample, 'sample.stl'], ['die', dieJob, die, 'die.stl']]) {
      const [a, b] = [await one.run(job, bytes, file), await pool.run(job, bytes, file, { onProgress })];
      // The simulation (verified jobs): the stock each left, every move's removal rate, the report.
      const equal = (x, y) => x.length === y.length && x.every((v, i) => Object.is(v, y[i]));
      const sim = a.sim && { same: equal(a.sim.start, b.sim.start) && equal(a.sim.mrr, b.sim.mrr) && JSON.stringify(a.sim.report) === JSON.stringify(b.sim.report), removed: b.sim.report.removed, cut: b.sim.mrr.filter((v) => v > 0).length };
      out[name] = { same: a.gcode === b.gcode, lines: a.gcode.split('\n').length, moves: [a.summary.moves, b.summary.moves], cutting: b.feeds.length / 6, sim };
    }
    out.stages = [...stages];
    return out;
  });
  assert.deepEqual(r.workers, [1, 3]);
  for (const name of ['sample', 'die']) {
    assert.ok(r[name].same, `${name}: the pooled program differs`);
    assert.ok(r[name].lines > 1000 && r[name].cutting > 1000, JSON.stringify(r[name]));
    assert.equal(r[name].moves[0], r[name].moves[1]);
  }
  // The sample job is verified: its simulation, cut in groups of bands on every worker, is the
  // one worker's to the last bit.
  assert.ok(r.sample.sim && r.sample.sim.same, JSON.stringify(r.sample.sim));
  assert.ok(r.sample.sim.removed > 1000 && r.sample.sim.cut > 1000, JSON.stringify(r.sample.sim));
  // The pool did share the work: it reported its phases.
  assert.ok(r.stages.includes('CL z-maps (3 workers)') && r.stages.includes('passes and level maps (3 workers)') && r.stages.includes('regions of levels (3 workers)') && r.stages.includes('in-process stock (3 workers)'), r.stages.join(', '));
});

// A large typed array the page sends a worker without transferring it (a part's file, a CL
// surface, an operation's moves, each for every worker) goes in pieces of at most 1 MB, each
// copied in a task of its own on the page's thread (a die-sized STL copied whole for each worker
// held it over 200 ms on a busy machine, a die's surface and moves up to 290 ms). The die here
// (6 MB, a 3.8 MB surface) is such a part: handed over as a view into a larger buffer at an odd
// offset to a pool whose workers' messages are watched, the pool's program is the command
// line's, which reads the file itself.
test('a part, a surface and moves larger than a message\'s piece reach every worker whole: the pool\'s program is the command line\'s', async () => {
  const cli = path.resolve(root, '../target/debug/swarf');
  assert.ok(fs.existsSync(cli), `the swarf command line is not built at ${cli}`);
  assert.ok(die.length > 4 << 20, `the die is ${die.length} bytes`);
  const r = await page.evaluate(async () => {
    const { createEngine } = await import('./swarf.js');
    const { die } = window.t;
    // Simulated, as the page's jobs are: the moves go to every worker, which cut the stock.
    const dieJob = structuredClone(window.t.dieJob);
    dieJob.simulation.verify = true;
    // Every message to a worker: the largest typed array copied (not transferred) in one, and
    // the fields that came in pieces.
    const seen = { largest: 0, fields: new Set() };
    const worker = () => {
      const w = new Worker('./worker.js', { type: 'module' });
      return {
        set onmessage(f) { w.onmessage = f; },
        set onerror(f) { w.onerror = f; },
        terminate: () => w.terminate(),
        postMessage(m, transfer = []) {
          for (const v of Object.values(m)) if (ArrayBuffer.isView(v) && !transfer.includes(v.buffer)) seen.largest = Math.max(seen.largest, v.byteLength);
          if (m.type === 'bytes') seen.fields.add(m.field);
          w.postMessage(m, transfer);
        },
      };
    };
    const pool = await createEngine({ worker, workers: 3, warmUp: false });
    const wide = new Uint8Array(die.length + 11);
    wide.set(die, 7);
    const result = await pool.run(dieJob, wide.subarray(7, 7 + die.length), 'die.stl');
    pool.close();
    return { gcode: result.gcode, job: JSON.stringify(dieJob), triangles: result.part.triangles, largest: seen.largest, fields: [...seen.fields].sort() };
  });
  assert.equal(r.triangles, (die.length - 84) / 50);
  assert.deepEqual(r.fields, ['bytes', 'moves', 'z']);
  assert.ok(r.largest <= 1 << 20, `a message copied ${r.largest} bytes of one array`);
  const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'swarf-pool-'));
  fs.writeFileSync(path.join(dir, 'job.json'), r.job);
  fs.writeFileSync(path.join(dir, 'die.stl'), die);
  execFileSync(cli, ['run', path.join(dir, 'job.json'), path.join(dir, 'die.stl'), '-o', path.join(dir, 'cli.nc'), '-q']);
  const fromCli = fs.readFileSync(path.join(dir, 'cli.nc'), 'utf8');
  assert.ok(fromCli.split('\n').length > 1000);
  assert.ok(r.gcode === fromCli, 'the pool\'s program differs from the command line\'s');
  fs.rmSync(dir, { recursive: true, force: true });
});

test('a pooled run cancels, the engine goes on, and bad input fails as with one worker', async () => {
  const r = await page.evaluate(async () => {
    const { one, pool, die, dieJob } = window.t;
    const controller = new AbortController();
    let seen = null;
    // Cancelled once the pool is sharing the raster passes.
    const onProgress = (f, stage) => { if (/passes and level maps/.test(stage) && !seen) { seen = stage; controller.abort(); } };
    const error = await pool.run(dieJob, die, 'die.stl', { onProgress, signal: controller.signal }).then(() => null, (e) => e.name);
    const again = await pool.run(dieJob, die, 'die.stl');
    const alone = await one.run(dieJob, die, 'die.stl');
    const bad = async (engine) => engine.run(dieJob, die.slice(0, 1000), 'die.stl').then(() => 'ran', (e) => e.message);
    return { seen, error, workers: pool.workers, same: again.gcode === alone.gcode, bad: [await bad(one), await bad(pool)] };
  });
  assert.ok(r.seen, 'the run reached the passes');
  assert.equal(r.error, 'AbortError');
  assert.equal(r.workers, 3);
  assert.ok(r.same, 'after a cancel, the pool writes the same program as one worker');
  assert.match(r.bad[0], /STL|truncated|triangles/i);
  assert.equal(r.bad[1], r.bad[0]);
});

test('a pooled run cancelled while its workers contour levels or cut the stock goes on as one worker', async () => {
  const r = await page.evaluate(async () => {
    const { one, pool } = window.t;
    const job = one.defaultJob();
    const out = {};
    for (const phase of ['regions of levels', 'in-process stock (']) {
      const controller = new AbortController();
      let seen = null;
      const onProgress = (f, stage) => { if (stage.includes(phase) && !seen) { seen = stage; controller.abort(); } };
      const error = await pool.run(job, one.sample, 'sample.stl', { onProgress, signal: controller.signal }).then(() => null, (e) => e.name);
      out[phase] = { seen, error };
    }
    const [again, alone] = [await pool.run(job, one.sample, 'sample.stl'), await one.run(job, one.sample, 'sample.stl')];
    out.same = again.gcode === alone.gcode && JSON.stringify(again.sim.report) === JSON.stringify(alone.sim.report);
    return out;
  });
  for (const phase of ['regions of levels', 'in-process stock (']) {
    assert.ok(r[phase].seen, `the run reached "${phase}"`);
    assert.equal(r[phase].error, 'AbortError');
  }
  assert.ok(r.same, 'after the cancels, the pool writes the same program and simulation as one worker');
});

test('runs asked for at once on a pool come out as each would alone', async () => {
  const r = await page.evaluate(async () => {
    const { one, pool, die, dieJob } = window.t;
    const other = structuredClone(dieJob);
    other.operations[0].angle = 90;
    // Both started before either ends: the second waits for the first.
    const [a, b] = await Promise.all([pool.run(dieJob, die, 'die.stl'), pool.run(other, die, 'die.stl')]);
    const [a1, b1] = [await one.run(dieJob, die, 'die.stl'), await one.run(other, die, 'die.stl')];
    return { a: a.gcode === a1.gcode, b: b.gcode === b1.gcode, differ: a1.gcode !== b1.gcode };
  });
  assert.deepEqual(r, { a: true, b: true, differ: true });
});

test('a pool shares a run only among as many workers as the memory holds for the part', async () => {
  const r = await page.evaluate(async () => {
    const { createEngine, workersFor } = await import('./swarf.js');
    const { one, die, dieJob } = window.t;
    const stagesOf = async (engine) => {
      const stages = new Set();
      const out = await engine.run(dieJob, die, 'die.stl', { onProgress: (f, stage) => stages.add(stage.replace(/^.*: /, '')) });
      return { stages: [...stages], gcode: out.gcode };
    };
    // The die (120,000 triangles, 6 MB): about 210 MB a worker. With 0.5 GB, half holds one
    // worker; with 1 GB, two of the three; with no figure, all three.
    const small = await createEngine({ workers: 3, memory: 0.5 });
    const some = await createEngine({ workers: 3, memory: 1 });
    const out = {
      rule: [workersFor(8, 25e6, 8), workersFor(8, 25e6, 2), workersFor(8, 25e6, 0.25), workersFor(3, 25e6), workersFor(8, 1e5, 4)],
      bytes: die.byteLength,
      small: await stagesOf(small),
      some: await stagesOf(some),
      alone: (await one.run(dieJob, die, 'die.stl')).gcode,
    };
    small.close();
    some.close();
    return out;
  });
  // 25 MB: 664 MB a worker; 4 GB of 8 hold 6, 1 GB of 2 holds 1; never fewer than one; all
  // where the memory is not known; a small part shares among every worker.
  assert.deepEqual(r.rule, [6, 1, 1, 3, 8]);
  assert.ok(!r.small.stages.some((s) => /workers\)/.test(s)), `one worker ran it alone: ${r.small.stages.join(', ')}`);
  assert.ok(r.some.stages.includes('CL z-maps (2 workers)'), r.some.stages.join(', '));
  assert.equal(r.small.gcode, r.alone);
  assert.equal(r.some.gcode, r.alone);
});

test('an engine warms up once in a worker of its own, which a run ends; the programs are the same', async () => {
  const r = await page.evaluate(async () => {
    const { createEngine } = await import('./swarf.js');
    const { one } = window.t;
    // Workers that tell what was asked of them and whether they were ended.
    const spied = [];
    const worker = () => {
      const w = new Worker(new URL('./worker.js', location.href), { type: 'module' });
      const seen = { asked: [], ended: false };
      const post = w.postMessage.bind(w), end = w.terminate.bind(w);
      w.postMessage = (m, t) => { seen.asked.push(m.type); post(m, t); };
      w.terminate = () => { seen.ended = true; end(); };
      spied.push(seen);
      return w;
    };
    const job = one.defaultJob();
    job.operations = [{ ...job.operations[1], stepover: 3, grid: 1 }];
    job.simulation.verify = false;
    const alone = (await one.run(job, one.sample, 'sample.stl')).gcode;
    // Left to warm up: one more worker than the pool, asked for a shared run, then ended.
    const calm = await createEngine({ workers: 2, worker });
    await calm.warmedUp;
    const calmWorkers = structuredClone(spied.splice(0));
    const calmRun = (await calm.run(job, one.sample, 'sample.stl')).gcode;
    // A run asked for at once ends the warm-up under way.
    const eager = await createEngine({ workers: 1, worker });
    const eagerRun = (await eager.run(job, one.sample, 'sample.stl')).gcode;
    await eager.warmedUp;
    const eagerWorkers = structuredClone(spied.splice(0));
    // No warm-up asked for: the pool's workers only.
    const none = await createEngine({ workers: 2, worker, warmUp: false });
    const noneRun = (await none.run(job, one.sample, 'sample.stl')).gcode;
    const noneWorkers = structuredClone(spied.splice(0));
    for (const e of [calm, eager, none]) e.close();
    return { same: [calmRun, eagerRun, noneRun].map((g) => g === alone), lines: alone.split('\n').length, calmWorkers, eagerWorkers, noneWorkers };
  });
  assert.deepEqual(r.same, [true, true, true]);
  assert.ok(r.lines > 100, `${r.lines} lines`);
  // The pool's two workers and the warm-up's, which ran the warm-up job shared (prepared,
  // planned, finished) and was ended; the pool's were not.
  assert.equal(r.calmWorkers.length, 3, JSON.stringify(r.calmWorkers));
  const side = r.calmWorkers[2];
  assert.ok(side.ended && ['hello', 'prepare', 'startPlan', 'finishPlan'].every((t) => side.asked.includes(t)), JSON.stringify(side));
  assert.ok(r.calmWorkers.slice(0, 2).every((w) => !w.ended && w.asked.includes('hello')), JSON.stringify(r.calmWorkers));
  // One worker: the warm-up's worker was asked for the job whole, then ended by the run.
  assert.equal(r.eagerWorkers.length, 2, JSON.stringify(r.eagerWorkers));
  assert.ok(r.eagerWorkers[1].ended && r.eagerWorkers[1].asked.includes('hello'), JSON.stringify(r.eagerWorkers));
  assert.ok(r.eagerWorkers[0].asked.includes('run') && !r.eagerWorkers[0].ended, JSON.stringify(r.eagerWorkers));
  assert.equal(r.noneWorkers.length, 2, JSON.stringify(r.noneWorkers));
});
