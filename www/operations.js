// The operations of the job on show, in order: listed with their colour, tools and whether
// they run; added, moved, removed; the picked one's form; and for drawings, the loops it cuts,
// picked by clicking them in the view.
import { $, state, hooks, job, ops, hasSetups, setupIndex, selectedOp, selectedTool, is2d, store, toolsOf, buildJob, formOf, picksHoles } from './state.js';
import { fillFields, message, sized, check } from './forms.js';
import { opColor, cssColor } from './viewer.js';
import * as units from './units.js';

export function fillOps() {
  const list = $('op-list'), operations = ops();
  hooks.fillSetups?.();
  state.selected[state.kind] = Math.max(0, Math.min(state.selected[state.kind], operations.length - 1));
  const items = sized(list, operations.length, () => {
    const li = document.createElement('li');
    li.innerHTML = '<input type="checkbox" class="op-enabled" title="run this operation" aria-label="run this operation"><span class="swatch"></span><span class="op-name"></span><span class="op-buttons"><button type="button" class="op-up" title="earlier" aria-label="earlier">▲</button><button type="button" class="op-down" title="later" aria-label="later">▼</button><button type="button" class="op-copy" title="duplicate" aria-label="duplicate">+1</button><button type="button" class="op-remove" title="remove (Ctrl+Z brings it back)" aria-label="remove">✕</button></span>';
    return li;
  });
  operations.forEach((op, i) => {
    const li = items[i];
    li.className = i === state.selected[state.kind] ? 'selected' : '';
    li.dataset.index = String(i);
    li.querySelector('.swatch').style.background = cssColor(opColor(i));
    li.querySelector('.op-enabled').checked = op.enabled !== false;
    const name = `${op.name} · ${toolsOf(op).map((t) => `T${t}`).join(' ') || 'no tool'}`;
    li.querySelector('.op-name').textContent = name;
    li.querySelector('.op-name').title = name;
  });
  const op = selectedOp();
  $('op-editor').hidden = !op;
  if (!op) return;
  buildForm(op.kind);
  fillFields($('op-fields'), op);
  // The heights are open where the operation has any of its own.
  const heights = $('op-fields').querySelector('details.heights');
  if (heights) {
    const froms = [op.topFrom, op.bottomFrom, op.clearanceFrom];
    // (A hole kind's R plane, `retract`, always set, is not one of its own heights.)
    const optional = new Set((formOf(op.kind)?.fields ?? []).filter((f) => f.empty).map((f) => f.key));
    heights.open = HEIGHT_KEYS.some((k) => op[k] != null && optional.has(k)) || froms.includes('partingLine') || froms.includes('point') || op.point != null || state.pickingPoint;
    const [px, py, pz] = (op.point ?? []).map((v) => units.place(v));
    $('op-point').textContent = state.pickingPoint ? 'click the part in the view' : op.point ? `picked: X${px} Y${py} Z${pz}` : 'none picked';
  }
  // A cut through the sheet goes past its bottom by the breakthrough (0.2 mm).
  const through = $('through-depth');
  if (through) through.textContent = `${units.place(Number(state.jobs.drawing.drawing.thickness) + 0.2)} ${units.lengthUnit()}`;
  showPicked();
  showHoles();
}

// ---- forms ------------------------------------------------------------------------------
// An operation's form is made from the core's description of its kind (`defaults.forms`: each
// field's key, words, unit, range and what empty means), never written here per kind: a new
// kind of operation is one Rust file. A field is named `op-` and its key (`op-stepdown`,
// `op-tabs-count`).
// The heights' fields ([`Heights`] in the core).
const HEIGHT_KEYS = ['top', 'topFrom', 'bottom', 'bottomFrom', 'clearance', 'clearanceFrom', 'retract'];
const UNIT_WORDS = { length: 'mm', feed: 'mm/min', degrees: '°', seconds: 's', none: '' };

// The kinds to add, grouped by what they work on, those for what is on show (a part or a
// drawing) first, the first of them chosen.
let kindsFor = null;
export function fillKinds() {
  if (!state.defaults || kindsFor === state.kind) return;
  kindsFor = state.kind;
  const select = $('op-kind'), words = { part: 'for parts', drawing: 'for drawings (2D)', either: 'for parts and drawings' };
  const order = state.kind === 'drawing' ? ['drawing', 'either', 'part'] : ['part', 'either', 'drawing'];
  const groups = Object.fromEntries(order.map((k) => [k, words[k]]));
  select.replaceChildren();
  for (const [applies, words] of Object.entries(groups)) {
    const group = document.createElement('optgroup');
    group.label = words;
    for (const f of state.defaults.forms.filter((g) => g.applies === applies)) group.append(new Option(f.title, f.kind));
    select.append(group);
  }
  select.selectedIndex = 0;
}

function fieldElement(f) {
  const label = document.createElement('label');
  const input = document.createElement(f.input === 'choice' || f.input === 'tool' ? 'select' : 'input');
  input.name = `op-${f.key.replace(/\./g, '-')}`;
  input.dataset.key = f.key;
  input.dataset.unit = f.unit === 'length' ? 'length' : f.unit === 'feed' ? 'feed' : '';
  if (f.help) label.title = f.help;
  if (f.applies === 'drawing') label.classList.add('drawing-only');
  if (f.input === 'check') {
    input.type = 'checkbox';
    label.className = 'check';
    label.append(input, ` ${f.label}`);
    return label;
  }
  const said = [UNIT_WORDS[f.unit], f.note, f.empty && `empty: ${f.empty}`].filter(Boolean).join('; ');
  const words = document.createElement('span');
  // The depth through a sheet is said as a figure, kept up to date by fillOps.
  const [before, after] = `${f.label}${said ? ` (${said})` : ''}`.split('{throughDepth}');
  words.append(before);
  if (after !== undefined) {
    const figure = document.createElement('span');
    figure.id = 'through-depth';
    words.append(figure, after);
  }
  label.append(words, ' ', input);
  if (f.input === 'choice') for (const c of f.choices) input.append(new Option(c.label, c.value));
  else if (f.input === 'tool') input.dataset.type = 'int';
  else if (f.input === 'number' || f.input === 'int') {
    input.type = 'number';
    input.step = f.input === 'int' ? '1' : 'any';
    if (f.min != null) input.min = String(f.min);
    if (f.max != null) input.max = String(f.max);
    if (f.empty) input.dataset.type = 'optional';
    else if (f.input === 'int') input.dataset.type = 'int';
  } else {
    input.type = 'text';
    if (f.input === 'words') input.dataset.type = 'list';
    if (f.input === 'ints') input.dataset.type = 'ints';
  }
  return label;
}

// The form of operations of `kind` in the editor (made anew only when the kind changes), with
// the holes found to pick from after its name and tool where the kind picks holes.
function buildForm(kind) {
  const box = $('op-fields'), form = formOf(kind);
  if (!form || box.dataset.kind === kind) return;
  const holes = $('fs-hole-list');
  $('op-editor').append(holes);
  // A kind with the heights (every roughing and 3D finishing; a 2D or hole kind's clearance,
  // retract or R plane) has them under one heading, as Fusion's Heights tab, closed until wanted.
  const grouped = form.fields.some((f) => f.key === 'clearanceFrom');
  const topAndBottom = form.fields.some((f) => f.key === 'topFrom');
  const own = form.fields.filter((f) => !grouped || !HEIGHT_KEYS.includes(f.key)).map(fieldElement);
  if (grouped) {
    const details = document.createElement('details');
    details.className = 'heights';
    const summary = document.createElement('summary');
    summary.textContent = topAndBottom ? 'Heights: top, bottom (the parting line), clearance, retract' : 'Heights: clearance, retract';
    // A height from a point picked on the part: the button arms the next click in the view.
    const pick = document.createElement('div');
    pick.className = 'pick-point';
    pick.innerHTML = '<button type="button" id="op-pick-point" title="then click the part in the view: a height \'from a point picked on the part\' is measured from its Z">Pick a point on the part</button> <span id="op-point"></span>';
    details.append(summary, ...form.fields.filter((f) => HEIGHT_KEYS.includes(f.key)).map(fieldElement), pick);
    own.push(details);
  }
  box.replaceChildren(...own);
  box.dataset.kind = kind;
  $('op-hint').textContent = form.hint ?? '';
  $('op-hint').hidden = !form.hint;
  holes.hidden = form.picks !== 'holes';
  if (form.picks === 'holes') box.insertBefore(holes, [...box.children].find((l) => !['name', 'tool'].includes(l.querySelector('[data-key]')?.dataset.key)) ?? null);
  units.relabel(box);
  hooks.fillToolChoices?.();
}

// The heights' "Pick a point on the part": the next click on the part in the view picks it.
export function armPointPick() {
  state.pickingPoint = true;
  fillOps();
  message('Click the part in the view to pick the point.', 'note');
}

// The shapes a kind of operation cuts with, the first the one a tool is added as where the
// library has none, and whether it takes the largest (roughing, facing) or the smallest.
const FITS = [
  [/^rough|^face$|^pocket2d$|^profile2d$|^bore$/, { shapes: ['flat', 'bullNose'], words: 'flat end mill', largest: true }],
  [/^finish/, { shapes: ['ball', 'bullNose'], words: 'ball end mill', largest: true }],
  [/^chamfer$|^engrave$|^vcarve$/, { shapes: ['vBit'], words: 'V-bit', largest: false }],
  [/^drill$/, { shapes: ['drill', 'spotDrill'], words: 'drill', largest: false }],
  [/^threadMill$/, { shapes: ['threadMill'], words: 'thread mill', largest: false }],
];

// The tool a new operation of `kind` takes: the selected tool where its shape suits the kind,
// else the library's that suits it (the largest flat end mill to rough, a ball to finish in
// 3D, a V-bit to chamfer or carve, a drill of the smallest hole found), else one added to the
// library, said: `{ tool, added }`.
function toolFor(kind) {
  const fit = FITS.find(([re]) => re.test(kind))?.[1];
  const chosen = selectedTool();
  if (!fit) return { tool: chosen ?? state.tools[0] };
  const holes = kind === 'drill' ? (found() ?? []).filter((h) => !h.mark && h.diameter > 0) : [];
  const hole = holes.length ? Math.min(...holes.map((h) => h.diameter)) : null;
  const suits = (t) => fit.shapes.includes(t.shape) && (hole === null || t.shape !== 'drill' || drillFits(t, hole));
  if (chosen && suits(chosen) && hole === null) return { tool: chosen };
  const all = state.tools.filter(suits).sort((a, b) => fit.shapes.indexOf(a.shape) - fit.shapes.indexOf(b.shape) || (fit.largest ? b.diameter - a.diameter : a.diameter - b.diameter));
  if (all.length) return { tool: all[0] };
  const t = structuredClone(state.defaults.tool);
  const flat = state.tools.filter((u) => u.shape === 'flat').sort((a, b) => b.diameter - a.diameter)[0];
  const diameter = kind === 'drill' ? hole ?? 5 : fit.shapes[0] === 'ball' && flat ? flat.diameter : 6;
  Object.assign(t, { number: Math.max(0, ...state.tools.map((u) => u.number)) + 1, shape: fit.shapes[0], diameter, name: `${Number(diameter.toFixed(3))} mm ${fit.words}`, cornerRadius: 0, tipDiameter: 0 });
  t.angle = fit.shapes[0] === 'drill' ? 118 : fit.shapes[0] === 'vBit' ? 90 : null;
  state.tools.push(t);
  return { tool: t, added: t };
}

export function addOperation(kind) {
  const op = structuredClone(state.defaults.operations.find((o) => o.kind === kind));
  const operations = ops();
  // Octree roughing chooses its own tools (from the whole library unless told otherwise).
  let added = null;
  if (kind !== 'roughOctree') {
    const fit = toolFor(kind);
    op.tool = fit.tool?.number ?? 1;
    added = fit.added;
  }
  const same = operations.filter((o) => o.kind === kind).length;
  if (same) op.name = `${op.name} ${same + 1}`;
  operations.push(op);
  state.selected[state.kind] = operations.length - 1;
  store();
  if (added) hooks.fillTools?.();
  fillOps();
  hooks.changed?.();
  if (added) message(`Added T${added.number}, a φ${mm(added.diameter)} ${unit()} ${FITS.find(([re]) => re.test(kind))[1].words}, to the tool library for ${op.name}: no tool there suits it. Its sizes are in the Tools tab.`, 'note');
}

export function onOpList(e) {
  const li = e.target.closest('li');
  if (!li) return;
  const list = ops(), i = Number(li.dataset.index);
  if (e.target.classList.contains('op-enabled')) { list[i].enabled = e.target.checked; store(); hooks.changed?.(); return; }
  if (e.target.classList.contains('op-up') && i > 0) { [list[i - 1], list[i]] = [list[i], list[i - 1]]; state.selected[state.kind] = i - 1; }
  else if (e.target.classList.contains('op-down') && i < list.length - 1) { [list[i + 1], list[i]] = [list[i], list[i + 1]]; state.selected[state.kind] = i + 1; }
  else if (e.target.classList.contains('op-copy')) {
    const copy = structuredClone(list[i]);
    copy.name = `${list[i].name} copy`;
    list.splice(i + 1, 0, copy);
    state.selected[state.kind] = i + 1;
  } else if (e.target.classList.contains('op-remove')) {
    const [gone] = list.splice(i, 1);
    state.selected[state.kind] = Math.max(0, i - 1);
    message(`Removed '${gone.name}': Undo (Ctrl+Z) brings it back.`, 'note');
  }
  else state.selected[state.kind] = i;
  store();
  fillOps();
  hooks.changed?.();
}

// The drawing's loop `l` as line segments (xyz pairs at Z0) from the view's data.
function loopLines(d, l) {
  const data = l.hole ? d.holes : d.outer;
  return data.slice(3 * l.lines[0], 3 * l.lines[1]);
}

// Whether an operation works on a drawing's loops: the 2D ones, a chamfer of loops, and a
// drawing's facing (a region).
const picksLoops = (op) => is2d(op) || (op.kind === 'chamfer' && op.edges === 'loops') || (op.kind === 'face' && state.kind === 'drawing');

// The loops the selected 2D operation picked, highlighted in the view.
export function showPicked() {
  if (!state.viewer || state.kind !== 'drawing' || !state.drawing) return;
  const op = selectedOp(), d = state.drawing;
  const picked = op && picksLoops(op) ? (op.loops ?? []) : [];
  state.viewer.setPicked(picked.filter((k) => d.loops[k]).flatMap((k) => loopLines(d, d.loops[k])));
}

// The loop drawn nearest the canvas point (x, y) (CSS pixels), within `reach` pixels of it, or
// null.
function loopAt(x, y, reach = 8) {
  const d = state.drawing, viewer = state.viewer;
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
export function pickLoop(x, y) {
  if (state.kind !== 'drawing' || !state.drawing || state.running) return;
  const op = selectedOp();
  if (!op || !picksLoops(op)) return;
  const index = loopAt(x, y);
  if (index === null) return;
  const loops = op.loops ?? [];
  op.loops = loops.includes(index) ? loops.filter((k) => k !== index) : [...loops, index].sort((a, b) => a - b);
  store();
  fillOps();
  const l = state.drawing.loops[index];
  message(`${op.name}: loop ${index} (${l.layer}, ${l.hole ? 'hole' : 'outline'}) ${op.loops.includes(index) ? 'picked' : 'no longer picked'}; loops ${op.loops.length ? op.loops.join(', ') : 'all on the layers'}`, 'note');
}

// ---- holes ------------------------------------------------------------------------------
// The holes the hole operations find (`swarf holes`), listed under their form and drawn in the
// view; a click on one adds it to the operation's holes or takes it out. An external thread
// mill takes the part's round bosses instead (`swarf holes --bosses`), and a chamfer of a
// part's edges its top edges (`swarf edges`, into its `loops`): found, listed and picked alike.
// `state.holes`, `state.bosses` and `state.edges` belong to the part or drawing they were
// found in.
const mm = units.exact, unit = units.lengthUnit;
const MODES = {
  holes: { one: 'hole', many: 'holes', field: 'holes', none: 'No holes found: a part\'s holes are its vertical round holes, a drawing\'s its circles.' },
  bosses: { one: 'boss', many: 'bosses', field: 'holes', none: 'No bosses found: a boss is a vertical round stud standing on the part, its wall facing out.' },
  edges: { one: 'edge', many: 'edges', field: 'loops', none: 'No top edges found: a top edge is the outline of a flat face of the part where it drops down a steep wall.' },
};
// What the operation picks from (a key of MODES), or null for an operation that picks none.
function modeOf(op) {
  if (!op || !picksHoles(op)) return null;
  if (op.kind === 'threadMill' && op.external === true) return 'bosses';
  if (op.kind === 'chamfer' && op.edges === 'partEdges') return 'edges';
  return 'holes';
}

// What the finds belong to: the part or drawing on show, and with setups the setup on show
// (a setup finds them in the part as it holds it).
const findsOf = () => (hasSetups() ? `${state.name} (setup ${setupIndex()})` : state.name);

// What the selected operation picks from, as found for the part or drawing on show.
function found(op = selectedOp()) {
  const mode = modeOf(op) ?? 'holes', f = state[mode];
  return f?.of === findsOf() ? f.items : [];
}

export async function findHoles() {
  const mode = modeOf(selectedOp()) ?? 'holes', m = MODES[mode];
  try {
    const j = buildJob();
    const items = await state.engine[mode](j, state.bytes, state.name, hasSetups(j) ? setupIndex(j) : undefined);
    state[mode] = { of: findsOf(), items };
    // The hole operations' settings are checked against the holes now known.
    if (mode === 'holes') check();
    const n = items.length;
    message(n ? `${n} ${n > 1 ? m.many : m.one} found: click one to pick it.` : m.none, n ? 'ok' : 'warning');
  } catch (e) {
    message(e.message, 'error');
  }
  showHoles();
}

// X0 Y0 on the centre of the one hole the selected operation picked: the work zero of the job,
// or with setups of the setup on show, its height kept (the core works out where that is from
// the stock's centre as the part is held). The holes are found again where they now lie.
export async function zeroOnHole() {
  const op = selectedOp(), picked = op?.holes ?? [];
  const h = found(op).find((x, k) => (x.loopIndex ?? k) === picked[0]);
  if (state.kind !== 'part' || picked.length !== 1 || !h) { message('Find the holes of a part and pick one (click it in the list or the view) to set X0 Y0 on its centre.', 'warning'); return; }
  try {
    const j = buildJob({ all: true }), k = hasSetups(j) ? setupIndex(j) : undefined;
    const zero = await state.engine.zeroOn(j, state.part.bounds, k, h.center);
    if (k === undefined) job().stock.zero = zero; else job().setups[k].zero = zero;
    store();
    hooks.fillAll?.();
    hooks.changed?.();
    await hooks.showHeld?.();
    await findHoles();
    message(`X0 Y0 on the centre of hole ${picked[0]} (φ${mm(h.diameter)})${k === undefined ? '' : ` in setup ${k + 1}`}: ${mm(zero.at[0])}, ${mm(zero.at[1])} ${unit()} from the stock's centre.`, 'ok');
  } catch (e) {
    message(e.message, 'error');
  }
}

export function showHoles() {
  const op = selectedOp(), picking = modeOf(op), mode = picking ?? 'holes', m = MODES[mode];
  const items = found(op);
  const picked = new Set(picking ? (op[m.field] ?? []) : []);
  $('find-holes').textContent = `Find the ${m.many}`;
  $('hole-preset').hidden = mode !== 'holes';
  $('hole-list').setAttribute('aria-label', `${m.many} found`);
  const rows = sized($('hole-list'), items.length, () => document.createElement('li'));
  items.forEach((h, k) => {
    const li = rows[k];
    const index = h.loopIndex ?? k;
    li.dataset.index = String(index);
    li.className = picked.has(index) ? 'picked' : '';
    if (mode === 'edges') li.textContent = `edge ${index}: the outline of a face at Z${mm(h.z)}, ${mm(h.length)} ${unit()} long: ${h.sharp ? 'sharp' : 'not sharp all round (a chamfer leaves it)'}`;
    else if (mode === 'bosses') li.textContent = `boss ${index}: φ${mm(h.diameter)} at (${mm(h.center[0])}, ${mm(h.center[1])}), ${mm(h.top - h.bottom)} ${unit()} tall`;
    else if (h.mark) li.textContent = `hole ${index}: a drill mark at (${mm(h.center[0])}, ${mm(h.center[1])}), layer ${h.layer}, drilled as wide as its drill`;
    else li.textContent = `hole ${index}: φ${mm(h.diameter)} at (${mm(h.center[0])}, ${mm(h.center[1])}), ${mm(h.top - h.bottom)} ${unit()} deep, ${h.through ? 'through' : `blind (${h.bottomShape} bottom)`}`;
  });
  state.viewer?.setHoles(picking && mode !== 'edges' ? items : [], picked);
  state.viewer?.setEdges(mode === 'edges' ? items : [], picked);
}

export function onHoleList(e) {
  const li = e.target.closest('li');
  const op = selectedOp();
  if (!li || !modeOf(op)) return;
  toggleHole(op, Number(li.dataset.index));
}

// The hole (or boss) drawn at the canvas point (x, y) (CSS pixels): the nearest whose circle
// holds the point, or whose centre lies within `reach` pixels of it; null if none.
function holeAt(x, y, reach = 10) {
  const holes = found(), viewer = state.viewer;
  let best = null, nearest = Infinity;
  holes.forEach((h, k) => {
    const c = viewer.project([h.center[0], h.center[1], h.top]), rim = viewer.project([h.center[0] + h.diameter / 2, h.center[1], h.top]);
    if (!c || !rim) return;
    const d = Math.hypot(c[0] - x, c[1] - y);
    if (d <= Math.max(reach, Math.hypot(rim[0] - c[0], rim[1] - c[1])) && d < nearest) { nearest = d; best = h.loopIndex ?? k; }
  });
  return best;
}

// The top edge drawn nearest the canvas point (x, y), if within `reach` pixels of its line.
function edgeAt(x, y, reach = 8) {
  const viewer = state.viewer;
  let best = null, nearest = reach;
  found().forEach((e, k) => {
    const pts = e.points.map(([px, py]) => viewer.project([px, py, e.z]));
    pts.forEach((a, i) => {
      const b = pts[(i + 1) % pts.length];
      if (!a || !b) return;
      const dx = b[0] - a[0], dy = b[1] - a[1], len2 = dx * dx + dy * dy;
      const t = len2 > 0 ? Math.max(0, Math.min(1, ((x - a[0]) * dx + (y - a[1]) * dy) / len2)) : 0;
      const d = Math.hypot(a[0] + t * dx - x, a[1] + t * dy - y);
      if (d <= nearest) { nearest = d; best = k; }
    });
  });
  return best;
}

// A click in the view: with a hole operation selected and the holes (bosses, edges) found,
// picks the one under it (or lets it go); else a drawing's loop, for the operations that take
// loops.
export function pickInView(x, y) {
  const op = selectedOp(), mode = modeOf(op);
  if (state.pickingPoint && op && !state.running) {
    const hit = state.viewer.pickSurface(x, y);
    if (!hit) { message('No part under the pointer: click on the part to pick the point its heights are measured from.', 'note'); return; }
    state.pickingPoint = false;
    op.point = hit.map((v) => Math.round(v * 1000) / 1000);
    store();
    fillOps();
    message(`${op.name}: the point picked at X${units.place(op.point[0])} Y${units.place(op.point[1])} Z${units.place(op.point[2])}; a height 'from a point picked on the part' is measured from its Z`, 'note');
    return;
  }
  if (mode && !state.running) {
    const k = mode === 'edges' ? edgeAt(x, y) : holeAt(x, y);
    if (k !== null) { toggleHole(op, k); return; }
  }
  pickLoop(x, y);
}

function toggleHole(op, k) {
  const m = MODES[modeOf(op)];
  const set = new Set(op[m.field] ?? []);
  if (set.has(k)) set.delete(k); else set.add(k);
  op[m.field] = [...set].sort((a, b) => a - b);
  store();
  fillOps();
  hooks.changed?.();
  message(`${op.name}: ${m.one} ${k} ${set.has(k) ? 'picked' : 'no longer picked'}; ${m.many} ${op[m.field].length ? op[m.field].join(', ') : 'all'}`, 'note');
}

// Spot, drill and chamfer the picked holes (all found, if none is picked), as a machinist
// plans them: the holes grouped by size, each group drilled with the library's drill that fits
// it (a new drill of that size where none does), bored on a helix with an end mill where the
// library has one narrow enough and no drill fits, recesses shallower than a spot left to the
// milling operations; the drilled holes spotted first, and all chamfered.
const JOBBER_MOST = 13; // the largest hole a drill is added for, rather than bored (mm)
const DRILL_UNDER = 0.1; // a drill this much under a hole's size still fits it (mm)
const DRILL_OVER = 0.02; // … and this much over (0.01 on the radius, inside the gouge tolerance)
// Whether drill `t` makes a hole of diameter `size`.
const drillFits = (t, size) => t.diameter <= size + DRILL_OVER && t.diameter >= size - DRILL_UNDER;
export function presetHoles() {
  const op = selectedOp();
  const holes = found(op);
  // Nothing picked: every hole but the drill marks (a DXF's POINTs are as often its
  // dimensions' anchors), as the operations take "all".
  const picked = op?.holes?.length ? op.holes : holes.map((h, k) => (h.mark ? null : h.loopIndex ?? k)).filter((k) => k !== null);
  if (!picked.length) { message('Find the holes first, and pick the ones to make.', 'warning'); return; }
  const indexOf = (h) => h.loopIndex ?? holes.indexOf(h);
  const chosen = holes.filter((h) => picked.includes(indexOf(h)));
  const spot = state.tools.find((t) => t.shape === 'spotDrill') ?? state.tools.find((t) => t.shape === 'vBit');
  const chamfer = state.tools.find((t) => t.shape === 'vBit') ?? spot;
  if (!spot) { message('Add a spot drill or a V-bit to the tool library first.', 'warning'); return; }
  // A spot's depth in a hole: a cone as wide as the hole (at most the tool).
  const spotDepth = (h) => Math.min(h.diameter, spot.diameter) / 2 / Math.tan(((spot.angle ?? 90) * Math.PI) / 360);
  const recesses = chosen.filter((h) => !h.mark && h.top - h.bottom < spotDepth(h));
  const made = chosen.filter((h) => !recesses.includes(h));
  // Groups by size (to a hundredth of a millimetre); drill marks go with the smallest drill.
  const groups = new Map();
  for (const h of made.filter((x) => !x.mark)) {
    const key = Math.round(h.diameter * 100) / 100;
    if (!groups.has(key)) groups.set(key, []);
    groups.get(key).push(h);
  }
  const drills = state.tools.filter((t) => t.shape === 'drill');
  const mills = state.tools.filter((t) => t.shape === 'flat' || t.shape === 'bullNose');
  const added = [], drilled = [], bored = [], plan = [];
  for (const [, list] of [...groups].sort((a, b) => a[0] - b[0])) {
    const size = Math.round(list[0].diameter * 1000) / 1000;
    const fit = drills.filter((t) => drillFits(t, size)).sort((a, b) => Math.abs(a.diameter - size) - Math.abs(b.diameter - size))[0];
    // A bore's tool: the widest end mill that leaves room for a helix (at most 80 % of the
    // hole). A hole a jobber drill makes (up to φ13) gets a drill of its size added instead.
    const mill = mills.filter((t) => t.diameter <= 0.8 * size).sort((a, b) => b.diameter - a.diameter)[0];
    if (fit) { plan.push({ kind: 'drill', tool: fit, size, list }); drilled.push(...list); }
    else if (mill && size > JOBBER_MOST) { plan.push({ kind: 'bore', tool: mill, size, list }); bored.push(...list); }
    else {
      const t = structuredClone(state.defaults.tool);
      Object.assign(t, { number: Math.max(0, ...state.tools.map((u) => u.number)) + 1, name: `drill φ${mm(size)}`, shape: 'drill', diameter: size, angle: 118, fluteLength: Math.max(t.fluteLength ?? 0, Math.ceil(Math.max(...list.map((h) => h.top - h.bottom)) + 3)) });
      state.tools.push(t);
      drills.push(t);
      added.push(t);
      plan.push({ kind: 'drill', tool: t, size, list });
      drilled.push(...list);
    }
  }
  const marks = made.filter((h) => h.mark);
  if (marks.length) {
    const smallest = plan.find((p) => p.kind === 'drill');
    if (smallest) { smallest.list.push(...marks); drilled.push(...marks); }
    else if (drills[0]) { plan.push({ kind: 'drill', tool: drills[0], size: drills[0].diameter, list: marks }); drilled.push(...marks); }
  }
  const add = (kind, fields, list) => {
    const o = structuredClone(state.defaults.operations.find((d) => d.kind === kind));
    Object.assign(o, fields, { holes: list.map(indexOf).sort((a, b) => a - b) });
    ops().push(o);
  };
  if (drilled.length) add('drill', { name: 'spot', tool: spot.number, cycle: 'spot' }, drilled);
  for (const p of plan) {
    if (p.kind === 'drill') add('drill', { name: `drill φ${mm(p.tool.diameter)}`, tool: p.tool.number, cycle: 'peck' }, p.list);
    else add('bore', { name: `bore φ${mm(p.size)}`, tool: p.tool.number }, p.list);
  }
  const edged = made.filter((h) => !h.mark);
  if (chamfer && edged.length) add('chamfer', { tool: chamfer.number }, edged);
  state.selected[state.kind] = ops().length - 1;
  store();
  hooks.fillTools?.();
  fillOps();
  hooks.changed?.();
  const said = plan.map((p) => `${p.kind === 'drill' ? `drill T${p.tool.number} φ${mm(p.tool.diameter)}` : `bore with T${p.tool.number} φ${mm(p.tool.diameter)}`}: ${p.list.length} hole${p.list.length > 1 ? 's' : ''} φ${mm(p.size)}`);
  const notes = [
    added.length ? `added ${added.map((t) => `T${t.number} (φ${mm(t.diameter)} drill)`).join(', ')} to the library, as no drill there fits` : '',
    recesses.length ? `left ${recesses.length} recess${recesses.length > 1 ? 'es' : ''} shallower than a spot (${recesses.map((h) => `φ${mm(h.diameter)} ${mm(h.top - h.bottom)} ${unit()} deep`).join(', ')}) to the milling operations` : '',
  ].filter(Boolean);
  message(`Spot, ${said.join('; ')}${edged.length && chamfer ? '; chamfer' : ''}.${notes.length ? ` ${notes.join('; ')}.` : ''}`, 'ok');
}
