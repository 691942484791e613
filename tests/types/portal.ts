// What a portal writes against swarf.js, checked by TypeScript (tests/e2e: tsc --strict): the
// README's example, and uses of the generated types that must compile, and one that must not.
import { createEngine, type Job } from '../../www/swarf.js';

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

export function wrong(job: Job) {
  // @ts-expect-error: no such controller
  job.post.dialect = 'heidenhain';
}
