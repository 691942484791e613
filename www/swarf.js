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

export class Engine {
  #worker = null;
  #pending = new Map();
  #nextId = 1;
  #options;

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
  }

  async start() {
    const o = this.#options;
    this.#worker = o.worker ? o.worker() : new Worker(o.workerUrl ?? new URL('./worker.js', import.meta.url), { type: 'module' });
    this.#worker.onmessage = (event) => {
      const m = event.data, entry = this.#pending.get(m.id);
      if (!entry) return;
      if (m.type === 'progress') { entry.onProgress?.(m.fraction, m.stage); return; }
      this.#pending.delete(m.id);
      if (m.ok) entry.resolve(m); else entry.reject(new Error(m.error));
    };
    this.#worker.onerror = (e) => {
      for (const entry of this.#pending.values()) entry.reject(new Error(e.message || 'the worker failed'));
      this.#pending.clear();
    };
    const hello = await this.call({ type: 'hello', wasm: o.wasm ?? null });
    Object.assign(this, { defaults: hello.defaults, posts: hello.posts, sample: hello.sample, sampleDrawing: hello.sampleDrawing });
    return this;
  }

  /** A message to the worker; resolves with its answer. The page's own requests go here. */
  call(message, transfer = [], onProgress) {
    const id = this.#nextId++;
    return new Promise((resolve, reject) => {
      this.#pending.set(id, { resolve, reject, onProgress });
      this.#worker.postMessage({ id, ...message }, transfer);
    });
  }

  /** A fresh copy of the default job for a part (`'part'`) or a drawing (`'drawing'`). */
  defaultJob(kind = 'part') {
    return structuredClone(kind === 'drawing' ? this.defaults.drawingJob : this.defaults.job);
  }

  /** Reads a part or drawing for the view: `{ part }` (typed arrays) or `{ drawing }`. */
  async open(bytes, name, job = this.defaultJob()) {
    const r = await this.call({ type: 'load', bytes, name, setup: job.part, drawingSetup: job.drawing });
    return r.drawing ? { drawing: r.drawing } : { part: r.part };
  }

  /** Reads a job file as `swarf run` does (a misspelt field is named). */
  async readJob(text) { return (await this.call({ type: 'readJob', text })).job; }
  /** Reads a post (JSON); the error names a field it does not know. */
  async readPost(text) { return (await this.call({ type: 'readPost', text })).post; }
  /** Reads a project file: `{ job, name, bytes }` (`bytes` null when the project only names its part). */
  async readProject(text) { return (await this.call({ type: 'readProject', text })).project; }
  /** A project file (JSON text) of the job with the part or drawing embedded. */
  async writeProject(job, name, bytes) { return (await this.call({ type: 'writeProject', job, name, bytes })).text; }

  /**
   * Runs a job on a part or drawing. `onProgress(fraction, stage)` reports as it goes;
   * aborting `signal` ends the work (the worker is replaced, the engine stays usable) and
   * rejects with a `CancelledError`. Resolves with `{ gcode, summary, feeds, rapids, feedOps,
   * feedTools, octants, part, drawing, sim }`.
   */
  async run(job, bytes, name, { onProgress, signal } = {}) {
    if (signal?.aborted) throw new CancelledError();
    const onAbort = () => this.cancel();
    signal?.addEventListener('abort', onAbort, { once: true });
    try {
      return await this.call({ type: 'run', job, bytes, name }, [], onProgress);
    } finally {
      signal?.removeEventListener('abort', onAbort);
    }
  }

  /** The last run's program written again for another post, without planning again. */
  async repost(post) {
    const { gcode, extension, cycle } = await this.call({ type: 'repost', post });
    return { gcode, extension, cycle };
  }

  /** The last run's simulated stock after `count` moves (a Float32Array of heights). */
  async seek(count) { return (await this.call({ type: 'seek', count })).tops; }

  /** Ends whatever runs: its promise rejects with a `CancelledError`; a fresh worker takes over. */
  async cancel() {
    this.#worker.terminate();
    for (const entry of this.#pending.values()) entry.reject(new CancelledError());
    this.#pending.clear();
    await this.start();
  }

  /** Ends the worker for good. */
  close() {
    this.#worker?.terminate();
    this.#worker = null;
  }
}

/**
 * Starts an engine. Options: `workerUrl` (default: worker.js beside this module), or `worker`
 * (a function making the Worker, for bundles), and `wasm` (the module's bytes or URL; default:
 * pkg/swarf_bg.wasm beside the worker).
 */
export async function createEngine(options = {}) {
  return new Engine(options).start();
}
