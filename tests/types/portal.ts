// What a portal writes against swarf.js, checked by TypeScript (tests/e2e: tsc --strict): the
// README's example, and uses of the generated types that must compile, and some that must not.
import { createEngine, type Job, type JobInput, type ToolInput, type OperationReport } from '../../www/swarf.js';

export async function makeProgram(stl: Uint8Array): Promise<string> {
  const engine = await createEngine();
  const job: Job = engine.defaultJob();
  job.tools[0].diameter = 6;
  job.post.dialect = 'grbl';
  job.operations = job.operations.filter((op) => op.kind === 'finishRaster');
  for (const op of job.operations) if (op.kind === 'finishRaster') op.stepover = 1;
  const controller = new AbortController();
  const result = await engine.run(job, stl, 'part.stl', { onProgress: (f, stage) => console.log(f, stage), signal: controller.signal });
  console.log(`cycle time ${result.summary.cycle.seconds} s`);
  return result.gcode;
}

// A portal gives only what differs from the defaults: a tool without its corner radius, shank
// or coolant, an operation with its kind and two settings, a post with its controller.
export async function shortJob(stl: Uint8Array): Promise<number> {
  const engine = await createEngine({ workers: 1 });
  const ball: ToolInput = { number: 1, shape: 'ball', diameter: 6 };
  const input: JobInput = { tools: [ball], operations: [{ kind: 'finishRaster', tool: 1, stepover: 1 }], post: { dialect: 'grbl' } };
  const problems = await engine.checkJob(input);
  if (problems.length) throw new Error(problems.map((p) => `${p.path}: ${p.message}`).join('; '));
  const result = await engine.run(input, stl, 'part.stl');
  // The results are typed: each operation's time is a number, each warning has its level.
  const first: OperationReport = result.summary.operations[0];
  const seconds: number = first.seconds + result.summary.time.reduce((s, t) => s + t.seconds, 0);
  const amber: boolean = result.summary.warnings.some((w) => w.level === 'warning');
  const line: number = result.moveLines[0];
  return seconds + line + (amber ? 1 : 0) + (result.sim ? result.sim.times[0] : 0);
}

// A part from both sides: a job with setups gives a program a setup, each named and placed.
export async function bothSides(stl: Uint8Array, job: JobInput): Promise<string[]> {
  const engine = await createEngine();
  const frames = await engine.setupFrames(job, [-40, -25, -20, 40, 25, 0]);
  const turned: boolean = frames.some((f) => f.rotation[8] < 0);
  const { setups } = await engine.runSetups(job, stl, 'part.stl');
  const bottom = await engine.seek(0, 1);
  return setups.map((r) => `${r.setup.name} ${r.setup.stock.max[2]} ${turned} ${bottom.length}: ${r.gcode}`);
}

export function wrong(job: Job, input: JobInput) {
  // @ts-expect-error: no such controller
  job.post.dialect = 'heidenhain';
  // @ts-expect-error: an operation says which it is
  input.operations = [{ tool: 1, stepover: 1 }];
  // @ts-expect-error: a roughing's step-over is a fraction of the diameter, stepoverFraction
  input.operations = [{ kind: 'roughZlevel', stepover: 0.4 }];
}

// The default job takes operations and tools written as inputs (issue 55), and stays a Job.
export async function addToDefaults(stl: Uint8Array): Promise<number> {
  const engine = await createEngine({ workers: 1 });
  const job = engine.defaultJob();
  job.tools.push({ number: 3, shape: 'drill', diameter: 5, fluteLength: 30 });
  job.operations.push({ kind: 'drill', tool: 3, cycle: 'peck' });
  const whole: Job = job;
  const diameter: number = job.tools[0].diameter;
  const r = await engine.run(whole, stl, 'part.stl', { allowUnsafe: true });
  return diameter + r.summary.moves;
}
