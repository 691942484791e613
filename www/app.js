// The page: settings, the worker that runs swarf's wasm, the view, and the download.
import { Viewer, OP_COLORS, toolColor } from './viewer.js';
import { createEngine } from './swarf.js';

const $ = (id) => document.getElementById(id);
const form = $('settings');

let viewer = null;
try { viewer = new Viewer($('view')); } catch (e) { showError(`3D view unavailable: ${e.message}`); }

// ---- the engine (swarf.js: the wasm in a worker of its own) -------------------------------
let engine = null;
const call = (message, transfer, onProgress) => engine.call(message, transfer, onProgress);

// ---- state -------------------------------------------------------------------------------
// The page edits jobs as the core's JSON has them: one for parts and one for drawings, each
// with its list of operations, and one tool library (the browser keeps them across reloads).
// Every form is filled from these objects, which start from the core's defaults, so no default
// is written twice.
const TOOLS = 'swarf.tools', JOBS = 'swarf.jobs';
const state = {
  bytes: null, name: 'sample.stl', sample: null, sampleDrawing: null, defaults: null, gcode: null, running: false, kind: 'part', drawing: null,
  tools: [], jobs: { part: null, drawing: null }, selected: { tool: 0, part: 0, drawing: 0 },
};
window.swarf = state; // for the end-to-end test and the curious

function showError(text) { const m = $('message'); m.className = ''; m.textContent = text; }
function showInfo(text) { const m = $('message'); m.className = 'info'; m.textContent = text; }

const job = () => state.jobs[state.kind];
const selectedOp = () => job().operations[state.selected[state.kind]] ?? null;
const selectedTool = () => state.tools[state.selected.tool] ?? null;
const is2d = (op) => op.kind === 'profile2d' || op.kind === 'pocket2d' || op.kind === 'engrave';

function store() {
  try {
    localStorage.setItem(TOOLS, JSON.stringify(state.tools));
    localStorage.setItem(JOBS, JSON.stringify(state.jobs));
  } catch { /* private mode: nothing kept */ }
}

function restore() {
  const d = state.defaults;
  const read = (key) => { try { return JSON.parse(localStorage.getItem(key) || 'null'); } catch { return null; } };
  const tools = read(TOOLS), jobs = read(JOBS);
  const storedTools = Array.isArray(tools) && tools.length > 0;
  state.tools = storedTools ? tools : structuredClone(d.job.tools);
  const fresh = { part: structuredClone(d.job), drawing: structuredClone(d.drawingJob) };
  for (const kind of ['part', 'drawing']) {
    const j = jobs?.[kind];
    state.jobs[kind] = j && Array.isArray(j.operations) ? { ...fresh[kind], ...j } : fresh[kind];
    delete state.jobs[kind].tools;
  }
  // The drawing job's tool (a flat end mill) joins the library, under a free number when its
  // own is taken by another tool, and the drawing's operations follow it.
  // (A kept library is the user's: nothing joins it.)
  for (const t of storedTools ? [] : d.drawingJob.tools) {
    const tool = structuredClone(t);
    if (state.tools.some((u) => u.number === tool.number)) tool.number = Math.max(...state.tools.map((u) => u.number)) + 1;
    state.tools.push(tool);
    if (!jobs?.drawing) for (const op of state.jobs.drawing.operations) if (op.tool === t.number) op.tool = tool.number;
  }
  // A library from before (or emptied) leaves no operation pointing nowhere.
  for (const j of Object.values(state.jobs)) {
    for (const op of j.operations) {
      if (op.kind === 'roughOctree') op.tools = (op.tools ?? []).filter((n) => state.tools.some((t) => t.number === n));
      else if (!state.tools.some((t) => t.number === op.tool)) op.tool = state.tools[0]?.number ?? 1;
    }
  }
}

// Objects and their fields by dotted keys ("stock.marginXy", "tabs.count").
function getKey(obj, key) { return key.split('.').reduce((o, k) => (o == null ? undefined : o[k]), obj); }
function setKey(obj, key, value) {
  const ks = key.split('.');
  let o = obj;
  for (const k of ks.slice(0, -1)) { if (o[k] == null || typeof o[k] !== 'object') o[k] = {}; o = o[k]; }
  o[ks[ks.length - 1]] = value;
}

function labelOf(el) { return el.closest('label')?.firstChild?.textContent.trim() || el.name; }

// The value of a form field as its object holds it.
function valueOf(el) {
  const type = el.dataset.type;
  if (el.type === 'checkbox') return el.checked;
  if (type === 'list') return el.value.split(',').map((v) => v.trim()).filter(Boolean);
  if (type === 'ints') {
    const v = el.value.split(',').map((w) => w.trim()).filter(Boolean).map(Number);
    if (v.some((x) => !Number.isInteger(x) || x < 0)) throw new Error(`${labelOf(el)}: give tool numbers, separated by commas`);
    return v;
  }
  if (type === 'numbers' || type === 'box') {
    // A list of numbers (empty: none), and a box as its min and max corners.
    if (el.value.trim() === '') return null;
    const v = el.value.split(',').map((w) => Number(w.trim()));
    if (v.length !== Number(el.dataset.count) || v.some((x) => !Number.isFinite(x))) throw new Error(`${labelOf(el)}: give ${el.dataset.count} numbers, separated by commas`);
    return type === 'box' ? { min: v.slice(0, 3), max: v.slice(3) } : v;
  }
  if (el.type === 'number' || type === 'int') {
    if (el.value === '' && type === 'optional') return null;
    const v = Number(el.value);
    if (el.value === '' || !Number.isFinite(v)) throw new Error(`${labelOf(el)} is not a number`);
    return type === 'int' ? Math.round(v) : v;
  }
  return el.value;
}

function show(el, value) {
  if (el.type === 'checkbox') el.checked = !!value;
  else if (el.dataset.type === 'list' || el.dataset.type === 'numbers' || el.dataset.type === 'ints') el.value = (value || []).join(', ');
  else if (el.dataset.type === 'box') el.value = value ? [...value.min, ...value.max].join(', ') : '';
  else el.value = value ?? '';
}

function fillFields(container, obj) {
  for (const el of container.querySelectorAll('[data-key]')) show(el, getKey(obj, el.dataset.key));
}

// ---- the forms ---------------------------------------------------------------------------
function fillJob() {
  const j = job();
  fillFields($('fs-part'), j);
  fillFields($('fs-drawing'), j);
  fillFields($('fs-post'), j);
  const custom = j.post.custom;
  $('post-custom').hidden = !custom;
  $('post-custom').textContent = custom ? `Using your post "${custom.name}" (choose a controller to go back to a built-in one).` : '';
  fillFields($('fs-stock'), j);
  $('fs-stock').querySelector('[name=zeroHeight]').value = j.stock.zero?.height ?? '';
  $('fs-stock').querySelector('[name=zeroCorner]').value = j.stock.zero?.corner ?? 'center';
  for (const el of document.querySelectorAll('.part-only')) el.hidden = state.kind !== 'part';
}

function fillTools() {
  const list = $('tool-list');
  list.replaceChildren(...state.tools.map((t, i) => new Option(`T${t.number} · ${t.diameter} mm ${{ ball: 'ball', flat: 'flat', bullNose: `bull nose r${t.cornerRadius}` }[t.shape] || t.shape}${t.name ? ` · ${t.name}` : ''}`, String(i))));
  state.selected.tool = Math.min(state.selected.tool, state.tools.length - 1);
  list.value = String(state.selected.tool);
  const t = selectedTool();
  $('tool-editor').hidden = !t;
  if (t) fillFields($('tool-editor'), t);
  form.elements.cornerRadius.disabled = state.running || t?.shape !== 'bullNose';
  const opTool = form.elements.opTool;
  opTool.replaceChildren(...state.tools.map((u) => new Option(`T${u.number} · ${u.diameter} mm ${u.shape}${u.name ? ` · ${u.name}` : ''}`, String(u.number))));
  const op = selectedOp();
  if (op) opTool.value = String(op.tool);
}

function fillOps() {
  const j = job(), list = $('op-list');
  state.selected[state.kind] = Math.max(0, Math.min(state.selected[state.kind], j.operations.length - 1));
  list.replaceChildren(...j.operations.map((op, i) => {
    const li = document.createElement('li');
    li.className = i === state.selected[state.kind] ? 'selected' : '';
    li.dataset.index = String(i);
    const color = OP_COLORS[i % OP_COLORS.length].slice(0, 3).map((c) => Math.round(c * 255));
    li.innerHTML = `<input type="checkbox" class="op-enabled" title="run this operation" aria-label="enabled"><span class="swatch" style="background: rgb(${color.join(',')})"></span><span class="op-name"></span><span class="op-buttons"><button type="button" class="op-up" title="earlier">▲</button><button type="button" class="op-down" title="later">▼</button><button type="button" class="op-remove" title="remove">✕</button></span>`;
    li.querySelector('.op-enabled').checked = op.enabled !== false;
    li.querySelector('.op-name').textContent = `${op.name} · ${toolsOf(op).map((t) => `T${t}`).join(' ') || 'no tool'}`;
    return li;
  }));
  const op = selectedOp();
  $('op-editor').hidden = !op;
  if (!op) return;
  for (const el of $('op-editor').querySelectorAll('[data-kinds]')) el.hidden = !el.dataset.kinds.split(' ').includes(op.kind);
  for (const box of [$('fs-raster'), $('fs-2d'), $('fs-rough'), $('fs-waterline'), $('fs-octree')]) if (!box.hidden) fillFields(box, op);
  form.elements.opName.value = op.name;
  $('op-tool-label').hidden = op.kind === 'roughOctree';
  if (op.kind !== 'roughOctree') form.elements.opTool.value = String(op.tool);
  showPicked();
}

// The drawing's loop `l` as line segments (xyz pairs at Z0) from the view's data.
function loopLines(d, l) {
  const data = l.hole ? d.holes : d.outer;
  return data.slice(3 * l.lines[0], 3 * l.lines[1]);
}

// The loops the selected 2D operation picked, highlighted in the view.
function showPicked() {
  if (!viewer || state.kind !== 'drawing' || !state.drawing) return;
  const op = selectedOp(), d = state.drawing;
  const picked = op && is2d(op) ? (op.loops ?? []) : [];
  viewer.setPicked(picked.filter((k) => d.loops[k]).flatMap((k) => loopLines(d, d.loops[k])));
}

// The loop drawn nearest the canvas point (x, y) (CSS pixels), within `reach` pixels of it, or
// null.
function loopAt(x, y, reach = 8) {
  const d = state.drawing;
  let best = null, nearest = reach;
  for (const l of d.loops) {
    const data = loopLines(d, l);
    for (let k = 0; k + 6 <= data.length; k += 6) {
      const a = viewer.project([data[k], data[k + 1], 0]), b = viewer.project([data[k + 3], data[k + 4], 0]);
      if (!a || !b) continue;
      const [ex, ey] = [b[0] - a[0], b[1] - a[1]], len2 = ex * ex + ey * ey;
      const t = len2 > 0 ? Math.max(0, Math.min(1, ((x - a[0]) * ex + (y - a[1]) * ey) / len2)) : 0;
      const dist = Math.hypot(a[0] + t * ex - x, a[1] + t * ey - y);
      if (dist < nearest) { nearest = dist; best = l.index; }
    }
  }
  return best;
}

// Clicking a loop of the drawing adds it to the selected 2D operation's loops, or takes it
// out again: a drawing whose loops all lie on one layer can still be cut in parts.
function pickLoop(x, y) {
  if (state.kind !== 'drawing' || !state.drawing || state.running) return;
  const op = selectedOp();
  if (!op || !is2d(op)) return;
  const index = loopAt(x, y);
  if (index === null) return;
  const loops = op.loops ?? [];
  op.loops = loops.includes(index) ? loops.filter((k) => k !== index) : [...loops, index].sort((a, b) => a - b);
  store();
  fillOps();
  const l = state.drawing.loops[index];
  showInfo(`${op.name}: loop ${index} (${l.layer}, ${l.hole ? 'hole' : 'outline'}) ${op.loops.includes(index) ? 'picked' : 'no longer picked'}; loops ${op.loops.length ? op.loops.join(', ') : 'all on the layers'}`);
}
if (viewer) viewer.onPick = pickLoop;
window.swarfView = viewer; // for the end-to-end test

function fillAll() {
  fillJob();
  fillTools();
  fillOps();
}

// A field changed: the object it belongs to follows (a field that does not read is named and
// the object keeps its value).
function onField(el) {
  if (!el.dataset.key) return;
  let value;
  try { value = valueOf(el); } catch (e) { showError(e.message); return; }
  if (el.closest('#tool-editor')) {
    const t = selectedTool();
    if (!t) return;
    if (el.dataset.key === 'number') {
      if (state.tools.some((u) => u !== t && u.number === value)) { showError(`T${value} is in the library already`); return; }
      // Operations using the tool follow its new number.
      for (const j of Object.values(state.jobs)) {
        for (const op of j.operations) {
          if (op.tool === t.number) op.tool = value;
          if (op.tools) op.tools = op.tools.map((n) => (n === t.number ? value : n));
        }
      }
    }
    setKey(t, el.dataset.key, value);
    fillTools();
    fillOps();
  } else if (el.closest('#op-editor')) {
    const op = selectedOp();
    if (!op) return;
    setKey(op, el.dataset.key, value);
    if (el.dataset.key === 'name' || el.dataset.key === 'tool') fillOps();
    if (el.dataset.key === 'loops') showPicked();
  } else if (el.name === 'zeroHeight' || el.name === 'zeroCorner') {
    const height = form.elements.zeroHeight.value;
    job().stock.zero = height ? { height, corner: form.elements.zeroCorner.value } : null;
  } else {
    setKey(job(), el.dataset.key, value);
    // Choosing a controller goes back to its built-in post.
    if (el.dataset.key === 'post.dialect' && job().post.custom) { job().post.custom = null; fillJob(); }
  }
  store();
  showInfo('');
  if (el.dataset.key.startsWith('post.')) repost();
}

// ---- the tool library --------------------------------------------------------------------
function addTool(copy) {
  const base = copy && selectedTool() ? selectedTool() : state.defaults.tool;
  const t = structuredClone(base);
  t.number = Math.max(0, ...state.tools.map((u) => u.number)) + 1;
  if (!copy) t.name = '';
  state.tools.push(t);
  state.selected.tool = state.tools.length - 1;
  store();
  fillTools();
}

function deleteTool() {
  const t = selectedTool();
  if (!t) return;
  const users = Object.values(state.jobs).flatMap((j) => j.operations).filter((op) => (op.kind === 'roughOctree' ? op.tools ?? [] : [op.tool]).includes(t.number));
  if (users.length) { showError(`T${t.number} is used by ${users.map((o) => `'${o.name}'`).join(', ')}: give them another tool first`); return; }
  state.tools.splice(state.selected.tool, 1);
  store();
  fillTools();
}

function exportTools() {
  downloadText('swarf-tools.json', JSON.stringify({ tools: state.tools }, null, 2), 'application/json');
}

// Tools are read by the core, as a job's are: a misspelt field is named. Imported tools replace
// those of the same number and join the rest.
async function importTools(file) {
  try {
    const parsed = JSON.parse(await file.text());
    const tools = Array.isArray(parsed) ? parsed : parsed.tools;
    if (!Array.isArray(tools)) throw new Error('expected a list of tools, or { "tools": [...] }');
    const { job: read } = await call({ type: 'readJob', text: JSON.stringify({ tools }) });
    for (const t of read.tools) {
      const k = state.tools.findIndex((u) => u.number === t.number);
      if (k >= 0) state.tools[k] = t; else state.tools.push(t);
    }
    store();
    fillTools();
    fillOps();
    showInfo(`Imported ${read.tools.length} tool(s) from ${file.name}.`);
  } catch (e) {
    showError(`${file.name}: ${e.message}`);
  }
}

// ---- the operation list ------------------------------------------------------------------
function addOperation(kind) {
  const op = structuredClone(state.defaults.operations.find((o) => o.kind === kind));
  const j = job();
  // Octree roughing chooses its own tools (from the whole library unless told otherwise).
  if (kind !== 'roughOctree') op.tool = selectedTool()?.number ?? state.tools[0]?.number ?? 1;
  const same = j.operations.filter((o) => o.kind === kind).length;
  if (same) op.name = `${op.name} ${same + 1}`;
  j.operations.push(op);
  state.selected[state.kind] = j.operations.length - 1;
  store();
  fillOps();
}

function onOpList(e) {
  const li = e.target.closest('li');
  if (!li) return;
  const ops = job().operations, i = Number(li.dataset.index);
  if (e.target.classList.contains('op-enabled')) { ops[i].enabled = e.target.checked; store(); return; }
  if (e.target.classList.contains('op-up') && i > 0) { [ops[i - 1], ops[i]] = [ops[i], ops[i - 1]]; state.selected[state.kind] = i - 1; }
  else if (e.target.classList.contains('op-down') && i < ops.length - 1) { [ops[i + 1], ops[i]] = [ops[i], ops[i + 1]]; state.selected[state.kind] = i + 1; }
  else if (e.target.classList.contains('op-remove')) { ops.splice(i, 1); state.selected[state.kind] = Math.max(0, i - 1); }
  else state.selected[state.kind] = i;
  store();
  fillOps();
}

function partSetup() { return job().part ?? state.jobs.part.part; }

function drawingSetup() { return state.jobs.drawing.drawing; }

function setKind(kind) {
  state.kind = kind;
  $('fs-drawing').hidden = kind !== 'drawing';
  $('fs-part').hidden = kind === 'drawing';
  document.body.dataset.kind = kind;
  fillAll();
}

// The tools an operation uses: its own, or for octree roughing those it may choose from (its
// list, else every flat and bull-nose end in the library).
function toolsOf(op) {
  if (op.kind !== 'roughOctree') return [op.tool];
  return op.tools?.length ? op.tools : state.tools.filter((t) => t.shape === 'flat' || t.shape === 'bullNose').map((t) => t.number);
}

// The job to run or save: this kind's job with the library's tools its operations use.
function buildJob() {
  const j = structuredClone(job());
  j.name = state.name.replace(/\.[^.]*$/, '');
  const used = new Set(j.operations.flatMap(toolsOf));
  j.tools = state.tools.filter((t) => used.has(t.number));
  const wrong = j.operations.filter((op) => (state.kind === 'drawing') !== is2d(op));
  if (wrong.length && wrong.length === j.operations.length) throw new Error(state.kind === 'drawing' ? 'add a pocket or profile operation for a drawing' : 'add a raster operation for a part');
  return j;
}

function downloadText(name, text, type) {
  const a = document.createElement('a');
  a.href = URL.createObjectURL(new Blob([text], { type }));
  a.download = name;
  document.body.appendChild(a);
  a.click();
  setTimeout(() => { URL.revokeObjectURL(a.href); a.remove(); }, 1000);
}

// ---- part --------------------------------------------------------------------------------
// Reads and shows a part; only when that works does it become the current part, so a bad file
// loses nothing (the previous part and every setting stay).
async function showPart(bytes = state.bytes, name = state.name, label = $('part-name').textContent) {
  if (!bytes) return;
  try {
    const { part, drawing } = await call({ type: 'load', bytes, name, setup: state.jobs.part.part, drawingSetup: drawingSetup() });
    Object.assign(state, { bytes, name, gcode: null });
    $('part-name').textContent = label;
    viewer?.clearPaths();
    showSimulation(null);
    $('download').disabled = true;
    $('generate').disabled = state.running;
    if (drawing) {
      showDrawing(drawing);
      return;
    }
    setKind('part');
    viewer?.setPart(part);
    $('download').disabled = true;
    $('generate').disabled = state.running;
    const b = part.bounds, size = [0, 1, 2].map((k) => (b[k + 3] - b[k]).toFixed(1));
    $('stats').textContent = `${part.triangles.toLocaleString()} triangles${part.dropped ? ` (${part.dropped} degenerate ignored)` : ''}\nsize ${size.join(' × ')} mm\nfrom (${b.slice(0, 3).map((v) => v.toFixed(1)).join(', ')}) to (${b.slice(3).map((v) => v.toFixed(1)).join(', ')})`;
    showInfo('');
  } catch (e) {
    showError(e.message);
  }
}

// A drawing's loops in the view and a list of them (which are outlines, which are holes), with
// its layers; open chains are reported where they are.
function showDrawing(d) {
  setKind('drawing');
  state.drawing = d;
  viewer?.setDrawing(d);
  showPicked();
  const outer = d.loops.filter((l) => !l.hole).length, holes = d.loops.length - outer;
  const b = d.bounds;
  $('stats').textContent = `${d.loops.length} closed loops: ${outer} outlines (green), ${holes} holes (orange)\nlayers: ${d.layers.join(', ')}\nunits: ${d.units}\nsize ${(b[3] - b[0]).toFixed(1)} × ${(b[4] - b[1]).toFixed(1)} mm`
    + (d.ignored.length ? `\nignored: ${d.ignored.map(([k, n]) => `${n} ${k}`).join(', ')}` : '');
  const list = d.loops.slice(0, 200).map((l) => `${l.index}: ${l.layer}, ${l.hole ? 'hole' : 'outline'}, ${l.entities} entities, (${l.min.map((v) => v.toFixed(1)).join(', ')})–(${l.max.map((v) => v.toFixed(1)).join(', ')})`);
  $('loops').textContent = list.join('\n') + (d.loops.length > 200 ? `\n… and ${d.loops.length - 200} more` : '');
  if (d.openChains.length) {
    const o = d.openChains.slice(0, 5).map((c) => `layer ${c.layer} from (${c.start.map((v) => v.toFixed(2)).join(', ')}) to (${c.end.map((v) => v.toFixed(2)).join(', ')})`);
    showError(`${d.openChains.length} open chain(s), drawn in red, cannot be cut until closed: ${o.join('; ')}${d.openChains.length > 5 ? ' …' : ''}. Choose layers without them.`);
  } else {
    showInfo('');
  }
}

async function takeFile(file) {
  if (/\.json$/i.test(file.name)) return loadJob(file);
  showPart(new Uint8Array(await file.arrayBuffer()), file.name, file.name);
}

// ---- posts as data ----------------------------------------------------------------------
// The post in use (the user's own, else the built-in one of the chosen controller) saved as
// JSON to edit; a loaded one is read by the core, which names a field it does not know.
function currentPost() {
  const p = job().post;
  return p.custom ?? state.posts.find((b) => b.dialect === p.dialect)?.post;
}

function savePost() {
  const post = currentPost();
  if (post) downloadText(`${post.name.replace(/[^\w.-]+/g, '_')}.post.json`, JSON.stringify(post, null, 2), 'application/json');
}

async function loadPost(file) {
  try {
    const { post } = await call({ type: 'readPost', text: await file.text() });
    job().post.custom = post;
    store();
    fillJob();
    showInfo(`Loaded the post "${post.name}" from ${file.name}; programs now end in .${post.extension}.`);
    await repost();
  } catch (e) {
    showError(`${file.name}: ${e.message}`);
  }
}

// The program of the last Generate written again for the post now chosen (no planning again);
// `data-posted` counts the programs so written.
async function repost() {
  if (!state.gcode || state.running) return;
  try {
    const r = await call({ type: 'repost', post: job().post });
    state.gcode = r.gcode;
    state.extension = r.extension;
    showInfo(`The program is written again for ${currentPost()?.name}: cycle time ${clock(r.cycle.seconds)}.`);
  } catch (e) {
    clearResult();
    showError(e.message);
  }
  document.body.dataset.posted = String(Number(document.body.dataset.posted ?? 0) + 1);
}

// ---- jobs as JSON ------------------------------------------------------------------------
// The same JSON drives the page, `swarf run job.json part.stl` and the tests.
function saveJob() {
  let j;
  try { j = buildJob(); } catch (e) { showError(e.message); return; }
  downloadText(`${j.name || 'job'}.json`, JSON.stringify(j, null, 2), 'application/json');
}

// A job file comes back whole: every operation, in order, and its tools (which join the
// library, replacing those of the same number). The core reads it as `swarf run` would: a
// misspelt or unknown field is named, and then nothing changes.
async function loadJob(file) {
  try {
    const text = await file.text();
    if (/"format"\s*:\s*"swarf project"/.test(text)) return await openProject(file, text);
    const { job: read } = await call({ type: 'readJob', text });
    await applyJob(read);
    showInfo(`Loaded the job from ${file.name}: ${read.operations.length} operation(s).`);
  } catch (e) {
    showError(`${file.name}: ${e.message}`);
  }
}

// A job read by the core takes the place of the page's: its tools join the library (replacing
// those of the same number); `part` ({bytes, name}) is shown instead of the sample.
async function applyJob(read, part = null) {
  if (!read.operations.length) throw new Error('the job has no operations');
  for (const op of read.operations) {
    const missing = (op.kind === 'roughOctree' ? op.tools : [op.tool]).find((n) => !read.tools.some((t) => t.number === n));
    if (missing != null) throw new Error(`operation '${op.name}' uses tool ${missing}, which the job file does not have`);
  }
  const kind = read.operations.every(is2d) ? 'drawing' : 'part';
  for (const t of read.tools) {
    const k = state.tools.findIndex((u) => u.number === t.number);
    if (k >= 0) state.tools[k] = t; else state.tools.push(t);
  }
  delete read.tools;
  state.jobs[kind] = read;
  state.selected[kind] = 0;
  store();
  if (part) {
    setKind(kind);
    fillAll();
    await showPart(part.bytes, part.name, part.name);
  } else if (kind !== state.kind) {
    const sample = kind === 'drawing' ? [state.sampleDrawing, 'sample.dxf', 'sample drawing'] : [state.sample, 'sample.stl', 'sample part'];
    await showPart(...sample);
  } else {
    fillAll();
    await showPart();
  }
}

// ---- projects ----------------------------------------------------------------------------
// A project file holds the job and the part or drawing (embedded), for the page and for
// `swarf run project.swarf.json`.
async function saveProject() {
  let j;
  try { j = buildJob(); } catch (e) { showError(e.message); return; }
  const { text } = await call({ type: 'writeProject', job: j, name: state.name, bytes: state.bytes });
  downloadText(`${state.name.replace(/\.[^.]*$/, '')}.swarf.json`, text, 'application/json');
}

async function openProject(file, text) {
  try {
    const { project } = await call({ type: 'readProject', text: text ?? await file.text() });
    await applyJob(project.job, project.bytes ? { bytes: project.bytes, name: project.name } : null);
    showInfo(project.bytes
      ? `Opened the project ${file.name}: ${project.name}, ${project.job.operations.length} operation(s).`
      : `Opened the project ${file.name}; it names its part ${project.name} without holding it: open that file.`);
  } catch (e) {
    showError(`${file.name}: ${e.message}`);
  }
}

// ---- simulation: scrub, play, MRR plot ---------------------------------------------------
// The worker keeps the last result; the page asks for the stock after a number of moves and
// draws it. Program time runs at the programmed feeds, so playback follows the feed rate.
const sim = { data: null, time: 0, playing: false, busy: false, wanted: null, last: 0 };

function clock(seconds) {
  const s = Math.max(0, Math.round(seconds));
  const h = Math.floor(s / 3600), m = Math.floor((s % 3600) / 60), r = s % 60;
  return `${h ? `${h}:${String(m).padStart(2, '0')}` : m}:${String(r).padStart(2, '0')}`;
}

function movesBy(t) {
  const times = sim.data.times, n = times.length - 1;
  if (t >= times[n]) return n;
  let lo = 0, hi = n;
  while (lo < hi) { const mid = (lo + hi) >> 1; if (times[mid] < t) lo = mid + 1; else hi = mid; }
  return lo;
}

async function seek(count) {
  if (sim.busy) { sim.wanted = count; return; }
  if (count === sim.shown) return;
  sim.busy = true;
  try {
    const r = await call({ type: 'seek', count });
    viewer?.updateStock(r.tops);
    sim.shown = r.count;
    document.body.dataset.simMoves = String(r.count);
  } catch (e) {
    if (e.message !== 'cancelled by the user') showError(e.message);
  } finally {
    sim.busy = false;
  }
  if (sim.wanted !== null) { const next = sim.wanted; sim.wanted = null; seek(next); }
}

function setTime(t) {
  if (!sim.data) return;
  const total = sim.data.times[sim.data.times.length - 1];
  sim.time = Math.max(0, Math.min(total, t));
  $('scrub').value = sim.time;
  $('sim-time').textContent = `${clock(sim.time)} / ${clock(total)}`;
  drawMrr();
  seek(movesBy(sim.time));
}

function play() {
  if (!sim.data) return;
  const total = sim.data.times[sim.data.times.length - 1];
  if (!sim.playing && sim.time >= total) sim.time = 0;
  sim.playing = !sim.playing;
  $('play').textContent = sim.playing ? '❚❚' : '▶';
  sim.last = performance.now();
  const step = (now) => {
    if (!sim.playing) return;
    const dt = (now - sim.last) / 1000;
    sim.last = now;
    setTime(sim.time + dt * Number($('speed').value));
    if (sim.time >= total) { sim.playing = false; $('play').textContent = '▶'; return; }
    requestAnimationFrame(step);
  };
  requestAnimationFrame(step);
}

function drawMrr() {
  const c = $('mrr');
  if (!sim.data) return;
  const dpr = window.devicePixelRatio || 1, w = Math.max(1, Math.round(c.clientWidth * dpr)), h = Math.round(70 * dpr);
  if (c.width !== w || c.height !== h) { c.width = w; c.height = h; sim.buckets = null; }
  const { times, mrr } = sim.data, total = times[times.length - 1] || 1;
  if (!sim.buckets) {
    const b = new Float32Array(w);
    for (let k = 0; k < mrr.length; k++) {
      const x = Math.min(w - 1, Math.floor((times[k] / total) * w));
      if (mrr[k] > b[x]) b[x] = mrr[k];
    }
    sim.buckets = b;
    sim.peak = b.reduce((m, v) => Math.max(m, v), 0) || 1;
  }
  const g = c.getContext('2d');
  g.clearRect(0, 0, w, h);
  g.fillStyle = '#6b8fb8';
  for (let x = 0; x < w; x++) { const v = (sim.buckets[x] / sim.peak) * (h - 14 * dpr); g.fillRect(x, h - v, 1, v); }
  g.fillStyle = '#394550';
  g.font = `${11 * dpr}px system-ui`;
  g.fillText(`MRR, peak ${Math.round(sim.peak).toLocaleString()} mm³/min`, 4 * dpr, 11 * dpr);
  // Operations that hold a load (seed 004): the reference rate at a full step-down, dashed,
  // and the plain path's rate before the correction (its windows spread over the operation's
  // time), faint: the paper's Fig. 14.
  sim.marks.forEach((m, k) => {
    if (!m.load) return;
    const end = k + 1 < sim.marks.length ? sim.marks[k + 1].t : total;
    const [x0, x1] = [(m.t / total) * w, (end / total) * w];
    const y = (v) => h - (v / sim.peak) * (h - 14 * dpr);
    const plain = m.load.plain;
    if (plain.length) {
      g.strokeStyle = 'rgba(57, 69, 80, 0.35)';
      g.lineWidth = dpr;
      g.beginPath();
      plain.forEach((r, i) => { const x = x0 + ((x1 - x0) * i) / plain.length, v = y(Math.min(r * m.load.rate, sim.peak)); if (i) g.lineTo(x, v); else g.moveTo(x, v); });
      g.stroke();
    }
    g.strokeStyle = '#2b8a3e';
    g.lineWidth = dpr;
    g.setLineDash([4 * dpr, 3 * dpr]);
    g.beginPath();
    g.moveTo(x0, y(m.load.rate));
    g.lineTo(x1, y(m.load.rate));
    g.stroke();
    g.setLineDash([]);
    g.fillStyle = '#2b8a3e';
    g.fillText(`reference ${Math.round(m.load.rate).toLocaleString()}`, x0 + 3 * dpr, Math.max(11 * dpr, y(m.load.rate) - 3 * dpr));
  });
  // The operations: a line in each one's colour where it starts, and its name.
  for (const m of sim.marks) {
    const mx = Math.round((m.t / total) * w), c = OP_COLORS[m.index % OP_COLORS.length].slice(0, 3).map((v) => Math.round(v * 255));
    g.fillStyle = `rgb(${c.join(',')})`;
    g.fillRect(mx, 0, dpr, h);
    if (sim.marks.length > 1) g.fillText(m.name, mx + 3 * dpr, h - 3 * dpr);
  }
  const x = (sim.time / total) * w;
  g.fillStyle = '#d9480f';
  g.fillRect(x - dpr, 0, 2 * dpr, h);
}

function showSimulation(data, summary = null) {
  sim.data = data;
  // Where each operation starts in program time, for the marks on the MRR plot.
  sim.marks = data && summary ? summary.operationStarts.map((m, k) => ({ t: data.times[m], name: summary.operations[k].name, index: summary.operations[k].index, load: summary.operations[k].load })) : [];
  sim.buckets = null;
  sim.playing = false;
  $('play').textContent = '▶';
  $('sim').hidden = !data;
  if (!data) return;
  const total = data.times[data.times.length - 1];
  $('scrub').max = total;
  const r = data.report;
  $('sim-report').textContent = r.text.trim();
  $('sim-report').className = r.gougeCount + r.rapidCollisionCount + r.bodyCollisionCount > 0 ? 'problem' : '';
  viewer?.setStock(data.grid, data.part, data.start);
  state.lastSimGrid = data.grid;
  // The stock as the run sent it: after the last move.
  sim.shown = data.times.length - 1;
  document.body.dataset.simMoves = String(sim.shown);
  viewer?.setMarks(data.findings);
  // Show the finished cut first; the scrubber goes back from there.
  setTime(total);
}

// ---- generate, cancel, download ----------------------------------------------------------
// Runs `steps` one task each (the view held, then drawn once).
async function inSteps(steps) {
  if (!viewer) { steps.forEach((step) => step()); return; }
  await viewer.batch(async () => {
    for (const step of steps) {
      step();
      await new Promise((resolve) => setTimeout(resolve, 0));
    }
  });
}


function setRunning(running) {
  state.running = running;
  $('generate').disabled = running || !state.bytes;
  $('cancel').disabled = !running;
  form.querySelectorAll('input, select, button').forEach((el) => { el.disabled = running; });
  if (!running) fillTools();
}

// A failed or cancelled Generate leaves nothing of the result it replaced: no path, no
// simulation, no statistics, no download.
function clearResult() {
  state.gcode = null;
  state.problem = null;
  viewer?.clearPaths();
  showSimulation(null);
  $('stats').textContent = '';
  $('download').disabled = true;
  $('progress').value = 0;
}

async function generate() {
  let job;
  try { job = buildJob(); } catch (e) { showError(e.message); return; }
  store();
  clearResult();
  document.body.dataset.generated = 'running';
  setRunning(true);
  showInfo('');
  $('progress').value = 0;
  const started = performance.now();
  try {
    const r = await call({ type: 'run', job, bytes: state.bytes, name: state.name }, [], (fraction, stage) => {
      $('progress').value = fraction;
      $('stage').textContent = stage;
    });
    state.gcode = r.gcode;
    state.extension = r.summary.extension;
    const s = r.summary;
    // The result reaches the view in steps, each a task of its own, so that none holds the
    // page's thread long on a die-sized result; the view draws once, after the last.
    const byTool = new Set(job.operations.map((op, i) => (op.kind === 'roughOctree' ? i : -1)).filter((i) => i >= 0));
    await inSteps([
      // The part framed again (the job may have placed it elsewhere).
      () => (r.drawing ? viewer?.setDrawing(r.drawing, false) : viewer?.setPart(r.part, true)),
      () => {
        viewer?.setPaths(r.feeds, r.rapids, s.stock, r.feedOps, r.feedTools, byTool);
        showPicked();
        if (r.octants.length) viewer?.setOctants(r.octants);
      },
      () => showSimulation(r.sim, s),
    ]);
    const changes = s.cycle.toolChanges ? ` (${clock(s.seconds)} of moves, ${s.cycle.toolChanges} tool change${s.cycle.toolChanges > 1 ? 's' : ''} at ${job.post.toolChangeSeconds} s)` : '';
    const stages = (o) => (o.stages ?? []).map((st) => `\n  T${st.tool} φ${st.diameter} (${st.role === 'profile' ? 'profile' : st.role === 'first' ? 'first tool' : 'octants'}): ${st.why}; ${Math.round(st.area).toLocaleString()} mm² cleared, ${Math.round(st.removed).toLocaleString()} mm³ removed, ${clock(st.seconds)} min`).join('');
    const perOp = s.operations.length > 1 || s.operations.some((o) => o.stages) ? `\n${s.operations.map((o) => `${o.name} (T${o.tools.join(', T')}): ${clock(o.seconds)} min${o.removed != null ? `, ${Math.round(o.removed).toLocaleString()} mm³, peak ${Math.round(o.mrrMax).toLocaleString()} mm³/min` : ''}${o.leftMax != null ? `, leaves ≤ ${o.leftMax.toFixed(2)} mm` : ''}${stages(o)}`).join('\n')}` : '';
    $('stats').textContent = `${s.moves.toLocaleString()} moves · ${(s.feedLength / 1000).toFixed(2)} m cutting · ${(s.rapidLength / 1000).toFixed(2)} m rapid\nestimated cycle time ${clock(s.cycle.seconds)} min${changes}${perOp}\ncomputed in ${((performance.now() - started) / 1000).toFixed(2)} s`;
    // A problem is shown as one, in red, with its places marked in the view; the program can
    // still be downloaded, behind a confirmation that names it.
    state.problem = s.problem ?? null;
    const warnings = s.warnings.map((w) => (w.operation ? `${w.operation}: ${w.message}` : w.message));
    if (state.problem) showError([`Not safe to run: ${state.problem}`, ...warnings].join('\n'));
    else showInfo(warnings.join('\n'));
    $('progress').value = 1;
    $('stage').textContent = state.problem ? 'done, with problems' : 'done';
    $('download').disabled = false;
    document.body.dataset.generated = state.problem ? 'problem' : 'ok';
  } catch (e) {
    clearResult();
    if (e.message !== 'cancelled by the user') showError(e.message);
    $('stage').textContent = '';
    document.body.dataset.generated = 'failed';
  } finally {
    setRunning(false);
  }
}

function cancel() {
  // The wasm runs synchronously in the worker, so cancelling ends the worker; a fresh one takes
  // its place and every setting stays.
  engine.cancel().catch((e) => showError(e.message));
  // The new worker has no result to scrub; the last drawing stays until the next run.
  sim.busy = false;
  sim.wanted = null;
  clearResult();
  showInfo('Cancelled. Your settings are kept.');
  document.body.dataset.generated = 'cancelled';
}

function download() {
  if (!state.gcode) return;
  if (state.problem && !window.confirm(`This program is not safe to run: ${state.problem}.\n\nDownload it anyway? It starts with a warning comment.`)) return;
  const ext = state.extension ?? 'nc';
  const a = document.createElement('a');
  a.href = URL.createObjectURL(new Blob([state.gcode], { type: 'text/plain' }));
  a.download = `${state.name.replace(/\.[^.]*$/, '')}.${ext}`;
  document.body.appendChild(a);
  a.click();
  setTimeout(() => { URL.revokeObjectURL(a.href); a.remove(); }, 1000);
}

// ---- wiring ------------------------------------------------------------------------------
$('generate').addEventListener('click', generate);
$('play').addEventListener('click', play);
$('scrub').addEventListener('input', (e) => setTime(Number(e.target.value)));
$('show-stock').addEventListener('change', (e) => { if (viewer) { viewer.show.stock = e.target.checked; viewer.draw(); } });
$('show-paths').addEventListener('change', (e) => { if (viewer) { viewer.show.paths = e.target.checked; viewer.draw(); } });
$('show-octants').addEventListener('change', (e) => { if (viewer) { viewer.show.octants = e.target.checked; viewer.draw(); } });
new ResizeObserver(() => { sim.buckets = null; drawMrr(); }).observe($('mrr'));
$('cancel').addEventListener('click', cancel);
$('download').addEventListener('click', download);
$('save-job').addEventListener('click', saveJob);
$('save-project').addEventListener('click', saveProject);
$('open-project').addEventListener('change', (e) => { if (e.target.files[0]) openProject(e.target.files[0]); e.target.value = ''; });
$('save-post').addEventListener('click', savePost);
$('load-post').addEventListener('change', (e) => { if (e.target.files[0]) loadPost(e.target.files[0]); e.target.value = ''; });
$('load-job').addEventListener('change', (e) => { if (e.target.files[0]) loadJob(e.target.files[0]); e.target.value = ''; });
$('file').addEventListener('change', (e) => { if (e.target.files[0]) takeFile(e.target.files[0]); });
$('use-sample').addEventListener('click', () => showPart(state.sample, 'sample.stl', 'sample part'));
$('use-sample-drawing').addEventListener('click', () => showPart(state.sampleDrawing, 'sample.dxf', 'sample drawing'));
form.addEventListener('input', (e) => { if (e.target.type !== 'checkbox' && e.target.tagName !== 'SELECT') onField(e.target); });
form.addEventListener('change', (e) => {
  if (e.target.closest('#op-list')) return;
  onField(e.target);
  if (['partUnits', 'partScale', 'upAxis', 'placement', 'drawingUnits', 'drawingOrigin', 'thickness'].includes(e.target.name)) showPart();
});
$('tool-list').addEventListener('change', (e) => { state.selected.tool = Number(e.target.value); fillTools(); });
$('tool-add').addEventListener('click', () => addTool(false));
$('tool-copy').addEventListener('click', () => addTool(true));
$('tool-delete').addEventListener('click', deleteTool);
$('tool-export').addEventListener('click', exportTools);
$('tool-import').addEventListener('change', (e) => { if (e.target.files[0]) importTools(e.target.files[0]); e.target.value = ''; });
$('op-list').addEventListener('click', onOpList);
$('op-add').addEventListener('click', () => addOperation($('op-kind').value));
const drop = $('drop');
for (const t of ['dragenter', 'dragover']) document.addEventListener(t, (e) => { e.preventDefault(); drop.classList.add('over'); });
for (const t of ['dragleave', 'drop']) document.addEventListener(t, (e) => { e.preventDefault(); drop.classList.remove('over'); });
document.addEventListener('drop', (e) => { const f = e.dataTransfer?.files?.[0]; if (f) takeFile(f); });

createEngine(window.SWARF_ENGINE_OPTIONS ?? {}).then((e) => {
  engine = e;
  const { defaults, posts, sample, sampleDrawing } = engine;
  state.defaults = defaults;
  state.posts = posts;
  restore();
  fillAll();
  state.sample = sample;
  state.sampleDrawing = sampleDrawing;
  return showPart(sample, 'sample.stl', 'sample part');
}).then(() => {
  document.body.dataset.ready = 'true';
}).catch((e) => showError(`swarf could not start: ${e.message}`));
