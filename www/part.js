// The part or drawing on show: read by the core (a file that does not read loses nothing: the
// part before it and every setting stay), placed as its own settings say, and shown with its
// size, in the view with a grid, and with what the user should know of it. How a file is read
// (units, scale, up axis, turn) belongs to that file: a new file starts from its format's own.
import { $, state, hooks, job, store } from './state.js';
import { fillFields, message, answered } from './forms.js';
import * as units from './units.js';

const FORMAT_UNITS = { stl: 'mm, as STL says nothing', obj: 'mm, as OBJ says nothing', gltf: 'metres, as glTF is', glb: 'metres, as glTF is' };
const UP_NAMES = { z: '+Z', y: '+Y', x: '+X', '-z': '−Z', '-y': '−Y', '-x': '−X' };

export function setKind(kind) {
  state.kind = kind;
  $('fs-drawing').hidden = kind !== 'drawing';
  $('fs-part').hidden = kind === 'drawing';
  document.body.dataset.kind = kind;
  hooks.fillKinds?.();
  hooks.fillAll?.();
}

// The settings of how a part or drawing is read, back to the defaults (a new file's).
export function freshSetup() {
  state.jobs.part.part = structuredClone(state.defaults.job.part);
  const d = state.defaults.drawingJob.drawing;
  state.jobs.drawing.drawing = { ...state.jobs.drawing.drawing, units: d.units, origin: d.origin };
  store();
}


// The part's size, and how it was read: its units (the format's own, or the user's, marked),
// scale, up axis and turn.
function describePart(part) {
  const b = part.bounds, size = [0, 1, 2].map((k) => b[k + 3] - b[k]);
  const setup = state.jobs.part.part, ext = state.name.split('.').pop().toLowerCase();
  const readIn = setup.units === 'auto' ? `read in ${FORMAT_UNITS[ext] ?? 'mm'}` : '';
  const overrides = [];
  if (setup.units !== 'auto') overrides.push(`read in ${setup.units === 'm' ? 'metres' : setup.units}`);
  if (setup.scale !== 1) overrides.push(`scaled × ${setup.scale}`);
  if (setup.upAxis !== 'z') overrides.push(`${UP_NAMES[setup.upAxis]} up`);
  if (setup.rotation) overrides.push(`turned ${setup.rotation}°`);
  const el = $('part-size');
  el.innerHTML = '';
  el.append(`${size.map(units.size).join(' × ')} ${units.lengthUnit()} `);
  const note = document.createElement('span');
  note.className = 'units';
  note.textContent = `(X × Y × Z; ${part.triangles.toLocaleString()} triangles${part.dropped ? `, ${part.dropped} degenerate dropped` : ''}) ${readIn}`;
  el.append(note);
  if (overrides.length) {
    const o = document.createElement('span');
    o.className = 'override';
    o.textContent = overrides.join(', ');
    el.append(' ', o);
  }
  return size;
}

// What the user should know of the part or drawing as read (holes in its surface, a size that
// says another unit), in its own panel.
function partNotes(warnings, panel = 'part-notes') {
  $(panel).replaceChildren(...warnings.map((w) => {
    const div = document.createElement('div');
    div.className = w.level === 'note' ? 'note' : 'warning';
    div.textContent = units.words(w.message);
    return div;
  }));
}

// The view's grid and the line under it, in the page's units.
function showScale(size) {
  const spacing = state.viewer?.setGrid(undefined, units.unitLength()) ?? units.unitLength();
  $('scale').textContent = `grid ${units.exact(spacing)} ${units.lengthUnit()} · ${state.kind === 'drawing' ? 'drawing' : 'part'} ${size.map(units.size).join(' × ')} ${units.lengthUnit()}`;
}

// The sizes shown of the part or drawing on show, said again in the page's units.
export function showSizes() {
  if (state.kind === 'drawing' && state.drawing) describeDrawing(state.drawing);
  else if (state.part) showScale(describePart(state.part));
}

// Reads and shows a part or drawing; only when that works does it become the current one, so a
// bad file loses nothing (the previous part and every setting stay).
export async function showPart(bytes = state.bytes, name = state.name, label = state.label) {
  if (!bytes) return false;
  try {
    const { part, drawing } = await state.engine.call({ type: 'load', bytes, name, setup: state.jobs.part.part, stockMesh: state.jobs.part.stock.mesh ?? null, drawingSetup: state.jobs.drawing.drawing });
    Object.assign(state, { bytes, name, label });
    $('part-name').textContent = label;
    hooks.clearResult?.();
    if (drawing) {
      showDrawing(drawing);
    } else {
      state.part = part;
      setKind('part');
      // The last part's stock and zero go with it; this one's are staged next.
      state.viewer?.setStage(null);
      state.viewer?.setPart(part);
      // A job with setups shows the part as the setup on show holds it.
      hooks.showHeld?.();
      showScale(describePart(part));
      partNotes(part.warnings);
      const amber = part.warnings.filter((w) => w.level !== 'note');
      message(amber.length ? `${name}: ${amber.map((w) => w.message).join('\n')}` : '', amber.length ? 'warning' : 'note');
    }
    $('generate').disabled = state.running;
    hooks.changed?.();
    // Counted on the page's body: a test (or a portal) waits on it for the part as placed.
    document.body.dataset.parts = String(Number(document.body.dataset.parts ?? 0) + 1);
    return true;
  } catch (e) {
    message(e.message, 'error');
    return false;
  }
}

// A drawing's loops in the view and a list of them (which are outlines, which are holes), with
// its layers; open chains are reported where they are.
function showDrawing(d) {
  state.drawing = d;
  setKind('drawing');
  state.viewer?.setStage(null);
  state.viewer?.setDrawing(d);
  hooks.showPicked?.();
  describeDrawing(d);
  if (d.openChains.length) {
    const o = d.openChains.slice(0, 5).map((c) => `layer ${c.layer} from (${c.start.map(units.place).join(', ')}) to (${c.end.map(units.place).join(', ')})`);
    message(`${d.openChains.length} open chain(s), drawn in red, cannot be cut out until closed (they can be engraved): ${o.join('; ')}${d.openChains.length > 5 ? ' …' : ''}.`, 'warning');
  } else if (d.ignored.length) {
    // What the file holds that draws nothing (a circle of radius 0, text) is said in amber.
    message(`The drawing left out: ${d.ignored.map(([k, n]) => `${n} ${k}`).join('; ')}.`, 'warning');
  } else {
    message('');
  }
}

// The drawing's size, loops and layers, in the page's units.
function describeDrawing(d) {
  const outer = d.loops.filter((l) => !l.hole).length, holes = d.loops.length - outer;
  const b = d.bounds, size = [b[3] - b[0], b[4] - b[1], Number(state.jobs.drawing.drawing.thickness)];
  $('drawing-size').textContent = `${units.size(size[0])} × ${units.size(size[1])} ${units.lengthUnit()}, ${d.loops.length} closed loops: ${outer} outlines (green), ${holes} holes (orange); layers ${d.layers.join(', ')}; units of the file: ${d.units}`
    + (d.ignored.length ? `; left out: ${d.ignored.map(([k, n]) => `${n} ${k}`).join(', ')}` : '');
  partNotes(d.warnings ?? [], 'drawing-notes');
  showScale(size);
  const at = (p) => p.map((v) => units.size(v)).join(', ');
  const list = d.loops.slice(0, 200).map((l) => `${l.index}: ${l.layer}, ${l.hole ? 'hole' : 'outline'}, ${l.entities} entities, (${at(l.min)})–(${at(l.max)})`);
  $('loops').textContent = list.join('\n') + (d.loops.length > 200 ? `\n… and ${d.loops.length - 200} more` : '');
}

// A file dropped or chosen: a job or project (JSON), else a part or drawing, read from its own
// format's units with every reading setting back to its default.
export async function takeFile(file) {
  if (/\.json$/i.test(file.name)) return hooks.loadJob?.(file);
  try {
    await readFile(file);
  } finally {
    answered();
  }
}

// The largest file the page reads, as the core's `limits::MAX_FILE_BYTES` (512 MiB).
export const MAX_FILE_BYTES = 512 * 1024 * 1024;

async function readFile(file) {
  if (file.size > MAX_FILE_BYTES) {
    message(`${file.name}: it is ${(file.size / 1048576).toFixed(0)} MiB, larger than the ${MAX_FILE_BYTES / 1048576} MiB swarf reads; the part on show is kept.`, 'error');
    return;
  }
  const bytes = new Uint8Array(await file.arrayBuffer());
  const before = { part: structuredClone(state.jobs.part.part), drawing: structuredClone(state.jobs.drawing.drawing) };
  const drawingBefore = state.kind === 'drawing' ? state.name : state.drawingName;
  freshSetup();
  if (!(await showPart(bytes, file.name, file.name))) {
    // The file did not read: the part on show keeps its settings.
    state.jobs.part.part = before.part;
    state.jobs.drawing.drawing = before.drawing;
    store();
    hooks.fillAll?.();
  } else if (state.kind === 'drawing') {
    if (drawingBefore && drawingBefore !== file.name) newDrawing(state.drawing, drawingBefore);
    state.drawingName = file.name;
  }
}

// The drawing job's operations on a new drawing: kept, but what they picked (loops and holes, by
// their place in the last drawing) means nothing in this one: cleared, so each takes all of its
// kind; the hole operations turned off where this drawing has no hole to make. Said.
function newDrawing(d, was) {
  const cleared = [], off = [];
  const holes = d.loops.some((l) => l.hole);
  for (const op of state.jobs.drawing.operations ?? []) {
    if ((op.loops?.length ?? 0) + (op.holes?.length ?? 0) > 0) {
      if (op.loops) op.loops = [];
      if (op.holes) op.holes = [];
      cleared.push(op.name);
    }
    if (!holes && ['drill', 'bore', 'threadMill'].includes(op.kind) && op.enabled !== false) {
      op.enabled = false;
      off.push(op.name);
    }
  }
  if (!cleared.length && !off.length) return;
  store();
  hooks.fillAll?.();
  const said = [
    cleared.length ? `${cleared.join(', ')}: the loops and holes picked in ${was} are cleared (each takes all of its kind here; pick again in Operations)` : '',
    off.length ? `${off.join(', ')} turned off: this drawing has no holes` : '',
  ].filter(Boolean).join('; ');
  const m = $('message');
  message(`${m.textContent ? `${m.textContent}\n` : ''}A new drawing, the operations kept: ${said}.`, m.className === 'warning' ? 'warning' : 'note');
}

// The part's reading settings in its panel (after a change, the part is read again).
export function fillPart() {
  fillFields($('fs-part'), job());
  fillFields($('fs-drawing'), job());
}
