// swarf's public API for web pages: a DOM-free ES module. An engine runs swarf's wasm in a
// worker of its own, so the page's thread stays free; every call returns a promise. The page
// (app.js) is one consumer of this module and embed.html another. Types: swarf.d.ts, with the
// job's types generated from the Rust serde types (types/).
//
//   import { createEngine } from './swarf.js';
//   const engine = await createEngine();
//   const job = engine.defaultJob();                       // or 'drawing'
//   const result = await engine.run(job, bytes, 'part.stl', { onProgress, signal });
//   result.gcode, result.summary.cycle.seconds, result.feeds (Float32Array of segments)

/** Thrown (as the promise's rejection) when a run is cancelled through its AbortSignal. */
export class CancelledError extends Error {
  constructor() {
    super('cancelled by the user');
    this.name = 'AbortError';
  }
}

/**
 * Thrown (as the promise's rejection) when a run's program is not safe to run: its simulation
 * found a gouge, a rapid move through stock or the tool's body in material (`problem` says
 * which and where). The run's result is `result`, for a page that shows the places; a caller
 * that means to take such a program passes `allowUnsafe: true` (the CLI's `--write-anyway`).
 */
export class UnsafeProgramError extends Error {
  constructor(problem, result) {
    super(`the program is not safe to run: ${problem}`);
    this.name = 'UnsafeProgramError';
    this.problem = problem;
    this.result = result;
  }
}

/**
 * Thrown (as the promise's rejection) when a job does not read or does not fit: `path` is the
 * field's path as `checkJob` gives it (`operations[0].stepdown`, `stock.bar.diameter`; `''`
 * where the whole job is meant), `message` what is wrong.
 */
export class JobError extends Error {
  constructor(message, path = '') {
    super(message);
    this.name = 'JobError';
    this.path = path;
  }
}

/**
 * Thrown (as the promise's rejection) when a part's or drawing's file does not read: `file` is
 * its name, `message` says what and where in it (a line, a byte, an entity).
 */
export class FileError extends Error {
  constructor(message, file) {
    super(message);
    this.name = 'FileError';
    this.file = file;
  }
}

/**
 * A job's field path at the start of an engine's message, after a few words where they lead
 * ("operations[0].stepdown must be …", "unknown field: tools[0].diamter …", "setups: …").
 */
const JOB_PATH = /^(?:[a-z ]+: )?((?:tools|operations|setups|stock|part|drawing|post|machine|fixtures|simulation)(?:(?:\[\d+\]|\.[A-Za-z]+)+(?=[\s:(]|$)|(?=:\s)))/;

/** The engine's error `e` on a run of the file `name`, typed: a JobError or a FileError where it is one. */
function typed(e, name) {
  if (!(e instanceof Error) || e instanceof CancelledError || e instanceof UnsafeProgramError || e instanceof JobError || e instanceof FileError) return e;
  const path = e.message.match(JOB_PATH)?.[1];
  if (path) return new JobError(e.message, path);
  if (name && e.message.startsWith(`${name}:`)) return new FileError(e.message, name);
  return e;
}

/** The last Content-Security-Policy violation the page's document reported, if any. */
let violation = null;
globalThis.document?.addEventListener?.('securitypolicyviolation', (e) => { violation = e; });

/** Bytes of a typed array sent to a worker in one message at most (1 MB; see `Channel.call`). */
const PIECE_BYTES = 1 << 20;

/**
 * The fields of `message` that `Channel.call` sends in pieces: its typed arrays (or buffers) over
 * PIECE_BYTES whose buffers are not transferred (those are moved, not copied).
 */
function piecewise(message, transfer) {
  return Object.keys(message).filter((k) => {
    const v = message[k];
    return (ArrayBuffer.isView(v) || v instanceof ArrayBuffer) && v.byteLength > PIECE_BYTES && !transfer.includes(v.buffer ?? v);
  });
}

/**
 * Resolves in a task of its own, without the 4 ms a chain of timers waits between its tasks:
 * the pieces of a large message go out one a task, as fast as the page's thread takes them.
 */
function nextTask() {
  return new Promise((resolve) => {
    const { port1, port2 } = new MessageChannel();
    port1.onmessage = () => { port1.close(); resolve(); };
    port2.postMessage(null);
  });
}

/** One worker and the calls waiting on its answers. */
class Channel {
  #worker;
  /** The last part (triangles) the worker sent. */
  #part = null;
  #pending = new Map();
  #nextId = 1;

  constructor(worker) {
    this.#worker = worker;
    // Under Node, a worker with nothing asked of it keeps no script alive (one that forgets
    // `close()` still exits).
    worker.unref?.();
    worker.onmessage = (event) => {
      const m = event.data, entry = this.#pending.get(m.id);
      if (!entry) return;
      if (m.type === 'progress') { entry.onProgress?.(m.fraction, m.stage); return; }
      // A large answer comes in pieces, each a task of its own: kept until the last.
      if (m.type === 'piece') { entry.pieces = Object.assign(entry.pieces ?? {}, m.piece); return; }
      this.#pending.delete(m.id);
      if (!this.#pending.size) worker.unref?.();
      if (!m.ok) { entry.reject(new Error(m.error)); return; }
      if (entry.pieces) Object.assign(m, entry.pieces);
      // A part this worker sent before comes back as `same`: its triangles are those kept here.
      if (m.part?.same && this.#part) m.part = { ...this.#part, ...m.part, same: undefined };
      else if (m.part?.positions) this.#part = m.part;
      entry.resolve(m);
    };
    // A worker that cannot start: said with the Content-Security-Policy's directive where the
    // page's policy blocked it (the violation is reported to the page's document).
    worker.onerror = (e) => {
      e.preventDefault?.();
      setTimeout(() => this.#fail(new Error(violation ? `blocked by the Content-Security-Policy (${violation.effectiveDirective} does not allow ${violation.blockedURI || 'the worker'}): the worker could not start` : e.message || 'the worker failed to start (its script could not be loaded or run)')), 0);
    };
  }

  /** The sending of a large message's pieces, while under way: later messages wait for it. */
  #sending = null;
  /** Whether the worker was ended. */
  #ended = false;

  /**
   * Sends `message` (its buffers in `transfer` moved) and resolves with the worker's answer.
   * Its large typed arrays that are not transferred (a part's file, a CL surface, an operation's
   * moves, each for every worker of a pool) go in pieces of at most PIECE_BYTES, each copied and
   * sent in a task of its own, the worker joining them: copying them in the task that made the
   * call (often the task a worker's answer arrived in) held the page's thread 10-30 ms on an
   * idle machine and over 200 ms on a busy one. Calls on a channel arrive in the order made.
   */
  call(message, transfer = [], onProgress) {
    const id = this.#nextId++;
    this.#worker.ref?.();
    return new Promise((resolve, reject) => {
      this.#pending.set(id, { resolve, reject, onProgress });
      const fields = piecewise(message, transfer);
      if (!fields.length && !this.#sending) {
        this.#worker.postMessage({ id, ...message }, transfer);
        return;
      }
      // In the order called: after the pieces of a message before it.
      const sent = (this.#sending ?? Promise.resolve()).then(() => this.#inPieces(id, message, transfer, fields));
      this.#sending = sent;
      sent.then(() => { if (this.#sending === sent) this.#sending = null; }, (error) => {
        if (this.#sending === sent) this.#sending = null;
        this.#pending.delete(id);
        reject(error);
      });
    });
  }

  /**
   * `message` with its `fields` sent in pieces first (`{ type: 'bytes', field, piece }`, bytes
   * of at most PIECE_BYTES, each copied in a task of its own), then the message itself, each
   * of those fields replaced by `{ pieces, type }` (how many, and the typed array they make).
   */
  async #inPieces(id, message, transfer, fields) {
    const last = { id, ...message };
    for (const field of fields) {
      const v = message[field], all = new Uint8Array(v.buffer ?? v, v.byteOffset ?? 0, v.byteLength);
      const pieces = Math.ceil(all.length / PIECE_BYTES);
      for (let k = 0; k < pieces; k++) {
        await nextTask();
        // A worker ended meanwhile (a cancel) takes no more.
        if (this.#ended) return;
        const piece = all.slice(k * PIECE_BYTES, (k + 1) * PIECE_BYTES);
        this.#worker.postMessage({ id, type: 'bytes', field, piece }, [piece.buffer]);
      }
      // The typed array they make, by its own name (a Node Buffer's is Uint8Array's).
      last[field] = { pieces, type: ArrayBuffer.isView(v) ? v[Symbol.toStringTag] : 'Uint8Array' };
    }
    this.#worker.postMessage(last, transfer);
  }

  /** Ends the worker; every call waiting on it rejects with `error`. */
  end(error) {
    this.#ended = true;
    this.#worker.terminate();
    this.#fail(error);
  }

  #fail(error) {
    for (const entry of this.#pending.values()) entry.reject(error);
    this.#pending.clear();
  }
}

/**
 * A pool's worker holds its own copy of the part and of its preparation (the drop index and the
 * exact builder's features): about this many bytes per byte of the part's file, and the second
 * figure besides (measured on the die, a 25 MB binary STL: some 600 MB a worker; BENCHMARKS.md,
 * "Memory of the pool").
 */
const WORKER_BYTES_PER_PART_BYTE = 24;
const WORKER_BYTES_BESIDES = 64 * 2 ** 20;
/** The share of the device's memory a run's pool may take. */
const MEMORY_SHARE = 0.5;

/**
 * How many of `count` workers share a run on a part of `bytes` bytes when the device has
 * `memoryGb` of memory: as many as half of it holds, at least one; all where the memory is not
 * known (`navigator.deviceMemory` is Chromium's only).
 */
export function workersFor(count, bytes, memoryGb) {
  if (!(memoryGb > 0)) return count;
  const each = WORKER_BYTES_PER_PART_BYTE * bytes + WORKER_BYTES_BESIDES;
  return Math.max(1, Math.min(count, Math.floor((MEMORY_SHARE * memoryGb * 2 ** 30) / each)));
}

/** How many workers a run shares: `wanted`, else one per core (at most 8). */
function poolSize(wanted) {
  const cores = globalThis.navigator?.hardwareConcurrency ?? 1;
  return Math.max(1, Math.min(8, Math.floor(wanted ?? cores)));
}

/**
 * Runs `tasks` (messages) on `channels`, each channel taking the next task as it finishes one;
 * `done(task, answer)` takes each answer, `report(fraction)` the share done.
 */
async function share(channels, tasks, done, report) {
  let next = 0, finished = 0, failed = false;
  await Promise.all(channels.map(async (channel) => {
    try {
      while (!failed && next < tasks.length) {
        const task = tasks[next++];
        const answer = await channel.call(task, task.transfer ?? []);
        // Once a task failed, no answer of this run is used.
        if (failed) return;
        done(task, answer);
        report(++finished / tasks.length);
      }
    } catch (error) {
      failed = true;
      throw error;
    }
  }));
}

/** Groups of the simulated stock's bands of rows each worker of a pool cuts, on average. */
const GROUPS_PER_WORKER = 4;

/** Ranges `[from, to)` splitting `0..count` into about `pieces` even ones. */
function ranges(count, pieces) {
  const size = Math.max(1, Math.ceil(count / pieces));
  const out = [];
  for (let from = 0; from < count; from += size) out.push([from, Math.min(count, from + size)]);
  return out;
}

export class Engine {
  /** The worker that plans and keeps the last result (scrubbing, reposting). */
  #main = null;
  /** The rest of the pool: they make CL surfaces and level maps in bands, raster passes in ranges. */
  #helpers = [];
  #options;
  /** The last run asked for: the next waits for it. */
  #last = Promise.resolve();
  /** The warm-up, once started (the engine's workers replaced on a cancel need none). */
  #warming = null;
  /** The warm-up's worker while it runs. */
  #side = null;

  /** Use `createEngine()`. */
  constructor(options = {}) {
    this.#options = options;
    /** The core's defaults: `{ job, drawingJob, tool, operations }`. */
    this.defaults = null;
    /** The built-in posts: `[{ dialect, post }]`. */
    this.posts = [];
    /** The sample part (binary STL) and drawing (DXF) the core makes. */
    this.sample = null;
    this.sampleDrawing = null;
    /** Settles when the engine's warm-up has run (at once with `warmUp: false`). */
    this.warmedUp = Promise.resolve();
  }

  /** How many workers share a run. */
  get workers() {
    return 1 + this.#helpers.length;
  }

  async start() {
    const o = this.#options;
    const make = () => {
      if (o.worker) return o.worker();
      if (o.workerUrl) return new Worker(o.workerUrl, { type: 'module' });
      // Written as bundlers look for it (Vite, webpack, Parcel, Rollup's plugins): the worker
      // and the wasm it loads beside it are followed and emitted with the bundle.
      return new Worker(new URL('./worker.js', import.meta.url), { type: 'module' });
    };
    this.#main = new Channel(make());
    this.#helpers = Array.from({ length: poolSize(o.workers) - 1 }, () => new Channel(make()));
    const wasm = o.wasm ?? null;
    const [hello] = await Promise.all([this.#main.call({ type: 'hello', wasm }), ...this.#helpers.map((h) => h.call({ type: 'hello', helper: true, wasm }))]);
    Object.assign(this, { defaults: hello.defaults, posts: hello.posts, sample: hello.sample, sampleDrawing: hello.sampleDrawing });
    if (o.warmUp !== false && !this.#warming) this.warmedUp = this.#warming = this.#warmUp(make, wasm);
    return this;
  }

  /**
   * Runs the core's small warm-up job (every 3D strategy on a 16 × 12 mm part, about 0.1 s of
   * native work) once, in a worker of its own that ends with it, while the engine's workers
   * stay free. A browser compiles a module's functions as they are first called and optimises
   * them only once they have run a while, and the workers of a page share that code: without
   * the warm-up a user's first job runs partly in baseline code and takes about twice as long
   * (BENCHMARKS.md, issue 13). A run asked for before it is over ends it. Never rejects.
   */
  async #warmUp(make, wasm) {
    const side = (this.#side = new Channel(make()));
    try {
      const { warmUp } = await side.call({ type: 'hello', helper: true, warmUp: true, wasm });
      // An engine with a pool runs jobs shared (the side worker alone taking every part of it).
      if (this.#helpers.length) await this.#runShared([side], warmUp.job, warmUp.part, 'warm-up.stl');
      else await side.call({ type: 'run', job: warmUp.job, bytes: warmUp.part, name: 'warm-up.stl' });
    } catch {
      // A warm-up that fails costs the first run some speed, nothing else.
    } finally {
      side.end(new Error('the warm-up is over'));
      this.#side = null;
    }
  }

  /** A message to the worker that plans; resolves with its answer. The page's own requests go here. */
  call(message, transfer = [], onProgress) {
    return this.#main.call(message, transfer, onProgress);
  }

  /** A fresh copy of the default job for a part (`'part'`) or a drawing (`'drawing'`). */
  defaultJob(kind = 'part') {
    return structuredClone(kind === 'drawing' ? this.defaults.drawingJob : this.defaults.job);
  }

  /** Reads a part or drawing for the view: `{ part }` (typed arrays) or `{ drawing }`. */
  async open(bytes, name, job = this.defaultJob()) {
    const r = await this.call({ type: 'load', bytes, name, setup: job.part, stockMesh: job.stock?.mesh ?? null, drawingSetup: job.drawing });
    return r.drawing ? { drawing: r.drawing } : { part: r.part };
  }

  /**
   * The holes the hole operations (drill, bore, chamfer, threadMill) of `job` find in the part
   * or drawing in `bytes`, placed as the job places it, in the order their `holes` field numbers
   * them (a drawing's by its loops): `[{ center, diameter, top, bottom, through, bottomShape,
   * loopIndex, layer }]` (`swarf holes`). With `setup` (a job with setups), those of the part
   * as that setup holds it, which its operations pick from.
   */
  async holes(job, bytes, name, setup) { return (await this.call({ type: 'holes', job, bytes, name, setup })).holes; }
  /**
   * The round bosses (studs) an external thread mill (`threadMill` with `external: true`) of
   * `job` finds on the part in `bytes`, placed and numbered as its `holes` take them, in the
   * holes' form (`swarf holes --bosses`). A drawing has none: the promise rejects, saying so.
   */
  async bosses(job, bytes, name, setup) { return (await this.call({ type: 'bosses', job, bytes, name, setup })).holes; }
  /**
   * A part's top edges as a chamfer with `edges: 'partEdges'` of `job` finds them, placed as
   * the job places the part, numbered as its `loops` take them: `[{ z, sharp, length, points }]`
   * (`swarf edges`). A drawing's edges are its loops: the promise rejects, saying so.
   */
  async edges(job, bytes, name, setup) { return (await this.call({ type: 'edges', job, bytes, name, setup })).edges; }
  /** Reads a job file as `swarf run` does (a misspelt field is named). */
  async readJob(text) { return (await this.call({ type: 'readJob', text })).job; }
  /**
   * Every setting of `job` that does not fit, as `[{ path, message }]` (the core's own checks);
   * with `partBounds` (a part's `bounds`, as `open` gives them) also a stock box the part
   * sticks out of; with `holes` (as `holes` finds them) a hole operation's settings that do not
   * fit its holes: a hole deeper than the flutes, a peck deeper than the hole.
   */
  async checkJob(job, partBounds = null, holes = null) { return (await this.call({ type: 'checkJob', job, part: partBounds ? Array.from(partBounds) : null, holes })).problems; }
  /** Reads a post (JSON); the error names a field it does not know. */
  async readPost(text) { return (await this.call({ type: 'readPost', text })).post; }
  /** Reads a project file: `{ job, name, bytes }` (`bytes` null when the project only names its part). */
  async readProject(text) { return (await this.call({ type: 'readProject', text })).project; }
  /** A project file (JSON text) of the job with the part or drawing embedded. */
  async writeProject(job, name, bytes) { return (await this.call({ type: 'writeProject', job, name, bytes })).text; }

  /**
   * Runs a job on a part or drawing. `onProgress(fraction, stage)` reports as it goes;
   * aborting `signal` ends the work (the workers are replaced, the engine stays usable) and
   * rejects with a `CancelledError`. A program its simulation refuses rejects with an
   * `UnsafeProgramError` unless `allowUnsafe` is true. Resolves with `{ gcode, gcodeBytes, lineStarts, moveLines, summary, feeds, rapids,
   * feedOps, feedTools, feedMoves, rapidMoves, octants, part, drawing, sim }` (swarf.d.ts). With more than one worker, the pool first makes
   * the CL surfaces and the level maps of z-level work (in bands of rows) and the raster passes
   * (in ranges) on every worker, then plans operation by operation: the regions of a z-level
   * operation's levels are made on every worker first, and each operation's moves cut the
   * simulated stock in groups of bands of rows on every worker; the program and its
   * simulation are the same as one worker's. Runs asked for while
   * one runs wait for it. A job with setups runs through `runSetups`.
   */
  run(job, bytes, name, options = {}) {
    return this.#queued(() => this.#run(job, bytes, name, options));
  }

  /** `work` once the runs asked for before it are over: a pool's workers hold one prepared job each. */
  #queued(work) {
    const turn = this.#last.catch(() => {}).then(work);
    this.#last = turn;
    return turn;
  }

  async #run(job, bytes, name, { onProgress, signal, allowUnsafe = false } = {}) {
    if (job.setups?.length) throw new JobError('setups: the job has setups: run it with runSetups, which gives a program a setup', 'setups');
    const result = await this.#plan(job, bytes, name, onProgress, signal);
    // A program its own simulation refuses never leaves the engine quietly.
    if (result.summary.problem && !allowUnsafe) throw new UnsafeProgramError(result.summary.problem, result);
    return result;
  }

  /**
   * Runs a job with setups (a part machined from more than one side), one setup after another,
   * each from the stock the one before left (the planning worker keeps it), with the same
   * options as `run`: resolves with `{ setups: [result] }`, each a run's result with `setup`
   * (a SetupView: its index, name, where it holds the part and its stock box). A setup whose
   * program is unsafe rejects with an UnsafeProgramError naming the setup (its `result` the
   * whole), unless `allowUnsafe`. `seek` and `repost` then name the setup.
   */
  runSetups(job, bytes, name, options = {}) {
    return this.#queued(() => this.#runSetups(job, bytes, name, options));
  }

  async #runSetups(job, bytes, name, { onProgress, signal, allowUnsafe = false } = {}) {
    if (!job.setups?.length) throw new JobError('setups: the job has no setups: run it with run', 'setups');
    const n = job.setups.length, setups = [];
    for (let k = 0; k < n; k++) {
      const within = (f, stage) => onProgress?.((k + f) / n, `${job.setups[k].name || `Setup ${k + 1}`}: ${stage}`);
      const r = await this.#plan(job, bytes, name, within, signal, k);
      setups.push(r);
    }
    const result = { setups };
    const unsafe = setups.find((r) => r.summary.problem);
    if (unsafe && !allowUnsafe) throw new UnsafeProgramError(`${unsafe.setup.name}: ${unsafe.summary.problem}`, result);
    return result;
  }

  async #plan(job, bytes, name, onProgress, signal, setup) {
    if (signal?.aborted) throw aborted(signal);
    // A warm-up still under way would only take cores from the run: it ends here.
    this.#side?.end(new Error('a run began'));
    const onAbort = () => this.cancel();
    signal?.addEventListener('abort', onAbort, { once: true });
    try {
      const memory = this.#options.memory ?? globalThis.navigator?.deviceMemory;
      const sharing = workersFor(this.workers, bytes?.byteLength ?? bytes?.length ?? 0, memory);
      if (sharing === 1) return withText(await this.call({ type: 'run', job, bytes, name, setup }, [], onProgress));
      return withText(await this.#runShared([this.#main, ...this.#helpers.slice(0, sharing - 1)], job, bytes, name, onProgress, setup));
    } catch (e) {
      // Aborted: the signal's own reason where one was given (as fetch rejects).
      if (signal?.aborted) throw aborted(signal);
      throw typed(e, name);
    } finally {
      signal?.removeEventListener('abort', onAbort);
    }
  }

  /** A run shared by the workers `all`, the first of them planning (of setup `setup`, if any). */
  async #runShared(all, job, bytes, name, onProgress, setup) {
    const [planner, ...helpers] = all;
    const n = all.length;
    const [{ needs }] = await Promise.all(all.map((c, w) => c.call({ type: 'prepare', job, bytes, name, setup, helper: w > 0 })));
    const { surfaces, rasters, levelMaps } = needs;
    // Bands of rows of every exact CL surface, joined here.
    const joined = surfaces.map((s) => new Float64Array(s.nx * s.ny));
    const bands = surfaces.flatMap((s, surface) => ranges(s.ny, 4 * n).map(([j0, j1]) => ({ type: 'rows', surface, j0, j1 })));
    const stage = (from, to, what) => (f) => onProgress?.(from + (to - from) * f, `${what} (${n} workers)`);
    await share(all, bands, (t, r) => joined[t.surface].set(r.z, t.j0 * surfaces[t.surface].nx), stage(0, 0.2, 'CL z-maps'));
    // The planner keeps every surface; the others those the passes and level maps stand on.
    const under = new Set([...rasters.map((r) => r.surface), ...levelMaps]);
    await Promise.all(all.flatMap((c, w) => joined.map((z, surface) => (w === 0 || under.has(surface) ? c.call({ type: 'keepSurface', surface, z }) : null)).filter(Boolean)));
    // Ranges of raster passes, kept by the planner as they come; bands of the level maps
    // (each row's heights along the edges to the right, then up, then the widened cutter's
    // heights at its nodes: the node bounds the planner's links take), joined here.
    const size = (k) => surfaces[k].nx * surfaces[k].ny;
    const maps = new Map(levelMaps.map((k) => [k, { right: new Float64Array(size(k)), up: new Float64Array(size(k)), wide: new Float64Array(size(k)) }]));
    const tasks = [
      ...rasters.flatMap((r) => ranges(r.passes, 4 * n).map(([i0, i1]) => ({ type: 'passes', operation: r.operation, i0, i1 }))),
      ...levelMaps.flatMap((surface) => ranges(surfaces[surface].ny, 4 * n).map(([j0, j1]) => ({ type: 'levelRows', surface, j0, j1 }))),
    ];
    const kept = [];
    const done = (t, r) => {
      if (t.type === 'passes') {
        // Awaited below; handled now too, so that a pool ended before then (a cancel, a run that
        // ends the warm-up) leaves no rejection unhandled.
        const keep = planner.call({ type: 'keepPasses', operation: t.operation, first: t.i0, count: t.i1 - t.i0, flat: r.flat }, [r.flat.buffer]);
        keep.catch(() => {});
        kept.push(keep);
      } else {
        const nx = surfaces[t.surface].nx, half = (t.j1 - t.j0) * nx, m = maps.get(t.surface);
        m.right.set(r.z.subarray(0, half), t.j0 * nx);
        m.up.set(r.z.subarray(half, 2 * half), t.j0 * nx);
        m.wide.set(r.z.subarray(2 * half), t.j0 * nx);
      }
    };
    await share(all, tasks, done, stage(0.2, 0.5, 'passes and level maps'));
    // Every worker keeps the level maps: each contours regions of levels on them.
    for (const [surface, { right, up, wide }] of maps) kept.push(...all.map((c, w) => c.call({ type: 'keepLevelMap', surface, right, up, wide: w === 0 ? wide : new Float64Array(0) })));
    await Promise.all(kept);
    // Without z-level work the helpers only cut bands of the stock from now on: they let go of
    // their copy of the part and surfaces.
    if (!levelMaps.length) await Promise.all(helpers.map((h) => h.call({ type: 'release' })));
    const from = bands.length || tasks.length ? 0.5 : 0;
    let at = from;
    const planning = (f, s) => onProgress?.((at = from + (1 - from) * f), s);
    try {
      await planner.call({ type: 'startPlan' });
      // Operation by operation: the planner plans, then every worker cuts groups of the bands
      // of the in-process stock with its moves, and the planner takes them back.
      for (;;) {
        // The next operation's levels (z-level work): their regions, a level a task, made on
        // every worker and kept by the planner for the operation to take as it plans.
        const { work } = await planner.call({ type: 'regionWork' });
        if (work && work.levels.length > 1) {
          const { surface, levels, keep } = work, per = keep.length / levels.length;
          const made = [];
          const tasks = Array.from(levels, (z, k) => ({ type: 'levelRegions', surface, k, levels: levels.slice(k, k + 1), keep: keep.slice(k * per, (k + 1) * per) }));
          await share(all, tasks, (t, r) => { made[t.k] = r.flat; }, () => onProgress?.(at, `regions of levels (${n} workers)`));
          const flat = new Float64Array(made.reduce((sum, f) => sum + f.length, 0));
          made.reduce((offset, f) => (flat.set(f, offset), offset + f.length), 0);
          await planner.call({ type: 'keepRegions', flat }, [flat.buffer]);
        }
        const step = await planner.call({ type: 'planNext', groups: GROUPS_PER_WORKER * n }, [], planning);
        if (step.done) break;
        if (!step.groups) continue;
        // The moves to every helper (in pieces: a die's are tens of megabytes).
        await Promise.all(helpers.map((h) => h.call({ type: 'keepMoves', moves: step.moves })));
        const cut = { bands: [], cuts: [] };
        const groups = step.groups.map((group, g) => ({ type: 'cutBands', group, g, transfer: [group.buffer] }));
        await share(all, groups, (t, r) => { cut.bands[t.g] = r.bands; cut.cuts[t.g] = r.cuts; }, () => onProgress?.(at, `in-process stock (${n} workers)`));
        await planner.call({ type: 'absorb', groups: cut.bands, cuts: cut.cuts }, [...cut.bands, ...cut.cuts].map((a) => a.buffer));
      }
      return await planner.call({ type: 'finishPlan' }, [], planning);
    } finally {
      for (const h of helpers) h.call({ type: 'forget' }).catch(() => {});
    }
  }

  /**
   * The setup sheet of the last run (every setup of a job with setups) as a standalone,
   * printable HTML page: how to hold the part for each setup, its work offset and zero, the
   * stock, a picture from above with the zero marked, the tools, the operations and the times
   * (`swarf sheet`). `job` is the job that ran, `name` the part's file name.
   */
  async setupSheet(job, name) { return (await this.call({ type: 'sheet', job, name })).html; }

  /**
   * The last `runSetups`'s setups in one program, as `job.post` writes them (`post.oneProgram`):
   * each setup's program after the one before, the control stopping (M0) between them with a
   * message on how to hold the part, where to set the zero and which tool to put in.
   */
  async oneProgram(job) { return (await this.call({ type: 'oneProgram', job })).gcode; }

  /**
   * Reads a tool library machinists keep: Fusion's tool library JSON, a LinuxCNC tool table
   * (`.tbl`; `options.inches` when it is in inches), a FreeCAD bit (`.fctb`), or a FreeCAD
   * library (`.fctl`) with the bits it names among `files` (`[{ name, bytes }]`). Resolves
   * with `{ tools, notes }`: swarf's tools, and what the file holds that swarf did not take.
   */
  async readToolLibrary(files, options = {}) {
    const main = files.find((f) => /\.fctl$/i.test(f.name)) ?? files[0];
    const bits = files.filter((f) => f !== main).map((f) => ({ name: f.name, text: new TextDecoder().decode(f.bytes) }));
    return (await this.call({ type: 'readToolLibrary', bytes: main.bytes, name: main.name, inches: !!options.inches, bits })).library;
  }

  /** `tools` as a library of `format`: `'fusion'` (Fusion's JSON) or `'linuxCnc'` (a tool table): its text. */
  async writeToolLibrary(tools, format) { return (await this.call({ type: 'writeToolLibrary', tools, format })).text; }

  /**
   * `tools` as a FreeCAD library named `library`: `[{ name, text }]`, the library (`.fctl`,
   * for FreeCAD's `Tools/Library`) first, then a bit (`.fctb`, for `Tools/Bit`) a tool. A bit
   * holds no speeds or holder (FreeCAD's tool controller does): they are not written.
   */
  async writeFreecadLibrary(tools, library = 'swarf-tools') { return (await this.call({ type: 'writeFreecadLibrary', tools, library })).files; }

  /** Each tool's speeds and feeds as `job` cuts them (from the stock's material, or as typed): `[CuttingData]`. */
  async cuttingData(job) { return (await this.call({ type: 'cuttingData', job })).data; }

  /**
   * The work zero of `job` (or of its setup `setup`) with X0 Y0 on `point` ([x, y] where it
   * holds the part now: a hole's centre as `holes` gives it), its height kept: `WorkZero`, to
   * set as `job.stock.zero` or the setup's `zero`.
   */
  async zeroOn(job, partBounds, setup, point) { return (await this.call({ type: 'zeroOn', job, part: Array.from(partBounds), setup, point: Array.from(point) })).zero; }

  /**
   * Where each setup of `job` holds a part whose bounds are `partBounds` (as `open` gives them),
   * before a run: `[SetupView]` (empty for a job without setups), for a view that shows the
   * part turned over as the setup holds it.
   */
  async setupFrames(job, partBounds) { return (await this.call({ type: 'setupFrames', job, part: Array.from(partBounds) })).frames; }

  /**
   * How a view shows `job` before a run, on a part whose bounds are `partBounds` (as `open`
   * gives them): `[SetupView]`, each setup's frame, or the job's one for a job without setups
   * (the part moved to the work zero), each with its stock box and its fixtures' boxes in the
   * program's coordinates.
   */
  async stageFrames(job, partBounds) { return (await this.call({ type: 'stageFrames', job, part: Array.from(partBounds) })).frames; }

  /**
   * The last run's program (of its setup `setup`, for a job with setups) written again for
   * another post (or in the other unit), without planning again: `{ gcode, gcodeBytes,
   * lineStarts, extension, post, cycle, time, moveLines }`.
   */
  async repost(post, setup) {
    const { gcodeBytes, lineStarts, extension, post: name, cycle, time, moveLines } = await this.call({ type: 'repost', post, setup });
    return withText({ gcodeBytes, lineStarts, extension, post: name, cycle, time, moveLines });
  }

  /** The last run's simulated stock (of its setup `setup`) after `count` moves (a Float32Array of heights). */
  async seek(count, setup) { return (await this.call({ type: 'seek', count, setup })).tops; }

  /** Ends whatever runs: its promise rejects with a `CancelledError`; fresh workers take over. */
  async cancel() {
    for (const c of [this.#main, ...this.#helpers]) c.end(new CancelledError());
    await this.start();
  }

  /** Ends the workers for good. */
  close() {
    for (const c of [this.#main, ...this.#helpers, this.#side]) c?.end(new Error('the engine was closed'));
    this.#main = null;
    this.#helpers = [];
  }
}

/**
 * `m` with `gcode`, the program's text, made from `m.gcodeBytes` (its UTF-8 bytes, as the
 * worker sent them without a copy) when first read, and again if the bytes are replaced: a
 * die-sized program is tens of megabytes, and a page that shows it from the bytes and downloads
 * the bytes never holds its thread making the text.
 */
function withText(m) {
  let made = null;
  Object.defineProperty(m, 'gcode', {
    enumerable: true,
    get() {
      if (made?.bytes !== m.gcodeBytes) made = { bytes: m.gcodeBytes, text: new TextDecoder().decode(m.gcodeBytes) };
      return made.text;
    },
  });
  return m;
}

/**
 * Starts an engine. Options: `workerUrl` (default: worker.js beside this module), or `worker`
 * (a function making a Worker, for bundles; called once per worker of the pool), `wasm` (the
 * module's bytes or URL; default: pkg/swarf_bg.wasm beside the worker), `workers` (how
 * many workers the pool has; default: one per core, `navigator.hardwareConcurrency`, at most 8)
 * and `memory` (GB the device has; default `navigator.deviceMemory` where the browser tells it:
 * a run shares only as many workers as half of it holds for the part, see `workersFor`) and
 * `warmUp` (default true; false: no warm-up job as the engine starts, see `Engine.warmedUp`).
 */
export async function createEngine(options = {}) {
  if (!options.worker && !options.workerUrl && inNode()) options = { ...options, ...(await nodeOptions(options)) };
  return new Engine(options).start();
}

/**
 * What a run aborted through `signal` rejects with: the reason given to `abort(reason)`, else
 * (abort() gives a DOMException named AbortError) a CancelledError.
 */
function aborted(signal) {
  const r = signal.reason;
  return r === undefined || (r?.name === 'AbortError' && !(r instanceof CancelledError)) ? new CancelledError() : r;
}

/** Whether this runs under Node (no Web Worker; worker_threads instead). */
function inNode() {
  return typeof Worker === 'undefined' && typeof process !== 'undefined' && !!process.versions?.node;
}

/**
 * Under Node: workers from worker_threads running node-worker.js (worker.js as a Web Worker
 * sees it), the wasm read from pkg/ beside this module, one worker per core. The modules are
 * named through a variable so that no bundler making a page pulls Node's in.
 */
async function nodeOptions(options) {
  const load = (name) => import(/* webpackIgnore: true */ /* @vite-ignore */ name);
  const [{ Worker: NodeWorker }, fs, os] = await Promise.all([load('node:worker_threads'), load('node:fs'), load('node:os')]);
  // Named through variables too: a bundler that follows `new URL('…', import.meta.url)` would
  // emit them into a page's bundle.
  const [workerFile, wasmFile] = ['./node-worker.js', './pkg/swarf_bg.wasm'];
  const script = new URL(/* webpackIgnore: true */ workerFile, import.meta.url);
  const worker = () => {
    const w = new NodeWorker(script);
    const port = { onmessage: null, onerror: null, postMessage: (m, transfer) => w.postMessage(m, transfer), terminate: () => w.terminate(), ref: () => w.ref(), unref: () => w.unref() };
    w.on('message', (data) => port.onmessage?.({ data }));
    w.on('error', (e) => port.onerror?.({ message: e.message, preventDefault() {} }));
    return port;
  };
  const wasm = options.wasm ?? fs.readFileSync(new URL(/* webpackIgnore: true */ wasmFile, import.meta.url));
  return { worker, wasm, workers: options.workers ?? Math.min(8, os.availableParallelism?.() ?? os.cpus().length) };
}
