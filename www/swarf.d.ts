// The API of swarf.js. The data it passes (jobs, tools, operations, posts, projects, results)
// has the types generated from swarf's Rust serde types (types/swarf-types.d.ts); only the
// engine's own calls, and the input forms of those types, are declared here.
import type { Job, Post, PostSettings, CycleTime, Project, Summary, DrawingView, ReportView, Reposted, Problem, Warning, OperationReport, TimeItem, Hole, EdgeView, SetupView, OperationForm, WorkZero, MaterialChoice, Machine, CuttingData, Imported, LibraryFormat, Holder } from './types/swarf-types.js';

// Every type of a job and of what the engine gives, by name (`Tool`, `Operation`, `Setup`,
// `Holder`, `RoughAdaptive`, …).
export type * from './types/swarf-types.js';

/**
 * What the engine takes of a type: every field the core fills with its default may be left out
 * (an operation's `kind` may not: it says which operation it is). Fixed-length lists (a box's
 * corners) are given whole. The engine reads what it is given as `swarf run` reads a job file:
 * a misspelt field or a value of the wrong type is an error naming its path.
 */
/** Bytes on an ArrayBuffer of their own (what a `Blob` takes): `Uint8Array<ArrayBuffer>` where
 * TypeScript (5.7 on) makes typed arrays generic, the plain `Uint8Array` before. */
export type Bytes = ReturnType<typeof Uint8Array.from>;

export type Input<T> = T extends readonly [unknown, ...unknown[]]
  ? T
  : T extends (infer U)[]
    ? Input<U>[]
    : T extends object
      ? { [K in keyof T as K extends 'kind' ? K : never]: T[K] } & { [K in keyof T as K extends 'kind' ? never : K]?: Input<T[K]> }
      : T;

/** A job as a portal writes it: only what differs from the defaults. */
export type JobInput = Input<Job>;
export type ToolInput = Input<Job['tools'][number]>;
export type OperationInput = Input<Job['operations'][number]>;
export type PostSettingsInput = Input<PostSettings>;
/** The default job (`defaultJob`): every field filled, and its lists of operations and tools
 * open to ones written as inputs (`job.operations.push({ kind: 'drill', tool: 3 })`). */
export type DefaultJob = Job & { operations: (Job['operations'][number] | OperationInput)[]; tools: (Job['tools'][number] | ToolInput)[] };

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
  /** Holes in its surface (open edges), triangles dropped. */
  warnings: Warning[];
  /** The placed triangles' identity: equal only for the same triangles in the same place. */
  hash: string;
}

/** The simulated program, for scrubbing through it. */
export interface Simulation {
  /** originX, originY, spacing, nx, ny, stockBottom, stockTop, gougeTolerance of the stock's cells (as sent: coarsened to at most 512 × 512). */
  grid: number[];
  /** The part's surface plus the allowance per cell (NaN off the part). */
  part: Float32Array;
  /** When each move starts (s), and at the end the program's cycle time. */
  times: Float64Array;
  /** Each move's material removal rate (mm³/min). */
  mrr: Float32Array;
  /** Places of gouges and collisions: x, y, z, kind (0 gouge, 1 rapid, 2 tool body). */
  findings: Float32Array;
  report: ReportView;
  /** The stock's heights after the last move. */
  start: Float32Array;
}

export interface RunResult {
  /** The program (made from `gcodeBytes` when first read). */
  readonly gcode: string;
  /** The program as UTF-8 bytes: what a page shows or downloads without making one string of it. */
  gcodeBytes: Bytes;
  /** Where each line of the program starts in `gcodeBytes` (line 0 at 0). */
  lineStarts: Uint32Array;
  /** The line (0 first) of `gcode` each move of the program ended on. */
  moveLines: Uint32Array;
  summary: Summary;
  /** Cutting moves as segments: x0, y0, z0, x1, y1, z1 per segment (mm). */
  feeds: Float32Array;
  rapids: Float32Array;
  /** Per cutting segment, the index of its operation, its tool's number and its move. */
  feedOps: Float32Array;
  feedTools: Float32Array;
  feedMoves: Uint32Array;
  /** Per rapid segment, its move. */
  rapidMoves: Uint32Array;
  octants: Float32Array;
  part: PartPreview;
  drawing: DrawingView | null;
  sim: Simulation | null;
}

/** Where a setup holds the part, and its result. */
export interface SetupResult extends RunResult {
  setup: SetupView;
}

/** A job with setups, run: one result a setup, in order. */
export interface SetupsResult {
  setups: SetupResult[];
}

export interface RunOptions {
  onProgress?: (fraction: number, stage: string) => void;
  /**
   * Aborting it ends the work; the promise rejects with the reason given to `abort(reason)`
   * (as `fetch` does), or a CancelledError where none was given.
   */
  signal?: AbortSignal;
  /**
   * Resolve with a program its simulation refuses (a gouge, a rapid through stock, the tool's
   * body in material; it then starts with a warning comment), as `swarf run --write-anyway`
   * writes it. Default false: such a run rejects with an UnsafeProgramError.
   */
  allowUnsafe?: boolean;
}

export declare class CancelledError extends Error {
  name: 'AbortError';
}

/**
 * A job that does not read or fit: `path` is the field's path as `checkJob` gives it
 * (`operations[0].stepdown`, `stock.bar.diameter`, `setups`; `''` for the whole job).
 */
export declare class JobError extends Error {
  name: 'JobError';
  path: string;
}

/** A part's or drawing's file that does not read: `file` is its name; the message says where. */
export declare class FileError extends Error {
  name: 'FileError';
  file: string;
}

/** A run whose program is not safe to run: `problem` says why; `result` is the run's result. */
export declare class UnsafeProgramError extends Error {
  name: 'UnsafeProgramError';
  problem: string;
  result: RunResult;
}

export declare class Engine {
  /** How many workers share a run. */
  readonly workers: number;
  defaults: { job: Job; drawingJob: Job; tool: Job['tools'][number]; operations: Job['operations']; forms: OperationForm[]; materials: MaterialChoice[]; machines: Machine[]; holders: Holder[] };
  posts: { dialect: PostSettings['dialect']; post: Post }[];
  /** The sample part (binary STL) and drawing (DXF). */
  sample: Uint8Array;
  sampleDrawing: Uint8Array;
  /** Settles once the warm-up job has run (at once when the engine was made with `warmUp: false`). */
  warmedUp: Promise<void>;
  /** Every field filled; a portal may push operations and tools written as inputs. */
  defaultJob(kind?: 'part' | 'drawing'): DefaultJob;
  open(bytes: Uint8Array, name: string, job?: JobInput): Promise<{ part: PartPreview } | { drawing: DrawingView }>;
  readJob(text: string): Promise<Job>;
  /**
   * Every setting of a job that does not fit, by its path (empty when it is good). With
   * `partBounds` (a part's `bounds`), also a stock box the part sticks out of (`stock.sizeBox`);
   * with `holes` (as `holes` finds them), a hole operation's settings that do not fit its holes.
   */
  checkJob(job: JobInput, partBounds?: number[] | null, holes?: Hole[] | null): Promise<Problem[]>;
  readPost(text: string): Promise<Post>;
  readProject(text: string): Promise<{ job: Job; name: string; bytes: Uint8Array | null }>;
  writeProject(job: JobInput, name: string, bytes: Uint8Array): Promise<string>;
  /** Runs a job without setups (one with setups rejects: see `runSetups`). */
  run(job: JobInput, bytes: Uint8Array, name: string, options?: RunOptions): Promise<RunResult>;
  /** Runs a job with setups, one after another, each from the stock the one before left. */
  runSetups(job: JobInput, bytes: Uint8Array, name: string, options?: RunOptions): Promise<SetupsResult>;
  /** The last run's setup sheet (every setup's), a printable HTML page. */
  setupSheet(job: JobInput, name: string): Promise<string>;
  /** The last run's setups in one program (`job.post`), an operator stop (M0) between them saying how to hold the part next. */
  oneProgram(job: JobInput): Promise<string>;
  /** Reads a tool library (Fusion JSON, LinuxCNC .tbl, FreeCAD .fctb, or .fctl with its bits among `files`): swarf's tools and what was not taken. */
  readToolLibrary(files: { name: string; bytes: Uint8Array }[], options?: { inches?: boolean }): Promise<Imported>;
  /** `tools` as Fusion's tool library JSON or a LinuxCNC tool table. */
  writeToolLibrary(tools: Job['tools'], format: LibraryFormat): Promise<string>;
  /** `tools` as a FreeCAD library: its `.fctl` first, then a `.fctb` bit a tool (no speeds or holder: FreeCAD's tool controller holds those). */
  writeFreecadLibrary(tools: Job['tools'], library?: string): Promise<{ name: string; text: string }[]>;
  /** Each tool's speeds and feeds as `job` cuts them (from the stock's material, or as typed), with how they were worked out. */
  cuttingData(job: JobInput): Promise<CuttingData[]>;
  /** The work zero with X0 Y0 on `point` (a hole's centre as `holes` gives it) where `job`, or its setup `setup`, holds the part now; its height kept. */
  zeroOn(job: JobInput, partBounds: ArrayLike<number>, setup: number | undefined, point: ArrayLike<number>): Promise<WorkZero>;
  /** Where each setup of `job` holds a part of these bounds, before a run (empty without setups). */
  setupFrames(job: JobInput, partBounds: ArrayLike<number>): Promise<SetupView[]>;
  /** How a view shows `job` before a run: each setup's frame, or the job's one (the part moved to the work zero), with its stock box and fixtures' boxes. */
  stageFrames(job: JobInput, partBounds: ArrayLike<number>): Promise<SetupView[]>;
  holes(job: JobInput, bytes: Uint8Array, name: string, setup?: number): Promise<Hole[]>;
  /** A part's round bosses (studs), for an external thread mill: numbered as its `holes` take them. */
  bosses(job: JobInput, bytes: Uint8Array, name: string, setup?: number): Promise<Hole[]>;
  /** A part's top edges for a chamfer (`edges: 'partEdges'`): numbered as its `loops` take them. */
  edges(job: JobInput, bytes: Uint8Array, name: string, setup?: number): Promise<EdgeView[]>;
  repost(post: PostSettingsInput, setup?: number): Promise<Reposted & { moveLines: Uint32Array; gcodeBytes: Bytes; lineStarts: Uint32Array }>;
  seek(count: number, setup?: number): Promise<Float32Array>;
  cancel(): Promise<void>;
  close(): void;
}

export declare function createEngine(options?: EngineOptions): Promise<Engine>;

/** How many of `count` workers share a run on a part of `bytes` bytes with `memoryGb` of memory. */
export declare function workersFor(count: number, bytes: number, memoryGb?: number): number;
