// The API of swarf.js. The data it passes (jobs, tools, operations, posts, projects) has the
// types generated from swarf's Rust serde types (types/swarf-types.d.ts); only the engine's
// own calls are declared here.
import type { Job, Post, PostSettings, CycleTime, Project } from './types/swarf-types';

export type { Job, Post, PostSettings, CycleTime, Project };

export interface EngineOptions {
  /** The worker script (default: worker.js beside swarf.js). */
  workerUrl?: string | URL;
  /** Makes a worker instead (a bundle or single-file page); called once per worker of the pool. */
  worker?: () => Worker;
  /** How many workers share a run (default: one per core, at most 8; 1: no pool). */
  workers?: number;
  /**
   * The device's memory in GB (default: `navigator.deviceMemory`, where the browser tells it). A
   * run shares only as many workers as half of it holds: each holds its own copy of the part
   * and its preparation, about 24 times the part file's size.
   */
  memory?: number;
  /** The wasm module's bytes or URL (default: pkg/swarf_bg.wasm beside the worker). */
  wasm?: BufferSource | string | URL | null;
  /**
   * Runs a small built-in job once as the engine starts, in a worker of its own that ends with
   * it (default true), so that the browser has compiled and optimised the code before the
   * user's first run. The engine's workers stay free meanwhile. See `Engine.warmedUp`.
   */
  warmUp?: boolean;
}

export interface PartPreview {
  positions: Float32Array;
  normals: Float32Array;
  /** min x, y, z, max x, y, z (mm, placed). */
  bounds: number[];
  triangles: number;
  dropped: number;
}

export interface Summary {
  moves: number;
  feedLength: number;
  rapidLength: number;
  /** Seconds of motion at the feeds and the rapid rate. */
  seconds: number;
  /** The program's cycle time as its head states it (tool changes included). */
  cycle: CycleTime;
  warnings: { operation?: string | null; message: string }[];
  operations: Record<string, unknown>[];
  problem: string | null;
  /** The file extension the post expects (ngc, nc, tap). */
  extension: string;
  stock: number[];
  clearanceZ: number;
}

export interface RunResult {
  gcode: string;
  summary: Summary;
  /** Cutting moves as segments: x0, y0, z0, x1, y1, z1 per segment (mm). */
  feeds: Float32Array;
  rapids: Float32Array;
  /** Per cutting segment, the index of its operation and its tool's number. */
  feedOps: Float32Array;
  feedTools: Float32Array;
  octants: Float32Array;
  part: PartPreview;
  drawing: unknown | null;
  sim: unknown | null;
}

export interface RunOptions {
  onProgress?: (fraction: number, stage: string) => void;
  /** Aborting it ends the work; the promise rejects with a CancelledError. */
  signal?: AbortSignal;
}

export declare class CancelledError extends Error {
  name: 'AbortError';
}

export declare class Engine {
  /** How many workers share a run. */
  readonly workers: number;
  defaults: { job: Job; drawingJob: Job; tool: Job['tools'][number]; operations: Job['operations'] };
  posts: { dialect: PostSettings['dialect']; post: Post }[];
  /** The sample part (binary STL) and drawing (DXF). */
  sample: Uint8Array;
  sampleDrawing: Uint8Array;
  /** Settles once the warm-up job has run (at once when the engine was made with `warmUp: false`). */
  warmedUp: Promise<void>;
  defaultJob(kind?: 'part' | 'drawing'): Job;
  open(bytes: Uint8Array, name: string, job?: Job): Promise<{ part: PartPreview } | { drawing: unknown }>;
  readJob(text: string): Promise<Job>;
  readPost(text: string): Promise<Post>;
  readProject(text: string): Promise<{ job: Job; name: string; bytes: Uint8Array | null }>;
  writeProject(job: Job, name: string, bytes: Uint8Array): Promise<string>;
  run(job: Job, bytes: Uint8Array, name: string, options?: RunOptions): Promise<RunResult>;
  repost(post: PostSettings): Promise<{ gcode: string; extension: string; cycle: CycleTime }>;
  seek(count: number): Promise<Float32Array>;
  cancel(): Promise<void>;
  close(): void;
}

export declare function createEngine(options?: EngineOptions): Promise<Engine>;

/** How many of `count` workers share a run on a part of `bytes` bytes with `memoryGb` of memory. */
export declare function workersFor(count: number, bytes: number, memoryGb?: number): number;
