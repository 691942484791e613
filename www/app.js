// The page: settings, the worker that runs swarf's wasm, the view, and the download.
import { Viewer } from './viewer.js';

const $ = (id) => document.getElementById(id);
const form = $('settings');
const STORE = 'swarf.settings';

let viewer = null;
try { viewer = new Viewer($('view')); } catch (e) { showError(`3D view unavailable: ${e.message}`); }

// ---- worker ------------------------------------------------------------------------------
let worker, nextId = 1;
const pending = new Map();
function startWorker() {
  worker = new Worker(new URL('./worker.js', import.meta.url), { type: 'module' });
  worker.onmessage = (event) => {
    const m = event.data, entry = pending.get(m.id);
    if (!entry) return;
    if (m.type === 'progress') { entry.onProgress?.(m.fraction, m.stage); return; }
    pending.delete(m.id);
    m.ok ? entry.resolve(m) : entry.reject(new Error(m.error));
  };
  worker.onerror = (e) => {
    for (const entry of pending.values()) entry.reject(new Error(e.message || 'the worker failed'));
    pending.clear();
  };
}
function call(message, transfer = [], onProgress) {
  const id = nextId++;
  return new Promise((resolve, reject) => {
    pending.set(id, { resolve, reject, onProgress });
    worker.postMessage({ id, ...message }, transfer);
  });
}

// ---- state -------------------------------------------------------------------------------
const state = { bytes: null, name: 'sample.stl', sample: null, sampleDrawing: null, baseJob: null, gcode: null, running: false, kind: 'part', drawing: null };
window.swarf = state; // for the end-to-end test and the curious

function showError(text) { const m = $('message'); m.className = ''; m.textContent = text; }
function showInfo(text) { const m = $('message'); m.className = 'info'; m.textContent = text; }

function saveSettings() {
  const values = Object.fromEntries(new FormData(form).entries());
  try { localStorage.setItem(STORE, JSON.stringify(values)); } catch { /* private mode */ }
}
function restoreSettings() {
  let values = {};
  try { values = JSON.parse(localStorage.getItem(STORE) || '{}'); } catch { /* ignore */ }
  for (const [k, v] of Object.entries(values)) if (form.elements[k]) form.elements[k].value = v;
  updateCorner();
}
function updateCorner() { form.elements.cornerRadius.disabled = form.elements.shape.value !== 'bullNose'; }

function num(name) {
  const v = Number(form.elements[name].value);
  if (!Number.isFinite(v)) throw new Error(`${form.elements[name].closest('label').firstChild.textContent.trim()} is not a number`);
  return v;
}

function partSetup() {
  const f = form.elements;
  return { units: f.partUnits.value, upAxis: f.upAxis.value, placement: f.placement.value };
}

function toolFromForm() {
  const f = form.elements;
  return {
    number: 1, name: '', shape: f.shape.value, diameter: num('diameter'), cornerRadius: num('cornerRadius'),
    fluteLength: Math.max(20, num('diameter') * 3), spindleRpm: num('spindleRpm'), feedRate: num('feedRate'), plungeRate: num('plungeRate'),
  };
}

function drawingSetup() {
  const f = form.elements;
  return { units: f.drawingUnits.value, origin: f.drawingOrigin.value, thickness: num('thickness') };
}

// The 2.5D operation the form describes, as the job's JSON has it.
function operation2d() {
  const f = form.elements;
  const layers = f.layers.value.split(',').map((l) => l.trim()).filter(Boolean);
  const depth = f.depth2d.value === '' ? null : num('depth2d');
  const common = { tool: 1, layers, stepdown: num('stepdown'), leaveStock: num('leaveStock'), direction: f.direction.value };
  if (f.op2d.value === 'pocket2d') {
    return { kind: 'pocket2d', name: 'pocket', ...common, depth: depth ?? 3, stepover: num('stepoverFraction'), pattern: f.pocketPattern.value, entry: f.entry.value };
  }
  return { kind: 'profile2d', name: 'profile', ...common, depth, side: f.side.value, tabs: { count: Math.max(0, Math.round(num('tabs'))) } };
}

function setKind(kind) {
  state.kind = kind;
  $('fs-drawing').hidden = kind !== 'drawing';
  $('fs-raster').hidden = kind === 'drawing';
  document.body.dataset.kind = kind;
}

function buildJob() {
  const f = form.elements;
  const job = structuredClone(state.baseJob);
  if (state.kind === 'drawing') {
    job.name = state.name.replace(/\.[^.]*$/, '');
    job.drawing = drawingSetup();
    job.stock.marginXy = num('marginXy');
    job.tools = [toolFromForm()];
    job.operations = [operation2d()];
    job.post.dialect = f.dialect.value;
    job.post.units = f.gcodeUnits.value;
    return job;
  }
  job.name = state.name.replace(/\.[^.]*$/, '');
  job.part = partSetup();
  job.stock.marginXy = num('marginXy');
  job.tools = [toolFromForm()];
  job.operations = [{
    kind: 'finishRaster', name: 'raster finish', tool: 1, angle: num('angle'), stepover: num('stepover'), pattern: f.pattern.value,
    boundary: f.boundary.value, allowance: num('allowance'), grid: num('grid'), builder: f.builder.value,
  }];
  job.post.dialect = f.dialect.value;
  job.post.units = f.gcodeUnits.value;
  return job;
}

// ---- part --------------------------------------------------------------------------------
// Reads and shows a part; only when that works does it become the current part, so a bad file
// loses nothing (the previous part and every setting stay).
async function showPart(bytes = state.bytes, name = state.name, label = $('part-name').textContent) {
  if (!bytes) return;
  try {
    let setup;
    try { setup = drawingSetup(); } catch { setup = { units: 'file', origin: 'lowerLeft', thickness: 6 }; }
    const { part, drawing } = await call({ type: 'load', bytes, name, setup: partSetup(), drawingSetup: setup });
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

// ---- jobs as JSON ------------------------------------------------------------------------
// The same JSON drives the page, `swarf run job.json part.stl` and the tests.
function saveJob() {
  let job;
  try { job = buildJob(); } catch (e) { showError(e.message); return; }
  const a = document.createElement('a');
  a.href = URL.createObjectURL(new Blob([JSON.stringify(job, null, 2)], { type: 'application/json' }));
  a.download = `${job.name || 'job'}.json`;
  document.body.appendChild(a);
  a.click();
  setTimeout(() => { URL.revokeObjectURL(a.href); a.remove(); }, 1000);
}

async function loadJob(file) {
  try {
    // The core reads it as `swarf run` would: a misspelt or unknown field is named, not
    // dropped.
    const { job } = await call({ type: 'readJob', text: await file.text() });
    const op = (job.operations || []).find((o) => ['finishRaster', 'profile2d', 'pocket2d'].includes(o.kind));
    const tool = (job.tools || []).find((t) => !op || t.number === op.tool) || (job.tools || [])[0];
    if (!op || !tool) throw new Error('the job has no raster, profile or pocket operation with its tool');
    const f = form.elements;
    const set = (name, value) => { if (value !== undefined && value !== null && f[name]) f[name].value = value; };
    if (op.kind !== 'finishRaster') {
      set('op2d', op.kind); set('layers', (op.layers || []).join(', ')); set('depth2d', op.depth ?? '');
      set('stepdown', op.stepdown); set('leaveStock', op.leaveStock); set('direction', op.direction);
      set('side', op.side); set('tabs', op.tabs?.count); set('pocketPattern', op.pattern); set('entry', op.entry);
      if (op.kind === 'pocket2d') set('stepoverFraction', op.stepover);
      set('drawingUnits', job.drawing?.units); set('drawingOrigin', job.drawing?.origin); set('thickness', job.drawing?.thickness);
    }
    set('partUnits', job.part?.units); set('upAxis', job.part?.upAxis); set('placement', job.part?.placement);
    set('marginXy', job.stock?.marginXy);
    set('shape', tool.shape); set('diameter', tool.diameter); set('cornerRadius', tool.cornerRadius);
    set('spindleRpm', tool.spindleRpm); set('feedRate', tool.feedRate); set('plungeRate', tool.plungeRate);
    for (const k of ['stepover', 'angle', 'pattern', 'boundary', 'allowance', 'grid', 'builder']) set(k, op[k]);
    set('dialect', job.post?.dialect); set('gcodeUnits', job.post?.units);
    state.baseJob = { ...state.baseJob, ...job };
    saveSettings();
    updateCorner();
    await showPart();
    showInfo(`Loaded the job from ${file.name}.`);
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
  sim.busy = true;
  try {
    const r = await call({ type: 'seek', count });
    viewer?.updateStock(r.tops);
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
  const x = (sim.time / total) * w;
  g.fillStyle = '#d9480f';
  g.fillRect(x - dpr, 0, 2 * dpr, h);
}

function showSimulation(data) {
  sim.data = data;
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
  viewer?.setMarks(data.findings);
  // Show the finished cut first; the scrubber goes back from there.
  setTime(total);
}

// ---- generate, cancel, download ----------------------------------------------------------
function setRunning(running) {
  state.running = running;
  $('generate').disabled = running || !state.bytes;
  $('cancel').disabled = !running;
  form.querySelectorAll('input, select').forEach((el) => { el.disabled = running; });
  if (!running) updateCorner();
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
  saveSettings();
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
    if (r.drawing) viewer?.setDrawing(r.drawing, false);
    else viewer?.setPart(r.part, false);
    viewer?.setPaths(r.feeds, r.rapids, r.summary.stock);
    showSimulation(r.sim);
    const s = r.summary;
    const minutes = Math.floor(s.seconds / 60), seconds = Math.round(s.seconds % 60);
    $('stats').textContent = `${s.moves.toLocaleString()} moves · ${(s.feedLength / 1000).toFixed(2)} m cutting · ${(s.rapidLength / 1000).toFixed(2)} m rapid\nestimated cycle time ${minutes}:${String(seconds).padStart(2, '0')} min\ncomputed in ${((performance.now() - started) / 1000).toFixed(2)} s`;
    // A problem is shown as one, in red, with its places marked in the view; the program can
    // still be downloaded, behind a confirmation that names it.
    state.problem = s.problem ?? null;
    if (state.problem) showError([`Not safe to run: ${state.problem}`, ...s.warnings].join('\n'));
    else showInfo(s.warnings.join('\n'));
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
  worker.terminate();
  for (const entry of pending.values()) entry.reject(new Error('cancelled by the user'));
  pending.clear();
  startWorker();
  call({ type: 'hello' }).catch((e) => showError(e.message));
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
  const ext = form.elements.dialect.value === 'grbl' ? 'nc' : 'ngc';
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
new ResizeObserver(() => { sim.buckets = null; drawMrr(); }).observe($('mrr'));
$('cancel').addEventListener('click', cancel);
$('download').addEventListener('click', download);
$('save-job').addEventListener('click', saveJob);
$('load-job').addEventListener('change', (e) => { if (e.target.files[0]) loadJob(e.target.files[0]); e.target.value = ''; });
$('file').addEventListener('change', (e) => { if (e.target.files[0]) takeFile(e.target.files[0]); });
$('use-sample').addEventListener('click', () => showPart(state.sample, 'sample.stl', 'sample part'));
$('use-sample-drawing').addEventListener('click', () => showPart(state.sampleDrawing, 'sample.dxf', 'sample drawing'));
form.addEventListener('change', (e) => {
  saveSettings();
  updateCorner();
  if (['partUnits', 'upAxis', 'placement', 'drawingUnits', 'drawingOrigin'].includes(e.target.name)) showPart();
});
const drop = $('drop');
for (const t of ['dragenter', 'dragover']) document.addEventListener(t, (e) => { e.preventDefault(); drop.classList.add('over'); });
for (const t of ['dragleave', 'drop']) document.addEventListener(t, (e) => { e.preventDefault(); drop.classList.remove('over'); });
document.addEventListener('drop', (e) => { const f = e.dataTransfer?.files?.[0]; if (f) takeFile(f); });

restoreSettings();
startWorker();
call({ type: 'hello' }).then(({ job, sample, sampleDrawing }) => {
  state.baseJob = job;
  state.sample = sample;
  state.sampleDrawing = sampleDrawing;
  return showPart(sample, 'sample.stl', 'sample part');
}).then(() => {
  document.body.dataset.ready = 'true';
}).catch((e) => showError(`swarf could not start: ${e.message}`));
