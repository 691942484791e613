// The page's state: the jobs it edits (one for parts, one for drawings), the tool library, the
// part or drawing on show and the last result; kept in the browser's storage across reloads.
// Every module of the page reads and changes it here. Jobs are the core's JSON: the forms
// start from the core's defaults, so no default is written twice.

export const $ = (id) => document.getElementById(id);

const TOOLS = 'swarf.tools', JOBS = 'swarf.jobs';

export const state = {
  engine: null, viewer: null,
  bytes: null, name: 'sample.stl', label: 'sample part', sample: null, sampleDrawing: null, defaults: null, posts: [],
  kind: 'part', drawing: null, part: null,
  tools: [], jobs: { part: null, drawing: null }, selected: { tool: 0, part: 0, drawing: 0, setup: 0 },
  // A job with setups gives a result a setup (`results`); `result` is the one on show.
  running: false, result: null, results: null, problem: null, extension: null,
  problems: [],
  // The last program's text (made when read: the page itself shows and downloads its bytes).
  get gcode() { return this.result?.gcode ?? null; },
};

// What other modules register for one another (a page module calls the ones registered after
// it only through these: the single-file build links modules in order).
export const hooks = {};

export const job = () => state.jobs[state.kind];
// A part's job may have setups (each its own operations; a job without is its one setup): the
// setup on show, and the operations the list edits (those of the setup on show).
export const hasSetups = (j = job()) => state.kind === 'part' && (j?.setups?.length ?? 0) > 0;
export const setupIndex = (j = job()) => (hasSetups(j) ? Math.max(0, Math.min(state.selected.setup, j.setups.length - 1)) : 0);
export const ops = (j = job()) => (hasSetups(j) ? j.setups[setupIndex(j)].operations : j.operations);
// Every operation of a job, of every setup.
export const allOps = (j) => [...(j.operations ?? []), ...(j.setups ?? []).flatMap((s) => s.operations ?? [])];
export const selectedOp = () => ops()[state.selected[state.kind]] ?? null;
export const selectedTool = () => state.tools[state.selected.tool] ?? null;
// Each kind's form, as the core describes it (`defaults.forms`): what it works on, what it
// picks from.
export const formOf = (kind) => state.defaults?.forms?.find((f) => f.kind === kind);
export const is2d = (op) => formOf(op.kind)?.applies === 'drawing';
// The hole operations work on a part's holes and on a drawing's circles alike, facing on a
// part's stock and a sheet alike.
export const picksHoles = (op) => formOf(op.kind)?.picks === 'holes';
export const isEither = (op) => formOf(op.kind)?.applies === 'either';

// Keeps the settings and makes their change a step to undo; the changes of one field typed
// without a pause (`burst`: the field's key) are one step.
export function store(burst = null) {
  keep();
  record(burst);
}

function keep() {
  try {
    localStorage.setItem(TOOLS, JSON.stringify(state.tools));
    localStorage.setItem(JOBS, JSON.stringify(state.jobs));
  } catch { /* private mode: nothing kept */ }
}

// ---- undo and redo ------------------------------------------------------------------------
// Every change that is stored is a step back (the library and both jobs as they were before
// it); the changes of one burst (the keystrokes of one field's value, typed without a pause)
// are one.
const UNDO_STEPS = 200;
const BURST_MS = 800;
const history = { done: [], undone: [], current: null, last: 0, burst: null };
const snapshot = () => JSON.stringify({ tools: state.tools, jobs: state.jobs });

function record(burst) {
  const now = snapshot();
  if (history.current === null || now === history.current) { history.current = now; return; }
  const same = burst !== null && burst === history.burst && performance.now() - history.last <= BURST_MS;
  history.burst = burst;
  if (!same || !history.done.length) {
    history.done.push(history.current);
    if (history.done.length > UNDO_STEPS) history.done.shift();
  }
  history.last = performance.now();
  history.current = now;
  history.undone = [];
  hooks.history?.();
}

// The settings as they stand become the start of the history (after the page has restored them).
export function startHistory() {
  Object.assign(history, { done: [], undone: [], current: snapshot(), last: 0 });
  hooks.history?.();
}

export const canUndo = () => history.done.length > 0;
export const canRedo = () => history.undone.length > 0;

// Goes one step back (`back`) or forward again; false where there is none.
export function undo(back = true) {
  const [from, to] = back ? [history.done, history.undone] : [history.undone, history.done];
  if (!from.length) return false;
  to.push(snapshot());
  const then = JSON.parse(from.pop());
  const placed = JSON.stringify(state.jobs[state.kind]?.part);
  state.tools = then.tools;
  state.jobs = then.jobs;
  history.current = snapshot();
  history.last = 0;
  history.burst = null;
  keep();
  hooks.fillAll?.();
  // A part read another way (units, scale, up axis, turn) is shown again as it was read.
  if (JSON.stringify(state.jobs[state.kind]?.part) !== placed) hooks.showPart?.();
  else hooks.showHeld?.();
  hooks.history?.();
  return true;
}

// The library and the jobs as the browser kept them, each read again by the core (an older
// page's job is read as its version says; one that no longer reads gives way to the defaults,
// and the message says so). How a part is read (units, scale, up axis, turn) belongs to the
// part, not to the page: it starts from the defaults, as it does for every new file.
export async function restore(read) {
  const d = state.defaults;
  const kept = (key) => { try { return JSON.parse(localStorage.getItem(key) || 'null'); } catch { return null; } };
  const tools = kept(TOOLS), jobs = kept(JOBS);
  const storedTools = Array.isArray(tools) && tools.length > 0;
  state.tools = storedTools ? tools : structuredClone(d.job.tools);
  const fresh = { part: structuredClone(d.job), drawing: structuredClone(d.drawingJob) };
  const lost = [];
  for (const kind of ['part', 'drawing']) {
    const j = jobs?.[kind];
    let restored = fresh[kind];
    if (j && Array.isArray(j.operations)) {
      try {
        restored = await read({ ...j, tools: [] });
      } catch (e) {
        lost.push(`${kind === 'part' ? 'the part job' : 'the drawing job'} (${e.message})`);
      }
    }
    restored.part = structuredClone(fresh.part.part);
    if (kind === 'drawing') restored.drawing = { ...restored.drawing, units: fresh.drawing.drawing.units, origin: fresh.drawing.drawing.origin };
    delete restored.tools;
    state.jobs[kind] = restored;
  }
  // The drawing job's tool (a flat end mill) joins a new library, under a free number when its
  // own is taken by another tool, and the drawing's operations follow it.
  for (const t of storedTools ? [] : d.drawingJob.tools) {
    const tool = structuredClone(t);
    if (state.tools.some((u) => u.number === tool.number)) tool.number = Math.max(...state.tools.map((u) => u.number)) + 1;
    state.tools.push(tool);
    if (!jobs?.drawing) for (const op of state.jobs.drawing.operations) if (op.tool === t.number) op.tool = tool.number;
  }
  // A library from before (or emptied) leaves no operation pointing nowhere.
  for (const j of Object.values(state.jobs)) {
    for (const op of allOps(j)) {
      if (op.kind === 'roughOctree') op.tools = (op.tools ?? []).filter((n) => state.tools.some((t) => t.number === n));
      else if (!state.tools.some((t) => t.number === op.tool)) op.tool = state.tools[0]?.number ?? 1;
    }
  }
  return lost;
}

// Objects and their fields by dotted keys ("stock.marginXy", "tabs.count").
export function getKey(obj, key) { return key.split('.').reduce((o, k) => (o == null ? undefined : o[k]), obj); }
export function setKey(obj, key, value) {
  const ks = key.split('.');
  let o = obj;
  for (const k of ks.slice(0, -1)) { if (o[k] == null || typeof o[k] !== 'object') o[k] = {}; o = o[k]; }
  o[ks[ks.length - 1]] = value;
}

// The tools an operation uses: its own, or for octree roughing those it may choose from (its
// list, else every flat and bull-nose end in the library).
export function toolsOf(op) {
  // A V-carve's flat tool clears its floor.
  if (op.kind === 'vcarve') return op.flatTool != null ? [op.tool, op.flatTool] : [op.tool];
  if (op.kind !== 'roughOctree') return [op.tool];
  return op.tools?.length ? op.tools : state.tools.filter((t) => t.shape === 'flat' || t.shape === 'bullNose').map((t) => t.number);
}

// The job to run or save: this kind's job with the library's tools its operations use (every
// tool of the library with `all`, so that a tool's place in the job is its place in the list).
export function buildJob({ all = false } = {}) {
  const j = structuredClone(job());
  j.name = state.name.replace(/\.[^.]*$/, '');
  const used = new Set(allOps(j).flatMap(toolsOf));
  j.tools = all ? structuredClone(state.tools) : state.tools.filter((t) => used.has(t.number));
  return j;
}

// The time `seconds` as the program's head writes it: h:mm:ss or m:ss, and which of the two.
export function clock(seconds) {
  const s = Math.max(0, Math.round(seconds));
  const h = Math.floor(s / 3600), m = Math.floor((s % 3600) / 60), r = s % 60;
  return `${h ? `${h}:${String(m).padStart(2, '0')}` : m}:${String(r).padStart(2, '0')}`;
}
export const clockFormat = (seconds) => (Math.round(seconds) >= 3600 ? 'h:mm:ss' : 'm:ss');

export function downloadText(name, text, type) {
  const a = document.createElement('a');
  a.href = URL.createObjectURL(new Blob([text], { type }));
  a.download = name;
  document.body.appendChild(a);
  a.click();
  setTimeout(() => { URL.revokeObjectURL(a.href); a.remove(); }, 1000);
}
