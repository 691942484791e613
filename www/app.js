// The page: the engine (swarf.js, the wasm in workers), the view, and the page's modules wired
// together. Each module is a client of the DOM-free swarf.js: state.js (the jobs and library),
// forms.js (fields and messages), tools.js (the library), operations.js (the operation list),
// part.js (the part or drawing), simulation.js (the scrubber), gcode.js (the program's pane)
// and results.js (Generate and what it gives back).
import { Viewer } from './viewer.js';
import { createEngine } from './swarf.js';
import { $, state, hooks, job, selectedOp, selectedTool, store, restore, setKey, undo, canUndo, canRedo, startHistory } from './state.js';
import { valueOf, fillFields, message, fieldError, check, markProblems } from './forms.js';
import { GcodePane } from './gcode.js';
import { sim, setTime, step, play, drawMrr, toLine, showRestArea } from './simulation.js';
import { fillTools, fillToolChoices, showSpeeds, onHolderField, addTool, deleteTool, exportTools, importTools, renumber } from './tools.js';
import { fillOps, fillKinds, addOperation, onOpList, showPicked, showHoles, pickInView, findHoles, onHoleList, presetHoles, zeroOnHole, armPointPick } from './operations.js';
import { fillSetups, addSetup, removeSetup, onSetupTabs, onSetupField, showHeld, restage, playSetup } from './setups.js';
import { setKind, showPart, takeFile, fillPart, freshSetup, showSizes } from './part.js';
import { pageUnits, setPageUnits } from './units.js';
import { showSummary, generate, cancel, download, clearResult, onLegend, resultTab, fillPost, savePost, loadPost, repost, saveJob, loadJob, saveProject, openProject, setRunning, showSetupResult, showSheet } from './results.js';

const form = $('settings');
window.swarf = state; // for the end-to-end test and the curious

try { state.viewer = new Viewer($('view')); } catch (e) { message(`3D view unavailable: ${e.message}`, 'error'); }
window.swarfView = state.viewer; // for the end-to-end test
if (state.viewer) state.viewer.onPick = pickInView;
sim.pane = new GcodePane($('gcode'), toLine);

function fillStock() {
  const j = job();
  fillFields($('fs-stock'), j);
  $('fs-stock').querySelector('[name=zeroHeight]').value = j.stock.zero?.height ?? '';
  $('fs-stock').querySelector('[name=zeroCorner]').value = j.stock.zero?.at ? 'at' : j.stock.zero?.corner ?? 'center';
  $('fs-stock').querySelector('[name=zeroCorner] [value=at]').hidden = !j.stock.zero?.at;
  for (const el of document.querySelectorAll('.part-only')) el.hidden = state.kind !== 'part';
  // The stock's shape: a box, a bar or a mesh, with the fields of the one it is.
  const shape = j.stock.mesh ? 'mesh' : j.stock.bar ? 'bar' : 'box';
  form.elements.stockShape.value = state.blankChosen && shape === 'box' ? 'mesh' : shape;
  $('bar-fields').hidden = state.kind !== 'part' || shape !== 'bar';
  $('blank-fields').hidden = state.kind !== 'part' || form.elements.stockShape.value !== 'mesh';
  $('stock-mesh-name').textContent = j.stock.mesh ? `${j.stock.mesh.name}: the stock is this mesh, placed with the part (centred on its top where the part is centred); its box is the stock's.` : 'Choose the file: until then the stock is a box.';
  const meshes = j.fixtures?.meshes ?? [];
  $('fixture-mesh-names').textContent = meshes.length ? `Fixtures as meshes: ${meshes.map((m) => m.name || m.file.name).join(', ')}.` : '';
  $('fixture-meshes-clear').hidden = !meshes.length;
  // A vise's fields where the stock is held in one.
  const vise = !!j.fixtures?.vise;
  form.elements.vise.checked = vise;
  $('vise-fields').hidden = state.kind !== 'part' || !vise;
}

// Held in a vise or not: a vise as the core makes it by default (its jaws follow the stock).
async function onVise(box) {
  const j = job();
  const made = box.checked ? (await state.engine.readJob(JSON.stringify({ fixtures: { vise: {} } }))).fixtures : null;
  j.fixtures = box.checked ? { ...made, ...j.fixtures, vise: made.vise } : { ...j.fixtures, vise: null };
  store('fixtures.vise');
  clearResult();
  fillStock();
  changed();
}

// The stock's shape chosen: a bar as the core makes one by default, a mesh once its file is
// read (a box until then), or a box again.
async function onStockShape(shape) {
  const j = job();
  state.blankChosen = shape === 'mesh';
  // The casting's file let go at once, before the engine is asked for a bar's defaults.
  const hadMesh = !!j.stock.mesh;
  if (shape !== 'mesh') j.stock.mesh = null;
  if (shape === 'bar' && !j.stock.bar) j.stock.bar = (await state.engine.readJob(JSON.stringify({ stock: { bar: {} } }))).stock.bar;
  if (shape !== 'bar') j.stock.bar = null;
  store('stock.shape');
  clearResult();
  fillStock();
  changed();
  // The part is placed by a blank's top: placed again without it.
  if (hadMesh && !j.stock.mesh) await showPart();
}

// A casting's or blank's file read into the job (its bytes travel with the job, to the workers,
// into projects and saved jobs).
async function onStockMesh(file) {
  const j = job();
  j.stock.mesh = { name: file.name, data: await base64Of(file) };
  j.stock.bar = null;
  store('stock.mesh');
  clearResult();
  fillStock();
  // The part placed by the blank's top, as the job places it.
  await showPart();
}

// A file's bytes in base64, as the job carries a mesh.
async function base64Of(file) {
  const bytes = new Uint8Array(await file.arrayBuffer());
  let text = '';
  for (let i = 0; i < bytes.length; i += 0x8000) text += String.fromCharCode(...bytes.subarray(i, i + 0x8000));
  return btoa(text);
}

// Fixtures as meshes added to the job (or all of them taken out).
async function onFixtureMeshes(files) {
  const j = job();
  const made = await Promise.all(files.map(async (f) => ({ name: f.name, file: { name: f.name, data: await base64Of(f) } })));
  j.fixtures = { ...j.fixtures, meshes: files.length ? [...(j.fixtures?.meshes ?? []), ...made] : [] };
  store('fixtures.meshes');
  clearResult();
  fillStock();
  changed();
}

// A built-in machine chosen: its limits, which the speeds and feeds from the material keep to.
function onMachine(name) {
  const m = state.defaults.machines.find((x) => x.name === name);
  if (!m) return;
  job().machine = structuredClone(m);
  store('machine');
  fillPost();
  fillTools();
  changed();
}

// The stock's materials and the built-in machines, as the core lists them.
function fillChoices() {
  const material = form.elements.material;
  for (const m of state.defaults.materials) material.append(new Option(m.words, m.value));
  const machine = form.elements.machine;
  for (const m of state.defaults.machines) machine.append(new Option(m.name, m.name));
  machine.append(new Option('your own (as set below)', ''));
}

function fillAll() {
  fillPart();
  fillStock();
  fillPost();
  fillTools();
  fillOps();
  changed();
  if (!state.running) showHistory();
}

// Something of the job changed: the core checks it again (a little later, once typing pauses),
// and marks each setting that does not fit at its field.
let checking = null;
function changed() {
  clearTimeout(checking);
  checking = setTimeout(() => { check(); showHeld(); }, 120);
}

// The undo and redo buttons say whether there is a step to take.
function showHistory() {
  $('undo').disabled = !canUndo();
  $('redo').disabled = !canRedo();
}

Object.assign(hooks, {
  fillAll, fillKinds, changed, showPicked, clearResult, setKind, showPart, loadJob, fillTools, fillToolChoices, fillSetups, showHeld, restage, showSetupResult, playSetup, history: showHistory,
  error: (text) => message(text, 'error'),
});

// A field changed: the object it belongs to follows (a field that does not read is marked, and
// the object keeps its value).
function onField(el) {
  if (!el.dataset.key) return;
  // A refusal of the last Generate is stale once the user changes a setting: kept to read, no
  // longer said in red as the job's state.
  const m = $('message');
  if (m.dataset.from === 'run' && m.className === 'error') message(`Changed since Generate refused the job; Generate again to check. It said: ${m.textContent}`, 'note');
  let value;
  try {
    value = valueOf(el);
    delete el.dataset.unreadable;
    fieldError(el, '');
  } catch (e) {
    el.dataset.unreadable = 'true';
    fieldError(el, e.message);
    return;
  }
  if (el.closest('#tool-editor')) {
    const t = selectedTool();
    if (!t) return;
    if (el.dataset.key === 'number') {
      if (state.tools.some((u) => u !== t && u.number === value)) { fieldError(el, `T${value} is in the library already`); return; }
      renumber(t.number, value);
    }
    setKey(t, el.dataset.key, value);
    // A speed or feed typed is the tool's own from then on, whatever the material.
    if (['spindleRpm', 'feedRate', 'plungeRate'].includes(el.dataset.key)) t.speeds = 'asTyped';
    fillTools();
    fillOps();
  } else if (el.closest('#op-editor')) {
    const op = selectedOp();
    if (!op) return;
    setKey(op, el.dataset.key, value);
    if (el.dataset.key === 'name' || el.dataset.key === 'tool') fillOps();
    if (el.dataset.key === 'loops') showPicked();
    if (['holes', 'external', 'loops', 'edges'].includes(el.dataset.key)) showHoles();
  } else if (el.name === 'zeroHeight' || el.name === 'zeroCorner') {
    const height = form.elements.zeroHeight.value;
    // A zero on a hole's centre keeps its place until a corner is chosen.
    const corner = form.elements.zeroCorner.value, at = corner === 'at' ? job().stock.zero?.at : null;
    job().stock.zero = height ? { height, corner: at ? 'center' : corner, at } : null;
  } else if (el.closest('#fs-part') || el.closest('#fs-drawing')) {
    // How a part is read is kept with the jobs of its kind.
    setKey(state.jobs[el.closest('#fs-part') ? 'part' : 'drawing'], el.dataset.key, value);
  } else {
    setKey(job(), el.dataset.key, value);
    // Choosing a controller goes back to its built-in post.
    if (el.dataset.key === 'post.dialect' && job().post.custom) { job().post.custom = null; fillPost(); }
  }
  store(el.dataset.key);
  changed();
  if (el.dataset.key === 'drawing.thickness') fillOps();
  // The speeds and feeds follow the material and the machine.
  if (el.dataset.key === 'stock.material' || el.dataset.key.startsWith('machine.')) { showSpeeds(); if (el.dataset.key.startsWith('machine.')) fillPost(); }
  if (el.dataset.key.startsWith('post.')) repost();
}

function tab(name) {
  for (const b of document.querySelectorAll('#tabs [data-tab]')) b.setAttribute('aria-selected', String(b.dataset.tab === name));
  for (const t of document.querySelectorAll('#settings .tab')) t.hidden = t.dataset.tab !== name;
  // A check answered while this tab was hidden marked no field in it: mark them now.
  if (state.problems) markProblems(state.problems);
}

// ---- wiring ------------------------------------------------------------------------------
$('tabs').addEventListener('click', (e) => { const b = e.target.closest('[data-tab]'); if (b) tab(b.dataset.tab); });
$('result-tabs').addEventListener('click', (e) => {
  const b = e.target.closest('[data-result]');
  if (b) resultTab(b.dataset.result);
  else if (e.target.id === 'results-toggle') { $('results').classList.toggle('collapsed'); state.viewer?.draw(); }
});
$('view-tools').addEventListener('click', (e) => { const b = e.target.closest('[data-view]'); if (b) state.viewer?.view(b.dataset.view); });
$('legend').addEventListener('change', onLegend);
$('legend').addEventListener('click', (e) => { if (e.target.closest('button[data-rest-op]')) onLegend(e); });
$('generate').addEventListener('click', generate);
$('play').addEventListener('click', play);
$('step-back').addEventListener('click', () => step(-1));
$('step-on').addEventListener('click', () => step(1));
$('scrub').addEventListener('input', (e) => setTime(Number(e.target.value)));
for (const [box, key] of [['show-stock', 'stock'], ['show-depth', 'depth'], ['show-paths', 'paths'], ['show-octants', 'octants'], ['show-tool', 'tool'], ['show-rest', 'rest']]) {
  $(box).addEventListener('change', (e) => { if (state.viewer) { state.viewer.show[key] = e.target.checked; state.viewer.draw(); } if (key === 'rest') showRestArea(); });
}
new ResizeObserver(() => { sim.buckets = null; drawMrr(); }).observe($('mrr'));
$('cancel').addEventListener('click', cancel);
$('undo').addEventListener('click', () => undo(true));
$('redo').addEventListener('click', () => undo(false));
// Keyboard shortcuts: Ctrl+Z and Ctrl+Shift+Z (or Ctrl+Y) undo and redo the settings (in a text
// field the field's own undo comes first), Ctrl+Enter generates, Escape cancels a run, and
// outside the fields Space plays or pauses the simulation and the arrows step it.
document.addEventListener('keydown', (e) => {
  const t = e.target, typing = t instanceof HTMLElement && (t.tagName === 'TEXTAREA' || (t.tagName === 'INPUT' && !['checkbox', 'radio', 'button', 'file'].includes(t.type)) || t.isContentEditable);
  const mod = e.ctrlKey || e.metaKey, key = e.key.toLowerCase();
  if (mod && key === 'enter') { e.preventDefault(); if (!$('generate').disabled) generate(); return; }
  if (e.key === 'Escape' && state.running) { e.preventDefault(); cancel(); return; }
  if (typing || e.altKey) return;
  if (mod && (key === 'z' || key === 'y')) {
    e.preventDefault();
    if (!state.running) undo(!(key === 'y' || e.shiftKey));
    return;
  }
  if (mod || t.tagName === 'SELECT' || t.tagName === 'BUTTON') return;
  if (key === ' ' && !$('sim').hidden) { e.preventDefault(); play(); }
  else if (e.key === 'ArrowLeft' && !$('sim').hidden) { e.preventDefault(); step(-1); }
  else if (e.key === 'ArrowRight' && !$('sim').hidden) { e.preventDefault(); step(1); }
});
$('download').addEventListener('click', download);
$('sheet').addEventListener('click', showSheet);
$('save-job').addEventListener('click', saveJob);
$('save-project').addEventListener('click', saveProject);
$('open-project').addEventListener('change', (e) => { if (e.target.files[0]) openProject(e.target.files[0]); e.target.value = ''; });
$('save-post').addEventListener('click', savePost);
$('load-post').addEventListener('change', (e) => { if (e.target.files[0]) loadPost(e.target.files[0]); e.target.value = ''; });
$('load-job').addEventListener('change', (e) => { if (e.target.files[0]) loadJob(e.target.files[0]); e.target.value = ''; });
$('file').addEventListener('change', (e) => { if (e.target.files[0]) takeFile(e.target.files[0]); e.target.value = ''; });
$('use-sample').addEventListener('click', () => { freshSetup(); fillPart(); showPart(state.sample, 'sample.stl', 'sample part'); });
$('use-sample-drawing').addEventListener('click', () => { freshSetup(); fillPart(); showPart(state.sampleDrawing, 'sample.dxf', 'sample drawing'); });
form.addEventListener('input', (e) => { if (e.target.type !== 'checkbox' && e.target.tagName !== 'SELECT') onField(e.target); });
form.addEventListener('change', (e) => {
  if (e.target.closest('#op-list')) return;
  if (e.target.name === 'vise') { onVise(e.target); return; }
  if (e.target.name === 'stockShape') { onStockShape(e.target.value); return; }
  if (e.target.id === 'fixture-meshes') { if (e.target.files.length) onFixtureMeshes([...e.target.files]); e.target.value = ''; return; }
  if (e.target.id === 'stock-mesh') { if (e.target.files[0]) onStockMesh(e.target.files[0]); e.target.value = ''; return; }
  if (e.target.name === 'machine') { onMachine(e.target.value); return; }
  if (e.target.name === 'holder' || e.target.name === 'holderSections') { onHolderField(e.target); return; }
  onField(e.target);
  if (e.target.closest('#fs-part') || e.target.closest('#fs-drawing')) showPart();
});
$('tool-list').addEventListener('change', (e) => { state.selected.tool = Number(e.target.value); fillTools(); changed(); });
$('fixture-meshes-clear').addEventListener('click', () => onFixtureMeshes([]));
$('tool-add').addEventListener('click', () => addTool(false));
$('tool-copy').addEventListener('click', () => addTool(true));
$('tool-delete').addEventListener('click', deleteTool);
$('tool-export').addEventListener('click', exportTools);
$('tool-import').addEventListener('change', (e) => { if (e.target.files.length) importTools([...e.target.files]); e.target.value = ''; });
$('op-list').addEventListener('click', onOpList);
$('setup-tabs').addEventListener('click', onSetupTabs);
$('setup-add').addEventListener('click', addSetup);
$('setup-remove').addEventListener('click', removeSetup);
$('setup-editor').addEventListener('change', (e) => onSetupField(e.target));
$('op-add').addEventListener('click', () => addOperation($('op-kind').value));
$('op-fields').addEventListener('click', (e) => { if (e.target.id === 'op-pick-point') armPointPick(); });
$('find-holes').addEventListener('click', findHoles);
$('hole-list').addEventListener('click', onHoleList);
$('hole-preset').addEventListener('click', presetHoles);
$('hole-zero').addEventListener('click', zeroOnHole);
// The page's units: every field and figure says them; a program still in the page's old units
// follows (a user who works in inches means G20), one set apart from them stays.
$('page-units').value = pageUnits();
$('page-units').addEventListener('change', (e) => {
  const was = pageUnits();
  setPageUnits(e.target.value);
  let followed = false;
  for (const kind of ['part', 'drawing']) {
    const post = state.jobs[kind].post;
    if (post.units === was) { post.units = pageUnits(); followed = true; }
  }
  if (followed) { store('post.units'); repost(); }
  fillAll();
  showSizes();
  showHoles();
  showSummary();
  drawMrr();
  message(`The page shows ${pageUnits() === 'inch' ? 'inches' : 'mm'}${followed ? `, and the program is written in them (${pageUnits() === 'inch' ? 'G20' : 'G21'}; the controller's tab sets it apart)` : ''}; the job and its files keep mm.`, 'note');
});

const drop = $('drop');
for (const t of ['dragenter', 'dragover']) document.addEventListener(t, (e) => { e.preventDefault(); drop.classList.add('over'); });
for (const t of ['dragleave', 'drop']) document.addEventListener(t, (e) => { e.preventDefault(); drop.classList.remove('over'); });
document.addEventListener('drop', (e) => { const f = e.dataTransfer?.files?.[0]; if (f) takeFile(f); });

createEngine(window.SWARF_ENGINE_OPTIONS ?? {}).then(async (engine) => {
  state.engine = engine;
  Object.assign(state, { defaults: engine.defaults, posts: engine.posts, sample: engine.sample, sampleDrawing: engine.sampleDrawing });
  fillKinds();
  fillChoices();
  const lost = await restore((j) => engine.readJob(JSON.stringify(j)));
  setKind('part');
  await showPart(engine.sample, 'sample.stl', 'sample part');
  if (lost.length) message(`The settings kept from before could not be read, and the defaults took their place: ${lost.join('; ')}`, 'warning');
  startHistory();
  setRunning(false);
}).then(() => {
  document.body.dataset.ready = 'true';
}).catch((e) => { console.error(e); message(`swarf could not start: ${e.message}`, 'error'); });
