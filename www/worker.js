// Runs the wasm pipeline off the page's thread, for swarf.js's engine. Cancel = the engine
// terminates this worker.
import init, { defaults, builtinPosts, readPost, readJob, checkJob, writeProject, readProject, samplePart, sampleDrawing, warmUpJob, warmUpPart, loadPart, loadDrawing, stageFrames, isDrawing, prepareJob, setupFrames, setupSheet, oneProgram, zeroOn, cuttingData, readToolLibrary, writeToolLibrary, writeFreecadLibrary, findHoles, findBosses, findEdges } from './pkg/swarf.js';

// The wasm is loaded on the first message: from the bytes or URL it names (a single-file page
// passes the bytes), else from pkg/ beside the glue.
let ready = null;
// The last job's results stay here so the page can scrub through their simulations: one, or
// one a setup of a job with setups ({ result, block } each, by the setup's index).
let results = [];
// The job being shared out by the engine's pool (a JobPlan): every worker prepares its own;
// and the setup it is of (undefined for a job without setups).
let plan = null;
let planSetup;

// The simulated stock goes to the view on at most this many cells: a finer simulation is shown
// by the highest of each block of its cells (so no material is hidden), which keeps drawing,
// scrubbing and the messages behind them quick on a die-sized job.
const VIEW_CELLS = 512 * 512;

function blockOf(grid) {
  const [, , , nx, ny] = grid;
  const factor = Math.max(1, Math.ceil(Math.sqrt((nx * ny) / VIEW_CELLS)));
  return { factor, nx, ny, vx: Math.ceil(nx / factor), vy: Math.ceil(ny / factor) };
}

// The highest value of each block of cells (NaN only where the whole block is), as a copy the
// message can own. `block`: { factor, nx, ny, vx, vy } of the result.
function coarse(values, block) {
  const { factor, nx, ny, vx, vy } = block;
  if (factor === 1) return values.slice();
  const out = new Float32Array(vx * vy).fill(NaN);
  for (let j = 0; j < ny; j++) {
    const row = ((j / factor) | 0) * vx;
    for (let i = 0; i < nx; i++) {
      const v = values[j * nx + i], k = row + ((i / factor) | 0);
      if (!Number.isNaN(v) && !(out[k] >= v)) out[k] = v;
    }
  }
  return out;
}

// The part last sent to the engine, by the core's hash of its placed triangles: a run on the
// part the page already shows sends it back as `same` (tens of megabytes on a die-sized part,
// arriving with the result on the page's thread), and the engine puts back its own. Only the
// very same triangles are the same part: a flip or a turn is a new one.
let sentPart = null;

// The pieces of the next message's large fields received so far ('bytes'), by field.
const fieldPieces = new Map();

// `pieces` (bytes) one after the other, as the view named `type` (Float64Array, …) over them.
function joined(pieces, type) {
  const all = new Uint8Array(pieces.reduce((n, p) => n + p.length, 0));
  pieces.reduce((at, p) => (all.set(p, at), at + p.length), 0);
  return new globalThis[type](all.buffer);
}

function partMessage(view, reuse = false) {
  const key = view.hash();
  const meta = { bounds: Array.from(view.bounds()), triangles: view.triangles(), dropped: view.dropped(), warnings: view.warnings(), hash: key };
  const positions = view.positions();
  if (reuse && key === sentPart) {
    view.free();
    return { part: { ...meta, same: true }, transfer: [] };
  }
  const part = { positions: positions.slice(), normals: view.normals().slice(), ...meta };
  sentPart = key;
  view.free();
  return { part, transfer: [part.positions.buffer, part.normals.buffer] };
}

function planned() {
  if (!plan) throw new Error('no job is prepared in this worker');
  return plan;
}

// Reports a run's progress to the engine, at most every 50 ms.
function progressTo(id) {
  let last = 0;
  return (fraction, stage) => {
    const now = performance.now();
    if (now - last > 50 || fraction >= 1) {
      last = now;
      self.postMessage({ id, type: 'progress', fraction, stage });
    }
    return true;
  };
}

// Where each line of a program (its UTF-8 bytes) starts: found here, in the worker, so that the
// page's thread only draws the lines in sight.
function linesOf(bytes) {
  let n = 1;
  for (let i = 0; i < bytes.length; i++) if (bytes[i] === 10) n++;
  const starts = new Uint32Array(n);
  for (let i = 0, k = 1; i < bytes.length; i++) if (bytes[i] === 10) starts[k++] = i + 1;
  return starts;
}

// The result kept for setup `setup` (a job without setups: its one).
function kept(setup) {
  const r = results[setup ?? 0];
  if (!r) throw new Error('generate a program first');
  return r;
}

// A plan of setup `setup` (undefined: a job without setups), starting from the stock the setup
// before left (its result is kept here, from the run before).
function prepared(job, bytes, name, setup, carry) {
  const p = prepareJob(job, bytes, name, setup);
  if (carry && setup > 0) {
    const before = results[setup - 1];
    if (!before) { p.free(); throw new Error(`setup ${setup} needs the stock setup ${setup - 1} left: run that first`); }
    p.carryFrom(before.result);
  }
  return p;
}

// Sends a run's result (a JobResult) to the engine and keeps it for scrubbing and reposting:
// a job's, or setup `setup`'s (the first setup's forgets those of the run before).
function send(id, result, setup) {
  const feeds = result.feeds().slice();
  const feedOps = result.feedOperations().slice();
  const feedTools = result.feedTools().slice();
  const feedMoves = result.feedMoves().slice();
  const octants = result.octants().slice();
  const rapids = result.rapids().slice();
  const rapidMoves = result.rapidMoves().slice();
  const moveLines = result.moveLines().slice();
  const gcodeBytes = result.gcodeBytes().slice(), lineStarts = linesOf(gcodeBytes);
  const summary = result.summary();
  const drawing = result.drawing();
  const { part, transfer: partTransfer } = partMessage(result.takePart(), true);
  const simTransfer = [];
  let sim = null, block = null;
  if (result.hasSimulation()) {
    const grid = Array.from(result.simGrid());
    block = blockOf(grid);
    sim = {
      grid: [grid[0], grid[1], grid[2] * block.factor, block.vx, block.vy, ...grid.slice(5)],
      part: coarse(result.simPart(), block),
      times: result.times().slice(),
      mrr: result.mrr().slice(),
      findings: result.findings().slice(),
      report: result.report(),
      start: coarse(result.seek(result.times().length - 1), block),
    };
    simTransfer.push(sim.part.buffer, sim.times.buffer, sim.mrr.buffer, sim.findings.buffer, sim.start.buffer);
  }
  const place = result.setup() ?? null;
  if (!setup) {
    for (const r of results) r?.result.free();
    results = [];
  } else {
    results[setup]?.result.free();
  }
  results[setup ?? 0] = { result, block };
  // In pieces, each a task of its own on the page's thread (the engine puts them together):
  // a die-sized result is a hundred megabytes of arrays.
  self.postMessage({ id, type: 'piece', piece: { part } }, partTransfer);
  self.postMessage({ id, type: 'piece', piece: { feeds, feedOps, feedTools, feedMoves, octants, rapids, rapidMoves } }, [feeds.buffer, feedOps.buffer, feedTools.buffer, feedMoves.buffer, octants.buffer, rapids.buffer, rapidMoves.buffer]);
  self.postMessage({ id, type: 'piece', piece: { gcodeBytes, lineStarts, moveLines } }, [gcodeBytes.buffer, lineStarts.buffer, moveLines.buffer]);
  self.postMessage({ id, ok: true, summary, drawing, sim, setup: place }, simTransfer);
}

// A Content-Security-Policy that blocks what the worker needs (compiling the wasm, fetching
// it) is said as such, with its directive, instead of a bare "Failed to fetch".
let violation = null;
self.addEventListener?.('securitypolicyviolation', (e) => { violation = e; });
function explained(error) {
  const text = String(error && error.message ? error.message : error);
  if (violation) return `blocked by the Content-Security-Policy (${violation.effectiveDirective} does not allow ${violation.blockedURI || 'it'}): ${text}`;
  if (/WebAssembly|wasm-unsafe-eval|unsafe-eval/i.test(text) && /Content Security Policy|Refused to compile/i.test(text)) return `blocked by the Content-Security-Policy (script-src needs 'wasm-unsafe-eval'): ${text}`;
  return text;
}

self.onmessage = async (event) => {
  const { id, type } = event.data;
  // A large typed array comes in pieces before its message (the field `{ pieces, type }`), joined
  // here (the engine's Channel.call).
  if (type === 'bytes') {
    const { field, piece } = event.data;
    if (!fieldPieces.has(field)) fieldPieces.set(field, []);
    fieldPieces.get(field).push(piece);
    return;
  }
  for (const [field, pieces] of fieldPieces) event.data[field] = joined(pieces, event.data[field].type);
  fieldPieces.clear();
  try {
    ready ??= init(event.data.wasm ? { module_or_path: event.data.wasm } : undefined);
    await ready;
    if (type === 'hello' && event.data.helper) {
      self.postMessage({ id, ok: true, warmUp: event.data.warmUp ? { job: warmUpJob(), part: warmUpPart() } : null });
    } else if (type === 'hello') {
      self.postMessage({ id, ok: true, defaults: defaults(), posts: builtinPosts(), sample: samplePart(), sampleDrawing: sampleDrawing() });
    } else if (type === 'readPost') {
      self.postMessage({ id, ok: true, post: readPost(event.data.text) });
    } else if (type === 'writeProject') {
      self.postMessage({ id, ok: true, text: writeProject(event.data.job, event.data.name, event.data.bytes) });
    } else if (type === 'readProject') {
      self.postMessage({ id, ok: true, project: readProject(event.data.text) });
    } else if (type === 'readJob') {
      self.postMessage({ id, ok: true, job: readJob(event.data.text) });
    } else if (type === 'checkJob') {
      self.postMessage({ id, ok: true, problems: checkJob(event.data.job, event.data.part ? Float64Array.from(event.data.part) : undefined, event.data.holes ?? null) });
    } else if (type === 'load') {
      if (isDrawing(event.data.bytes, event.data.name)) {
        self.postMessage({ id, ok: true, drawing: loadDrawing(event.data.bytes, event.data.name, event.data.drawingSetup) });
      } else {
        const { part, transfer } = partMessage(loadPart(event.data.bytes, event.data.name, event.data.setup, event.data.stockMesh ?? null));
        self.postMessage({ id, ok: true, part }, transfer);
      }
    } else if (type === 'sheet') {
      if (!results.length) throw new Error('generate a program first');
      self.postMessage({ id, ok: true, html: setupSheet(event.data.job, event.data.name, results.map((r) => r.result.sheet())) });
    } else if (type === 'oneProgram') {
      if (!results.length) throw new Error('generate a program first');
      const kept = results.map((r) => r.result), post = event.data.job.post ?? {};
      self.postMessage({ id, ok: true, gcode: oneProgram(event.data.job, kept.map((r) => r.sheet()), kept.map((r) => r.program(post)), kept.map((r) => r.problem() ?? '')) });
    } else if (type === 'readToolLibrary') {
      const { bytes, name, inches, bits } = event.data;
      self.postMessage({ id, ok: true, library: readToolLibrary(bytes, name, inches, bits) });
    } else if (type === 'writeToolLibrary') {
      self.postMessage({ id, ok: true, text: writeToolLibrary(event.data.tools, event.data.format) });
    } else if (type === 'writeFreecadLibrary') {
      self.postMessage({ id, ok: true, files: writeFreecadLibrary(event.data.tools, event.data.library) });
    } else if (type === 'cuttingData') {
      self.postMessage({ id, ok: true, data: cuttingData(event.data.job) });
    } else if (type === 'zeroOn') {
      const { job, part, setup, point } = event.data;
      self.postMessage({ id, ok: true, zero: zeroOn(job, Float64Array.from(part), setup ?? undefined, point[0], point[1]) });
    } else if (type === 'stageFrames') {
      self.postMessage({ id, ok: true, frames: stageFrames(event.data.job, Float64Array.from(event.data.part)) });
    } else if (type === 'setupFrames') {
      self.postMessage({ id, ok: true, frames: setupFrames(event.data.job, Float64Array.from(event.data.part)) });
    } else if (type === 'run') {
      const { job, bytes, name, setup } = event.data;
      const p = prepared(job, bytes, name, setup, true);
      try {
        send(id, p.run(progressTo(id)), setup);
      } finally {
        p.free();
      }
    } else if (type === 'prepare') {
      plan?.free();
      plan = null;
      planSetup = event.data.setup;
      plan = prepared(event.data.job, event.data.bytes, event.data.name, planSetup, !event.data.helper);
      // Only the planning worker's list of what can be shared is used.
      self.postMessage({ id, ok: true, needs: event.data.helper ? null : plan.needs() });
    } else if (type === 'rows') {
      const z = planned().surfaceRows(event.data.surface, event.data.j0, event.data.j1);
      self.postMessage({ id, ok: true, z }, [z.buffer]);
    } else if (type === 'keepSurface') {
      planned().keepSurface(event.data.surface, event.data.z);
      self.postMessage({ id, ok: true });
    } else if (type === 'levelRows') {
      const z = planned().levelRows(event.data.surface, event.data.j0, event.data.j1);
      self.postMessage({ id, ok: true, z }, [z.buffer]);
    } else if (type === 'keepLevelMap') {
      planned().keepLevelMap(event.data.surface, event.data.right, event.data.up, event.data.wide);
      self.postMessage({ id, ok: true });
    } else if (type === 'passes') {
      const flat = planned().rasterPasses(event.data.operation, event.data.i0, event.data.i1);
      self.postMessage({ id, ok: true, flat }, [flat.buffer]);
    } else if (type === 'keepPasses') {
      planned().keepPasses(event.data.operation, event.data.first, event.data.count, event.data.flat);
      self.postMessage({ id, ok: true });
    } else if (type === 'release') {
      planned().release();
      self.postMessage({ id, ok: true });
    } else if (type === 'startPlan') {
      planned().start();
      self.postMessage({ id, ok: true });
    } else if (type === 'regionWork') {
      const work = planned().regionWork();
      self.postMessage({ id, ok: true, work: work ?? null });
    } else if (type === 'levelRegions') {
      const flat = planned().levelRegions(event.data.surface, event.data.levels, event.data.keep);
      self.postMessage({ id, ok: true, flat }, [flat.buffer]);
    } else if (type === 'keepRegions') {
      planned().keepRegions(event.data.flat);
      self.postMessage({ id, ok: true });
    } else if (type === 'planNext') {
      // The next operation planned; its moves and the stock's bands go to the pool to cut.
      const p = planned(), count = p.planNext(progressTo(id));
      if (count === undefined) {
        self.postMessage({ id, ok: true, done: true });
      } else if (count === 0) {
        self.postMessage({ id, ok: true, done: false, groups: null });
      } else {
        const moves = p.pendingMoves(), groups = p.takeBands(event.data.groups);
        self.postMessage({ id, ok: true, done: false, moves, groups }, [moves.buffer, ...groups.map((g) => g.buffer)]);
      }
    } else if (type === 'keepMoves') {
      planned().keepMoves(event.data.moves);
      self.postMessage({ id, ok: true });
    } else if (type === 'cutBands') {
      const [bands, cuts] = planned().cutBands(event.data.group);
      self.postMessage({ id, ok: true, bands, cuts }, [bands.buffer, cuts.buffer]);
    } else if (type === 'absorb') {
      planned().absorb(event.data.groups, event.data.cuts);
      self.postMessage({ id, ok: true });
    } else if (type === 'finishPlan') {
      const p = planned();
      plan = null;
      try {
        send(id, p.finish(progressTo(id)), planSetup);
      } finally {
        p.free();
      }
    } else if (type === 'forget') {
      plan?.free();
      plan = null;
      self.postMessage({ id, ok: true });
    } else if (type === 'holes') {
      self.postMessage({ id, ok: true, holes: findHoles(event.data.job, event.data.bytes, event.data.name, event.data.setup) });
    } else if (type === 'bosses') {
      self.postMessage({ id, ok: true, holes: findBosses(event.data.job, event.data.bytes, event.data.name, event.data.setup) });
    } else if (type === 'edges') {
      self.postMessage({ id, ok: true, edges: findEdges(event.data.job, event.data.bytes, event.data.name, event.data.setup) });
    } else if (type === 'repost') {
      // The program as bytes, as a run's is (see `send`).
      const { gcode, ...rest } = kept(event.data.setup).result.repost(event.data.post);
      const gcodeBytes = new TextEncoder().encode(gcode), lineStarts = linesOf(gcodeBytes);
      self.postMessage({ id, ok: true, ...rest, gcodeBytes, lineStarts }, [gcodeBytes.buffer, lineStarts.buffer, rest.moveLines.buffer]);
    } else if (type === 'seek') {
      // The stock after `count` moves, and the tool a fraction `f` into move `at` (default:
      // the end of the last move counted).
      const { count, at = Math.max(0, count - 1), f = count > 0 ? 1 : 0 } = event.data;
      const { result, block } = kept(event.data.setup);
      const tops = coarse(result.seek(count), block);
      self.postMessage({ id, ok: true, tops, count, tool: Array.from(result.toolAt(at, f)) }, [tops.buffer]);
    } else if (type === 'toolAt') {
      self.postMessage({ id, ok: true, tool: Array.from(kept(event.data.setup).result.toolAt(event.data.at, event.data.f)) });
    }
  } catch (error) {
    // A policy's violation is reported a moment after the fetch it blocked fails.
    if (error instanceof TypeError && !violation) await new Promise((resolve) => setTimeout(resolve, 50));
    self.postMessage({ id, ok: false, error: explained(error) });
  }
};
