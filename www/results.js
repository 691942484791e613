// Generate, cancel and download, and what a run gives back: the view of its paths, the
// summary with the cycle time's breakdown, the warnings (amber, with their places) and errors
// (red), the program in its pane, its simulation; the job, the project and the post as files.
import { $, state, hooks, job, ops, store, buildJob, is2d, isEither, allOps, hasSetups, setupIndex, clock, clockFormat, downloadText } from './state.js';
import { fillFields, message, check, answered, problemWords } from './forms.js';
import { opColor, toolColor, cssColor, RAPID_COLOR, MARK_COLORS } from './viewer.js';
import { sim, showSimulation, showRestAreas } from './simulation.js';
import * as units from './units.js';

// Runs `steps` one task each (the view held, then drawn once); a step that returns steps has
// them run so too.
async function inSteps(steps) {
  const viewer = state.viewer;
  const run = (step) => { const more = step(); if (Array.isArray(more)) more.forEach(run); };
  if (!viewer) { steps.forEach(run); return; }
  await viewer.batch(async () => {
    const queue = [...steps];
    while (queue.length) {
      // Each step in a task of its own, the first too: the task that brought the result
      // (its message from the worker) holds the page's thread no longer than it takes to read.
      await new Promise((resolve) => setTimeout(resolve, 0));
      const more = queue.shift()();
      if (Array.isArray(more)) queue.unshift(...more);
    }
  });
}

export function setRunning(running) {
  state.running = running;
  document.querySelectorAll('#settings input, #settings select, #settings button, #panel .actions button, #panel .actions input, #drop button').forEach((el) => { el.disabled = running; });
  $('generate').disabled = running || !state.bytes;
  $('cancel').disabled = !running;
  $('download').disabled = $('sheet').disabled = running || !state.result;
  if (!running) hooks.fillAll?.();
}

// A failed or cancelled Generate, or a new part, leaves nothing of the result it replaced: no
// path, no simulation, no statistics, no download.
export function clearResult() {
  Object.assign(state, { result: null, results: null, problem: null });
  state.viewer?.clearPaths();
  showSimulation(null);
  $('stats').textContent = '';
  $('warnings').textContent = '';
  $('warning-count').textContent = '';
  $('sim-report').textContent = '';
  sim.pane?.set(null);
  $('download').disabled = $('sheet').disabled = true;
  $('progress').value = 0;
  $('stage').textContent = '';
  legend(null);
  // The part as the program will see it again, with its stock, fixtures and zero.
  hooks.restage?.();
}

// The legend over the view: each operation's colour (and for octree roughing, each tool's) and
// tools, with a box to hide it; the rapids' and the problems' colours. A rest operation's row
// has a button that shows the rest areas it starts from.
function legend(summary, byTool = new Set(), operations = []) {
  const el = $('legend');
  el.replaceChildren();
  if (!summary) { el.hidden = true; return; }
  el.hidden = false;
  const row = (color, text, key) => {
    const label = document.createElement('label');
    if (key !== undefined) {
      const box = document.createElement('input');
      box.type = 'checkbox';
      box.checked = !state.viewer?.hiddenOps.has(key);
      box.dataset.op = String(key);
      label.append(box);
    }
    const swatch = document.createElement('span');
    swatch.className = 'swatch';
    swatch.style.background = cssColor(color);
    label.append(swatch, ` ${text}`);
    el.append(label);
    return label;
  };
  for (const o of summary.operations) {
    if (byTool.has(o.index)) {
      row(opColor(o.index), `${o.name}:`, o.index);
      for (const t of o.tools) row(toolColor(t), `  T${t}`);
    } else {
      const label = row(opColor(o.index), `${o.name} (T${o.tools.join(', T')})`, o.index);
      if (operations[o.index]?.restOnly) {
        const b = document.createElement('button');
        b.type = 'button';
        b.className = 'rest-areas';
        b.dataset.restOp = String(o.index);
        b.textContent = 'rest areas';
        b.title = 'scrub to where it starts and show in magenta what the earlier operations left for it';
        label.append(' ', b);
      }
    }
  }
  row(RAPID_COLOR, 'rapids', 'rapids');
  row(MARK_COLORS[0], 'gouge');
  row([0.2, 0.42, 0.85, 1], 'material left');
}

export function onLegend(e) {
  const rest = e.target.closest('button[data-rest-op]');
  if (rest) { e.preventDefault(); showRestAreas(Number(rest.dataset.restOp)); return; }
  const box = e.target.closest('input[data-op]');
  if (!box || !state.viewer) return;
  const key = box.dataset.op === 'rapids' ? 'rapids' : Number(box.dataset.op);
  const hidden = new Set(state.viewer.hiddenOps);
  if (box.checked) hidden.delete(key); else hidden.add(key);
  state.viewer.setHiddenOps(hidden);
}

// The summary of the last Generate again (in the page's units, after they change).
export function showSummary() {
  if (state.summary && state.result) summaryTable(state.summary.s, state.summary.computed);
}

// The summary: figures, and the cycle time broken down as the program's head states it.
function summaryTable(s, computed) {
  const el = $('stats');
  el.replaceChildren();
  const head = document.createElement('div');
  head.textContent = `${s.moves.toLocaleString()} moves · ${units.distance(s.feedLength)} cutting · ${units.distance(s.rapidLength)} rapid · computed in ${computed.toFixed(2)} s`;
  const table = document.createElement('table');
  const tr = (cells, cls) => {
    const r = document.createElement('tr');
    if (cls) r.className = cls;
    cells.forEach((c, k) => { const td = document.createElement('td'); td.textContent = c; if (k > 0) td.className = 'num'; r.append(td); });
    table.append(r);
  };
  tr(['cycle time', `${clock(s.cycle.seconds)} ${clockFormat(s.cycle.seconds)}`, ''], 'head');
  const ops = new Map(s.operations.map((o) => [o.name, o]));
  for (const item of s.time) {
    const o = ops.get(item.label.replace(/ with T.*$/, ''));
    const rest = o?.restAfter?.length ? `rest roughing after ${o.restAfter.map((t) => `T${t}`).join(', ')}: ` : '';
    const engaged = o?.engagement ? `, engagement ${Math.round(100 * o.engagement.within)} % within ±10 % of ${o.engagement.target.toFixed(1)}° (peak ${Math.round(o.engagement.peak)}°)` : '';
    const extra = o && o.removed != null ? `${rest}${units.volume(o.removed)} removed, peak ${units.volume(o.mrrMax)}/min${o.powerMax != null ? ` (${o.powerMax.toFixed(2)} kW)` : ''}${o.leftMax != null ? `, leaves ≤ ${units.sized(o.leftMax)}` : ''}${engaged}` : '';
    tr([`  ${item.label}`, clock(item.seconds), extra]);
  }
  tr(['  total', clock(s.time.reduce((a, i) => a + i.seconds, 0)), `(${clockFormat(s.cycle.seconds)})`], 'total');
  el.append(head, table);
  if (s.feeds) {
    const f = s.feeds;
    const div = document.createElement('div');
    div.className = 'feeds';
    div.textContent = `Feeds optimised: ${f.faster.toLocaleString()} cuts faster where the chip thins, ${f.aired.toLocaleString()} moves in air at the air feed${f.slowed ? `, ${f.slowed.toLocaleString()} held for the spindle` : ''}; ${clock(f.seconds)} in motion against ${clock(f.plain)} as planned`;
    el.append(div);
  }
  const stages = s.operations.flatMap((o) => (o.stages ?? []).map((st) => `${o.name}: T${st.tool} φ${units.exact(st.diameter)} (${{ profile: 'around the part', first: 'first tool', rest: 'only where the larger cannot reach' }[st.role] ?? 'blocks left'}): ${st.why}; ${units.area(st.area)} cleared, ${units.volume(st.removed)} removed, ${clock(st.seconds)}`));
  if (stages.length) {
    const div = document.createElement('div');
    div.className = 'stages';
    div.textContent = stages.join('\n');
    el.append(div);
  }
}

// The warnings, each in its style (amber, or grey for a note) with its count and places; the
// problem, if any, first and in red. Returns how many there are of each.
function showWarnings(s) {
  const el = $('warnings');
  el.replaceChildren();
  const line = (text, cls) => { const d = document.createElement('div'); d.className = cls; d.textContent = text; el.append(d); return d; };
  if (s.problem) line(`Not safe to run: ${units.words(s.problem)}`, 'error');
  for (const w of s.warnings) {
    const d = line(units.words(w.operation ? `${w.operation}: ${w.message}` : w.message), w.level === 'note' ? 'note' : 'warning');
    // The loops an operation chose by itself, offered to pick (a V-carve with none picked).
    if (w.operation && w.loops?.length) {
      const b = document.createElement('button');
      b.type = 'button';
      b.className = 'pick-offered';
      b.textContent = `pick these ${w.loops.length} loops`;
      b.title = 'make the loops it carved the operation\'s own: then click a loop in the view to add or drop it';
      b.addEventListener('click', () => pickOffered(w.operation, w.loops));
      d.append(' ', b);
    }
  }
  const amber = s.warnings.filter((w) => w.level !== 'note').length;
  const count = $('warning-count');
  count.textContent = s.problem ? '!' : amber ? String(amber) : '';
  count.className = s.problem ? 'error' : '';
  return amber;
}

// Makes `loops` the loops of the operation named `name` (of the list on show), selects it in
// the operations' tab and shows them picked in the view.
function pickOffered(name, loops) {
  const list = ops(), k = list.findIndex((o) => o.name === name);
  if (k < 0) { message(`There is no operation named ${name} in the list any more.`, 'warning'); return; }
  list[k].loops = [...loops];
  state.selected[state.kind] = k;
  store();
  hooks.fillAll?.();
  hooks.changed?.();
  document.querySelector('#tabs [data-tab="ops"]')?.click();
  hooks.showPicked?.();
  message(`${name}: loops ${loops.join(', ')} picked, the regions it carved; click a loop in the view to add or drop it.`, 'note');
}

export function resultTab(name) {
  for (const b of document.querySelectorAll('#result-tabs [data-result]')) b.setAttribute('aria-selected', String(b.dataset.result === name));
  for (const r of document.querySelectorAll('#results .result')) r.hidden = r.dataset.result !== name;
  $('results').classList.remove('collapsed');
  if (name === 'gcode') sim.pane?.reveal();
}

export async function generate() {
  if (state.running) return;
  document.body.dataset.generated = 'running';
  const refuse = (text) => { message(text, 'error'); $('message').dataset.from = 'run'; document.body.dataset.generated = 'failed'; };
  const j = buildJob();
  const every = allOps(j);
  const wrong = every.filter((op) => !isEither(op) && (state.kind === 'drawing') !== is2d(op));
  if (wrong.length && wrong.length === every.length) {
    refuse(state.kind === 'drawing' ? 'add a pocket or profile operation for a drawing' : 'add a roughing or finishing operation for a part');
    return;
  }
  // The core's checks first, marked at their fields: the run would refuse the same.
  const problems = await check();
  if (problems.length) {
    refuse(`${problems.length} setting${problems.length > 1 ? 's need' : ' needs'} attention: ${problemWords(problems[0])}`);
    return;
  }
  store();
  clearResult();
  setRunning(true);
  message('');
  $('progress').value = 0;
  const started = performance.now();
  try {
    // The page takes an unsafe program too: it shows the problem in red with its places marked,
    // and asks before a download.
    const options = {
      allowUnsafe: true,
      onProgress: (fraction, stage) => { $('progress').value = fraction; $('stage').textContent = stage; },
    };
    // A job with setups gives a result a setup; the one on show is the setup on show's.
    const many = hasSetups(j);
    const results = many ? (await state.engine.runSetups(j, state.bytes, state.name, options)).setups : [await state.engine.run(j, state.bytes, state.name, options)];
    const computed = (performance.now() - started) / 1000;
    const k = many ? setupIndex(j) : 0;
    await showResult(results[k], many ? j.setups[k].operations : j.operations, computed);
    state.results = many ? results : null;
    state.computed = computed;
    // A problem is shown as one, in red, with its places marked in the view; the program can
    // still be downloaded, behind a confirmation that names it.
    const unsafe = results.find((r) => r.summary.problem);
    state.problem = unsafe ? (many ? `${unsafe.setup.name}: ${unsafe.summary.problem}` : unsafe.summary.problem) : null;
    const warned = results.flatMap((r) => r.summary.warnings.map((w) => ({ ...w, setup: many ? r.setup.name : null })));
    const amber = warned.filter((w) => w.level !== 'note');
    const notes = warned.length - amber.length;
    const cycle = results.reduce((t, r) => t + r.summary.cycle.seconds, 0);
    const each = many ? ` (${results.map((r) => `${r.setup.name} ${clock(r.summary.cycle.seconds)}`).join(', ')})` : '';
    if (state.problem) {
      message(`Not safe to run: ${state.problem}`, 'error');
      resultTab('warnings');
    } else if (amber.length) {
      message(`Done, with ${amber.length} warning${amber.length > 1 ? 's' : ''}: ${amber.map((w) => [w.setup, w.operation, w.message].filter(Boolean).join(': ')).join('\n')}`, 'warning');
      resultTab('warnings');
    } else {
      message(`Done: cycle time ${clock(cycle)} ${clockFormat(cycle)}${each}${notes ? ` (${notes} note${notes > 1 ? 's' : ''})` : ''}.`, 'ok');
      resultTab('summary');
    }
    $('progress').value = 1;
    $('stage').textContent = state.problem ? 'done, with problems' : 'done';
    $('download').disabled = $('sheet').disabled = false;
    document.body.dataset.generated = state.problem ? 'problem' : 'ok';
  } catch (e) {
    clearResult();
    const cancelled = e.message === 'cancelled by the user';
    if (!cancelled) {
      message(e.message, 'error');
      $('message').dataset.from = 'run';
    }
    $('stage').textContent = '';
    document.body.dataset.generated = cancelled ? 'cancelled' : 'failed';
  } finally {
    setRunning(false);
  }
}

// Shows the result `r` of a run of `operations` (a job's, or one setup's): its part as placed,
// its paths, program, simulation, legend, summary and warnings.
async function showResult(r, operations, computed) {
  // Which setup's result is on show (the simulation's requests name it).
  Object.assign(state, { result: r, extension: r.summary.extension, postName: r.summary.post, shownSetup: r.setup?.index });
  const s = r.summary;
  // The result reaches the view in steps, each a task of its own, so that none holds the
  // page's thread long on a die-sized result; the view draws once, after the last.
  const byTool = new Set(operations.map((op, i) => (op.kind === 'roughOctree' ? i : -1)).filter((i) => i >= 0));
  await inSteps([
    // The part framed again (the job may have placed it elsewhere).
    () => (r.drawing ? state.viewer?.setDrawing(r.drawing, false) : state.viewer?.setPart(r.part, true)),
    () => [
      ...(state.viewer?.pathSteps({ feeds: r.feeds, rapids: r.rapids, stock: s.stock, fixtures: s.fixtures, ops: r.feedOps, tools: r.feedTools, moves: r.feedMoves, rapidMoves: r.rapidMoves, byTool }) ?? []),
      () => {
        hooks.showPicked?.();
        if (r.octants.length) state.viewer?.setOctants(r.octants);
        // The blocks' box only where there are blocks to show (octree roughing).
        $('octants-box').hidden = !r.octants.length;
      },
    ],
    () => sim.pane?.set(r.gcodeBytes, r.lineStarts),
    () => showSimulation(r.sim, s),
  ]);
  legend(s, byTool, operations);
  state.summary = { s, computed };
  showSummary();
  showWarnings(s);
  document.body.dataset.shownSetup = String(r.setup?.index ?? 0);
}

// Setup `k`'s result on show (its tab chosen after Generate).
export async function showSetupResult(k) {
  const results = state.results;
  if (!results?.[k]) return;
  await showResult(results[k], job().setups[k].operations, state.computed ?? 0);
  $('download').disabled = $('sheet').disabled = false;
}

// The setup sheet of the last Generate, opened in a tab of its own to print (saved as a file
// where the browser opens no tab).
export async function showSheet() {
  if (!state.result) return;
  try {
    const html = await state.engine.setupSheet(buildJob(), state.name);
    const url = URL.createObjectURL(new Blob([html], { type: 'text/html' }));
    if (!window.open(url, '_blank')) downloadText(`${state.name.replace(/\.[^.]*$/, '')}-setup-sheet.html`, html, 'text/html');
    setTimeout(() => URL.revokeObjectURL(url), 60000);
  } catch (e) {
    message(e.message, 'error');
  }
}

export function cancel() {
  // The wasm runs synchronously in the worker, so cancelling ends the worker; a fresh one takes
  // its place and every setting stays.
  state.engine.cancel().catch((e) => message(e.message, 'error'));
  sim.busy = false;
  sim.wanted = null;
  clearResult();
  message('Cancelled. Your settings are kept.', 'note');
  document.body.dataset.generated = 'cancelled';
}

// The program's file name: the part's, the controller's, and the extension its controllers
// expect (`bracket-grbl.nc`, `bracket-fanuc.nc`: two controllers' programs never share one).
// A setup's program (`setup`: its index) says which it is: `bracket-op2-grbl.nc`, as
// `swarf run` names it.
export function programName(setup = null) {
  const slug = (state.postName ?? 'program').toLowerCase().replace(/[^a-z0-9]+/g, '').replace(/^$/, 'post');
  return `${state.name.replace(/\.[^.]*$/, '')}${setup === null ? '' : `-op${setup + 1}`}-${slug}.${state.extension ?? 'nc'}`;
}

// The program, or with setups every setup's program (one file each).
export function download() {
  if (!state.result) return;
  if (state.problem && !window.confirm(`This program is not safe to run: ${state.problem}.\n\nDownload it anyway? It starts with a warning comment.`)) return;
  if (!state.results) { downloadText(programName(), state.result.gcodeBytes, 'text/plain'); return; }
  if (job().post.oneProgram) { downloadOne(); return; }
  state.results.forEach((r, k) => downloadText(programName(k), r.gcodeBytes, 'text/plain'));
  message(`Downloaded ${state.results.length} programs, one a setup: ${state.results.map((r, k) => programName(k)).join(', ')}.`, 'ok');
}

// Every setup in one program, stopping between them (the core joins them).
async function downloadOne() {
  try {
    const gcode = await state.engine.oneProgram(buildJob({ all: true }));
    downloadText(programName(), gcode, 'text/plain');
    message(`Downloaded ${programName()}: ${state.results.length} setups in one program, the machine stopping (M0) between them.`, 'ok');
  } catch (e) {
    message(e.message, 'error');
  }
}

// ---- posts as data ----------------------------------------------------------------------
// The post in use (the user's own, else the built-in one of the chosen controller) saved as
// JSON to edit; a loaded one is read by the core, which names a field it does not know.
export function currentPost() {
  const p = job().post;
  return p.custom ?? state.posts.find((b) => b.dialect === p.dialect)?.post;
}

export function fillPost() {
  const j = job();
  fillFields($('fs-post'), j);
  const same = state.defaults.machines.find((m) => JSON.stringify(m) === JSON.stringify(j.machine));
  $('fs-post').querySelector('[name=machine]').value = same?.name ?? '';
  const custom = j.post.custom;
  $('post-custom').hidden = !custom;
  $('post-custom').textContent = custom ? `Using your post "${custom.name}" (choose a controller to go back to a built-in one).` : '';
}

export function savePost() {
  const post = currentPost();
  if (post) downloadText(`${post.name.replace(/[^\w.-]+/g, '_')}.post.json`, JSON.stringify(post, null, 2), 'application/json');
}

export async function loadPost(file) {
  try {
    const post = await state.engine.readPost(await file.text());
    job().post.custom = post;
    store();
    fillPost();
    message(`Loaded the post "${post.name}" from ${file.name}; programs now end in .${post.extension}.`, 'ok');
    await repost();
  } catch (e) {
    message(`${file.name}: ${e.message}`, 'error');
  }
}

// The program of the last Generate written again for the post (or the units) now chosen, no
// planning again: the plan is in millimetres and only the writing changes. `data-posted` counts
// the programs so written.
export async function repost() {
  if (!state.result || state.running) return;
  try {
    // Every setup's program, each written again.
    let r = null;
    for (const [k, result] of (state.results ?? [state.result]).entries()) {
      r = await state.engine.repost(job().post, state.results ? k : undefined);
      Object.assign(result, { moveLines: r.moveLines, gcodeBytes: r.gcodeBytes, lineStarts: r.lineStarts });
    }
    Object.assign(state, { extension: r.extension, postName: r.post });
    sim.pane?.set(state.result.gcodeBytes, state.result.lineStarts);
    message(`The program is written again for ${r.post}${job().post.units === 'inch' ? ' in inches' : ''}: cycle time ${clock(r.cycle.seconds)} ${clockFormat(r.cycle.seconds)}.`, 'ok');
  } catch (e) {
    clearResult();
    message(e.message, 'error');
  }
  document.body.dataset.posted = String(Number(document.body.dataset.posted ?? 0) + 1);
}

// ---- jobs and projects as files ----------------------------------------------------------
// The same JSON drives the page, `swarf run job.json part.stl` and the tests.
export function saveJob() {
  const j = buildJob();
  downloadText(`${j.name || 'job'}.json`, JSON.stringify(j, null, 2), 'application/json');
}

// A job file comes back whole: every operation, in order, and its tools (which join the
// library, replacing those of the same number). The core reads it as `swarf run` would: a
// misspelt or unknown field is named, and then nothing changes; values that do not fit are
// marked at their fields at once.
export async function loadJob(file) {
  try {
    const text = await file.text();
    if (/"format"\s*:\s*"swarf project"/.test(text)) return await openProject(file, text);
    const read = await state.engine.readJob(text);
    await applyJob(read);
    const problems = await check();
    if (problems.length) message(`Loaded the job from ${file.name}, but ${problems.length} setting${problems.length > 1 ? 's need' : ' needs'} attention: ${problems.map(problemWords).join('; ')}`, 'error');
    else message(`Loaded the job from ${file.name}: ${read.setups?.length ? `${read.setups.length} setups, ` : ''}${allOps(read).length} operation(s).`, 'ok');
  } catch (e) {
    message(`${file.name}: ${e.message}`, 'error');
  } finally {
    answered();
  }
}

// A job read by the core takes the place of the page's: its tools join the library (replacing
// those of the same number); `part` ({bytes, name}) is shown instead of the sample, read as the
// job says (a project keeps its part's units).
async function applyJob(read, part = null) {
  const every = allOps(read);
  if (!every.length) throw new Error('the job has no operations');
  for (const op of every) {
    const missing = (op.kind === 'roughOctree' ? op.tools : [op.tool]).find((n) => !read.tools.some((t) => t.number === n));
    if (missing != null) throw new Error(`operation '${op.name}' uses tool ${missing}, which the job does not have`);
  }
  // A job with setups turns a part over: a drawing is cut from one side.
  const kind = !read.setups?.length && every.some(is2d) && every.every((op) => is2d(op) || isEither(op)) ? 'drawing' : 'part';
  for (const t of read.tools) {
    const k = state.tools.findIndex((u) => u.number === t.number);
    if (k >= 0) state.tools[k] = t; else state.tools.push(t);
  }
  delete read.tools;
  // How the job reads its part belongs to that part: a project's part is read as its job says;
  // the part on show keeps its own settings under a job file.
  if (!part && kind === 'part') read.part = state.jobs.part.part;
  if (!part && kind === 'drawing') read.drawing = { ...read.drawing, units: state.jobs.drawing.drawing.units, origin: state.jobs.drawing.drawing.origin };
  state.jobs[kind] = read;
  state.selected[kind] = 0;
  state.selected.setup = 0;
  store();
  if (part) {
    hooks.setKind?.(kind);
    await hooks.showPart?.(part.bytes, part.name, part.name);
  } else if (kind !== state.kind) {
    const sample = kind === 'drawing' ? [state.sampleDrawing, 'sample.dxf', 'sample drawing'] : [state.sample, 'sample.stl', 'sample part'];
    await hooks.showPart?.(...sample);
  } else {
    hooks.fillAll?.();
    await hooks.showPart?.();
  }
}

// A project file holds the job and the part or drawing (embedded), for the page and for
// `swarf run project.swarf.json`.
export async function saveProject() {
  const j = buildJob();
  const text = await state.engine.writeProject(j, state.name, state.bytes);
  downloadText(`${state.name.replace(/\.[^.]*$/, '')}.swarf.json`, text, 'application/json');
}

export async function openProject(file, text) {
  try {
    const project = await state.engine.readProject(text ?? await file.text());
    await applyJob(project.job, project.bytes ? { bytes: project.bytes, name: project.name } : null);
    message(project.bytes
      ? `Opened the project ${file.name}: ${project.name}, ${allOps(project.job).length} operation(s).`
      : `Opened the project ${file.name}; it names its part ${project.name} without holding it: open that file.`, project.bytes ? 'ok' : 'warning');
  } catch (e) {
    message(`${file.name}: ${e.message}`, 'error');
  }
}
