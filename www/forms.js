// The forms: a field shows a value of the job, a tool or an operation by its dotted key
// (`data-key`), reads it back as that object holds it, and is marked where the core's own
// checks (`checkJob`) find the setting wrong. Messages come in three styles: an error (red), a
// warning (amber) and a note.
import { $, state, job, ops, setupIndex, getKey, buildJob, formOf } from './state.js';
import { unitOf, fromPage, fieldText, words } from './units.js';

export function labelOf(el) {
  const label = el.closest('label');
  return (label?.firstChild?.textContent ?? el.name).trim();
}

// The value of a form field as its object holds it.
export function valueOf(el) {
  const type = el.dataset.type;
  // A choice that may be none (`data-none`): its empty option is null.
  if (el.dataset.none !== undefined && el.value === '') return null;
  if (el.type === 'checkbox') return el.checked;
  if (type === 'list') return el.value.split(',').map((v) => v.trim()).filter(Boolean);
  if (type === 'ints') {
    const v = el.value.split(',').map((w) => w.trim()).filter(Boolean).map(Number);
    if (v.some((x) => !Number.isInteger(x) || x < 0)) throw new Error(`${labelOf(el)}: give whole numbers, separated by commas`);
    return v;
  }
  // A length or a feed is typed in the page's units and kept in mm.
  const mm = unitOf(el) ? fromPage : (v) => v;
  if (type === 'numbers' || type === 'box') {
    // A list of numbers (empty: none), and a box as its min and max corners.
    if (el.value.trim() === '') return null;
    const v = el.value.split(',').map((w) => Number(w.trim()));
    if (v.length !== Number(el.dataset.count) || v.some((x) => !Number.isFinite(x))) throw new Error(`${labelOf(el)}: give ${el.dataset.count} numbers, separated by commas`);
    const kept = v.map(mm);
    return type === 'box' ? { min: kept.slice(0, 3), max: kept.slice(3) } : kept;
  }
  if (type === 'boxes') {
    // Boxes, each as its min and max corners, ";" between them.
    if (el.value.trim() === '') return [];
    return el.value.split(';').map((part) => {
      const v = part.split(',').map((w) => Number(w.trim()));
      if (v.length !== 6 || v.some((x) => !Number.isFinite(x))) throw new Error(`${labelOf(el)}: give each box as 6 numbers separated by commas, and ";" between boxes`);
      const kept = v.map(mm);
      return { name: '', min: kept.slice(0, 3), max: kept.slice(3) };
    });
  }
  if (el.type === 'number' || type === 'int') {
    if (el.value === '' && type === 'optional') return null;
    const v = Number(el.value);
    if (el.value === '' || !Number.isFinite(v)) throw new Error(`${labelOf(el)}: not a number`);
    return type === 'int' ? Math.round(v) : mm(v);
  }
  return el.value;
}

export function show(el, value) {
  const page = (v) => (unitOf(el) && typeof v === 'number' ? fieldText(v, unitOf(el)) : v);
  if (el.type === 'checkbox') el.checked = !!value;
  else if (el.dataset.type === 'list' || el.dataset.type === 'numbers' || el.dataset.type === 'ints') el.value = (value || []).map(page).join(', ');
  else if (el.dataset.type === 'boxes') el.value = (value || []).map((b) => [...b.min, ...b.max].map(page).join(', ')).join('; ');
  else if (el.dataset.type === 'box') el.value = value ? [...value.min, ...value.max].map(page).join(', ') : '';
  else el.value = page(value) ?? '';
}

// Keeps `n` children in `list`, made by `make()` where there are too few, and returns them to
// be filled in place: a list is never rebuilt under the pointer, so a click that began on an
// item before a field's change event refreshed the list (blurring the field fires it between
// mousedown and mouseup) still lands on it.
export function sized(list, n, make) {
  while (list.children.length > n) list.lastElementChild.remove();
  while (list.children.length < n) list.append(make());
  return [...list.children];
}

export function fillFields(container, obj) {
  for (const el of container.querySelectorAll('[data-key]')) show(el, getKey(obj, el.dataset.key));
}

// The message under Generate: `level` error, warning, note or ok (empty text: none).
export function message(text, level = 'note') {
  const m = $('message');
  m.className = text ? level : '';
  m.dataset.from = '';
  m.textContent = words(text ? pathWords(text) : text);
}

// The job's field paths in a message (`stock.bar.diameter: …`, "raise stock.marginTop") said as
// the page's place of the field ("Stock → Bar diameter"), where the page has that field; a path
// it has none for (or a file's name, "part.stl") stays as it is. An operation's or a tool's
// path names the job it came with (a loaded file's), not the one on show: it stays too.
const PATH = /\b(?:stock|part|drawing|post|machine)\.[A-Za-z][A-Za-z.]*[A-Za-z]/g;
export function pathWords(text) {
  return String(text).replace(PATH, (p) => {
    const said = placeWords(p);
    return said.endsWith(`→ ${p.slice(p.indexOf('.') + 1)}`) ? p : said;
  });
}

// A file or job taken in has had its answer (read, or refused with the message): counted on
// the page's body (`data-answered`), the signal a test or a portal waits on.
export function answered() {
  document.body.dataset.answered = String(Number(document.body.dataset.answered ?? 0) + 1);
}

// A field's own message: a value that does not read (marked until it does).
export function fieldError(el, text) {
  el.classList.toggle('invalid', !!text);
  el.setAttribute('aria-invalid', text ? 'true' : 'false');
  if (text) el.closest('details')?.setAttribute('open', '');
  const label = el.closest('label');
  let note = label?.nextElementSibling?.classList.contains('field-error') ? label.nextElementSibling : null;
  if (!text) { note?.remove(); return; }
  if (!note) { note = document.createElement('span'); note.className = 'field-error'; label?.after(note); }
  note.textContent = words(text);
}

// Where a problem's path (`operations[2].stepdown`, `tools[0].diameter`, `stock.marginXy`) is
// in the page: its tab, and its field if that object is the one on show.
function placeOf(path) {
  // A setup's operation is the list's when the setup is on show.
  let m = path.match(/^setups\[(\d+)\]\.(.+)$/);
  if (m) {
    const k = Number(m[1]), rest = m[2], shown = k === setupIndex();
    const inner = rest.startsWith('operations[') && shown ? placeOf(rest) : {};
    const field = !rest.startsWith('operations') && shown ? `#setup-editor [data-setup="${rest}"]` : inner.field ?? null;
    return { tab: 'ops', setup: k, op: inner.op ?? null, field };
  }
  m = path.match(/^operations\[(\d+)\]\.(.+)$/);
  if (m) return { tab: 'ops', op: Number(m[1]), field: Number(m[1]) === state.selected[state.kind] ? `#op-editor [data-key="${m[2]}"]` : null };
  m = path.match(/^tools\[(\d+)\]\.(.+)$/);
  if (m) return { tab: 'tools', tool: Number(m[1]), field: Number(m[1]) === state.selected.tool ? `#tool-editor [data-key="${m[2]}"]` : null };
  m = path.match(/^(stock|part|drawing|post|machine)\.(.+)$/);
  if (m) return { tab: { stock: 'stock', part: 'part', drawing: 'part', post: 'post', machine: 'post' }[m[1]], field: `#settings [data-key="${m[1]}.${m[2]}"]` };
  return { tab: null, field: null };
}

// Where a problem's path is, in the page's words: "Operations → 'rough' → Step-down",
// "Tools → T1 → Diameter", "Stock → Stock around the part, X and Y" (the core's messages name no
// path: `checkJob` leaves it to the page).
const TAB_NAMES = { stock: 'Stock', part: 'Part', drawing: 'Part', post: 'Controller', machine: 'Controller' };
// An operation's setting in its form's words (the key where the form has no field for it).
const fieldWords = (op, key) => (op && formOf(op.kind)?.fields.find((f) => f.key === key)?.label) ?? key;
export function placeWords(path) {
  // The field on show where one is (several operation kinds share a key), its label without
  // the unit in brackets.
  const label = (selector) => {
    const all = [...document.querySelectorAll(selector)], el = all.find((e) => !e.closest('[hidden]')) ?? all[0];
    return el ? labelOf(el).replace(/\s*\([^)]*\)\s*$/, '') : null;
  };
  let m = path.match(/^setups\[(\d+)\]\.(.+)$/);
  if (m) {
    const k = Number(m[1]), setup = job()?.setups?.[k], name = setup?.name || `Setup ${k + 1}`;
    const op = m[2].match(/^operations\[(\d+)\]\.(.+)$/);
    if (op) {
      const o = setup?.operations?.[Number(op[1])];
      return `Operations → ${name} → '${o?.name ?? `operation ${Number(op[1]) + 1}`}' → ${fieldWords(o, op[2])}`;
    }
    return `Operations → ${name} → ${label(`#setup-editor [data-setup="${m[2]}"]`) ?? m[2]}`;
  }
  m = path.match(/^operations\[(\d+)\]\.(.+)$/);
  if (m) {
    const op = ops()[Number(m[1])];
    return `Operations → '${op?.name ?? `operation ${Number(m[1]) + 1}`}' → ${fieldWords(op, m[2])}`;
  }
  m = path.match(/^tools\[(\d+)\]\.(.+)$/);
  if (m) return `Tools → T${state.tools[Number(m[1])]?.number ?? Number(m[1]) + 1} → ${label(`#tool-editor [data-key="${m[2]}"]`) ?? m[2]}`;
  m = path.match(/^(stock|part|drawing|post|machine)\.(.+)$/);
  if (m) return `${TAB_NAMES[m[1]]} → ${label(`#settings [data-key="${m[1]}.${m[2]}"]`) ?? m[2]}`;
  return path;
}

// A problem said in the page's words: where, then what.
export const problemWords = (p) => (p.path ? `${placeWords(p.path)}: ${p.message}` : p.message);

// Marks the fields of `problems` (the core's checks of the job, `[{ path, message }]`), their
// tabs, operations and tools; clears the rest.
export function markProblems(problems) {
  state.problems = problems;
  for (const el of document.querySelectorAll('#settings .invalid[data-key]')) if (!el.dataset.unreadable) fieldError(el, '');
  for (const el of document.querySelectorAll('.has-problem')) el.classList.remove('has-problem');
  for (const p of problems) {
    const place = placeOf(p.path);
    const el = place.field && document.querySelector(place.field);
    if (el && !el.closest('[hidden]')) fieldError(el, p.message);
    if (place.tab) document.querySelector(`#tabs [data-tab="${place.tab}"]`)?.classList.add('has-problem');
    if (place.op != null) document.querySelector(`#op-list li[data-index="${place.op}"]`)?.classList.add('has-problem');
    if (place.setup != null) document.querySelector(`#setup-tabs [data-setup-index="${place.setup}"]`)?.classList.add('has-problem');
    if (place.tool != null) $('tool-list').options[place.tool]?.classList.add('has-problem');
  }
}

// The problems of the job on show, as the core finds them, marked where they are; in order
// (a later check's answer replaces an earlier one's, never the reverse).
let asked = 0;
export async function check() {
  if (!state.engine || !job()) return [];
  const k = ++asked;
  let problems;
  try {
    // The holes found in the part or drawing on show, for the hole operations' checks.
    const holes = state.holes?.of === state.name ? state.holes.items : null;
    problems = await state.engine.checkJob(buildJob({ all: true }), state.kind === 'part' ? state.part?.bounds : null, holes);
  } catch (e) {
    problems = [{ path: '', message: e.message }];
  }
  if (k === asked) markProblems(problems);
  return problems;
}
