// Setups: a part machined from more than one side. The setups are tabs over the operation list,
// each with its own operations, how the part is turned over for it (from the setup before, as
// a machinist turns it in the vise) and its work offset; a job without setups is its one setup.
// Before Generate the view shows the part as the setup on show holds it; after, that setup's
// paths, program and simulation (results.js shows them, `hooks.showSetupResult`).
import { $, state, hooks, job, hasSetups, setupIndex, store } from './state.js';
import { sized, message, fieldError } from './forms.js';
import { setTime, play } from './simulation.js';

const WORK_OFFSETS = ['G54', 'G55', 'G56', 'G57', 'G58', 'G59'];

// A setup's name: its own, or "Setup N" as the core names it.
export const setupName = (s, k) => s.name || `Setup ${k + 1}`;

// The tabs and the setup's own fields (a part's job only: a drawing is cut from one side).
export function fillSetups() {
  const box = $('setups'), j = job();
  box.hidden = state.kind !== 'part' || !j;
  if (box.hidden) return;
  const many = hasSetups(j), shown = setupIndex(j);
  const names = many ? j.setups.map(setupName) : ['Setup 1'];
  const tabs = sized($('setup-tabs'), names.length, () => {
    const b = document.createElement('button');
    b.type = 'button';
    b.setAttribute('role', 'tab');
    return b;
  });
  names.forEach((n, k) => {
    tabs[k].textContent = n;
    tabs[k].dataset.setupIndex = String(k);
    tabs[k].setAttribute('aria-selected', String(k === shown));
  });
  $('setup-editor').hidden = !many;
  if (!many) return;
  const s = j.setups[shown];
  offsetChoices(j, s.workOffset);
  for (const el of $('setup-editor').querySelectorAll('[data-setup]')) {
    const v = s[el.dataset.setup];
    el.value = v == null ? '' : String(v);
  }
  // The first setup holds the part as it is placed: it turns nothing over.
  $('setup-editor').querySelector('[data-setup="flip"]').disabled = state.running || shown === 0 || s.up != null;
  $('setup-remove').disabled = state.running;
}

// The work offsets the job's control has (its post's `workOffsets`: G59.1 to G59.3 on
// LinuxCNC and grblHAL, G54.1 P1 to P48 on Fanuc), and `current` whatever it is.
function offsetChoices(j, current) {
  const post = j.post.custom ?? state.posts.find((p) => p.dialect === j.post.dialect)?.post;
  const more = post?.workOffsets ?? {};
  const words = [...WORK_OFFSETS, ...(more.g59Dot ? ['G59.1', 'G59.2', 'G59.3'] : []), ...Array.from({ length: more.extended ?? 0 }, (_, k) => `G54.1 P${k + 1}`)];
  if (current && !words.includes(current)) words.push(current);
  const select = $('setup-editor').querySelector('[data-setup="workOffset"]');
  // None of its own: the job's (the Controller tab's), else its post's (G54 in the built-in
  // posts), said as the program writes it; the controller's current only where neither has one.
  const inherited = j.post.workOffset ?? post?.workOffset;
  const own = inherited ? `the job's (${inherited})` : 'the controller\'s current';
  const key = [own, ...words].join(',');
  if (select.dataset.choices === key) return;
  select.dataset.choices = key;
  select.replaceChildren(new Option(own, ''), ...words.map((w) => new Option(w, w)));
}

// The skin a part turned over keeps round its parting line until it is broken off (mm).
const SKIN = 1;

// Another setup: the part turned over about X (its bottom up), facing its new top first; the
// operations so far become the first setup's.
export function addSetup() {
  const j = job();
  if (!hasSetups(j)) {
    j.setups = [{ name: 'Top', flip: 'none', turn: 0, workOffset: null, zero: null, operations: j.operations }];
    j.operations = [];
  }
  const face = structuredClone(state.defaults.operations.find((o) => o.kind === 'face'));
  const flat = state.tools.find((t) => t.shape === 'flat') ?? state.tools[0];
  if (flat) face.tool = flat.number;
  const k = j.setups.length;
  // Each side roughed and finished down to the parting line (the part's widest section) from
  // its own face: the first setup's roughings and 3D finishings stop there, and the new side
  // cuts with copies of them that stop a skin short of it, so the part stays joined to the
  // stock until the skin is broken.
  let parted = '';
  const sided = k === 1 ? j.setups[0].operations.filter((o) => 'bottomFrom' in o && 'topFrom' in o && o.bottom == null && (o.bottomFrom ?? 'zero') === 'zero') : [];
  const copies = sided.map((o) => {
    o.bottomFrom = 'partingLine';
    return { ...structuredClone(o), name: `${o.name} (bottom)`, bottom: SKIN };
  });
  if (copies.length) parted = ` The roughing and finishing of each side stop at the parting line (the part's widest section), the bottom's ${SKIN} mm short of it: a skin that holds the part to the stock, to break off.`;
  j.setups.push({ name: k === 1 ? 'Bottom' : `Setup ${k + 1}`, flip: 'aboutX', turn: 0, workOffset: WORK_OFFSETS[k] ?? null, zero: null, operations: [face, ...copies] });
  // The bottom's facing needs stock under the part to face: a block cut to the part's height
  // has none, and its facing would find nothing to cut.
  let more = '';
  if (k === 1 && j.stock && !j.stock.bar && !j.stock.mesh && !(j.stock.marginBottom > 0)) {
    j.stock.marginBottom = j.stock.marginTop > 0 ? j.stock.marginTop : 1;
    more = ` 'Stock below the part' is now ${j.stock.marginBottom} mm (Stock tab), for the bottom's facing to cut.`;
  }
  message(`Added the setup '${j.setups[k].name}': the part turned over about X (its bottom up), held in ${j.setups[k].workOffset ?? j.post.workOffset ?? 'the controller\'s work offset'}; it starts from the stock the setup before leaves.${more}${parted}`, 'note');
  select(k);
}

// The setup on show removed; the last one left makes the job one setup again.
export function removeSetup() {
  const j = job();
  if (!hasSetups(j)) return;
  const k = setupIndex(j);
  const [gone] = j.setups.splice(k, 1);
  if (j.setups.length === 1) {
    j.operations = j.setups[0].operations;
    j.setups = [];
    // One side again: its roughings go down to the stock's bottom, as before it was parted.
    for (const o of j.operations) if (o.bottomFrom === 'partingLine' && o.bottom == null) o.bottomFrom = 'zero';
  }
  message(`Removed the setup '${setupName(gone, k)}': Undo (Ctrl+Z) brings it back.`, 'note');
  select(Math.max(0, k - 1));
}

// Shows setup `k`: its operations, and its result or the part as it holds it.
export async function select(k) {
  state.selected.setup = k;
  state.selected.part = 0;
  store();
  hooks.fillAll?.();
  hooks.changed?.();
  if (state.results?.[k]) {
    await hooks.showSetupResult?.(k);
  } else {
    hooks.clearResult?.();
    await showHeld();
  }
}

// The simulation of setup `k` played from its start (the stock the setup before left).
export async function playSetup(k) {
  await select(k);
  setTime(0);
  play();
}

export function onSetupTabs(e) {
  const b = e.target.closest('[data-setup-index]');
  if (b && !state.running) select(Number(b.dataset.setupIndex));
}

// A setup's field changed: the job follows (a result of other settings is no longer shown).
export function onSetupField(el) {
  const j = job(), key = el.dataset.setup;
  if (!key || !hasSetups(j)) return;
  const s = j.setups[setupIndex(j)];
  let value = el.value;
  if (key === 'turn') value = Number(value);
  if ((key === 'workOffset' || key === 'up') && value === '') value = null;
  // A face up is the setup's whole orientation: no flip from the setup before besides.
  if (key === 'up' && value !== null) s.flip = 'none';
  if (key === 'name') value = value.trim();
  fieldError(el, '');
  if (s[key] === value) return;
  s[key] = value;
  store(`setup.${key}`);
  if (key === 'name') { fillSetups(); hooks.changed?.(); return; }
  state.results = null;
  hooks.clearResult?.();
  fillSetups();
  hooks.changed?.();
  showHeld();
}

// Turns `part` (positions and normals, as the engine gives them) as `frame` holds it.
export function held(part, frame) {
  const [a, b, c, d, e, f, g, h, i] = frame.rotation;
  const [cx, cy, cz] = frame.centre, [sx, sy, sz] = frame.shift;
  const turn = (src, shifted) => {
    const out = new src.constructor(src.length);
    for (let k = 0; k < src.length; k += 3) {
      const x = src[k] - (shifted ? cx : 0), y = src[k + 1] - (shifted ? cy : 0), z = src[k + 2] - (shifted ? cz : 0);
      // Column after column: the first three numbers are where X goes.
      out[k] = a * x + d * y + g * z + (shifted ? cx + sx : 0);
      out[k + 1] = b * x + e * y + h * z + (shifted ? cy + sy : 0);
      out[k + 2] = c * x + f * y + i * z + (shifted ? cz + sz : 0);
    }
    return out;
  };
  // A box turned by quarter turns is the turned part's box: its corners turned, each axis's
  // least and greatest.
  const corners = turn(Float64Array.from(part.bounds), true);
  const bounds = [0, 1, 2].map((a) => Math.min(corners[a], corners[a + 3])).concat([0, 1, 2].map((a) => Math.max(corners[a], corners[a + 3])));
  return { ...part, positions: turn(part.positions, true), normals: turn(part.normals, false), bounds, hash: null };
}

// The part in the view as the setup on show holds it (before Generate), moved to its work zero,
// with the stock's box, the fixtures and the zero: what the program will see. Counted on the
// page's body (`data-setup-shown`), the signal a test waits on.
let asked = 0, shownPart = null, shownAs = null;
export async function showHeld() {
  return stage(false);
}

// The view has lost the part as staged (a result was shown, or cleared): stages it again.
export function restage() {
  return stage(true);
}

async function stage(again) {
  if (again) shownAs = undefined;
  const j = job(), k = ++asked, part0 = state.part;
  if (state.kind !== 'part' || !state.part || !state.viewer) return;
  let frame = null;
  try {
    const frames = await state.engine.stageFrames(j, state.part.bounds);
    if (k !== asked) return;
    frame = frames[hasSetups(j) ? setupIndex(j) : 0] ?? null;
  } catch {
    // A job that does not read is marked at its fields; the part stays as placed.
  }
  // A drawing or another part shown meanwhile is not this one's to stage.
  if (k !== asked || state.result || state.kind !== 'part' || state.part !== part0) return;
  // The part drawn again only where it moved (a die-sized part is tens of megabytes).
  const as = frame ? JSON.stringify([frame.rotation, frame.centre, frame.shift]) : null;
  const stock = frame ? [...frame.stock.min, ...frame.stock.max] : null;
  if (state.part !== shownPart || as !== shownAs) {
    const moved = frame && (frame.rotation.some((v, i) => v !== [1, 0, 0, 0, 1, 0, 0, 0, 1][i]) || frame.shift.some((v) => v !== 0));
    // A new part is framed with its stock, and one moved (a setup turned, the zero moved); one
    // drawn again after a result keeps the camera.
    const reframe = state.part !== shownPart || shownAs !== undefined;
    const part = moved ? held(state.part, frame) : state.part;
    state.viewer.setPart(part, reframe);
    if (reframe && stock) state.viewer.frameStage(part.bounds, stock);
    [shownPart, shownAs] = [state.part, as];
  }
  // Bar stock drawn as the bar it is, where the bar is as it came (the first setup's).
  const bar = j?.stock?.bar && (!hasSetups(j) || setupIndex(j) === 0) ? j.stock.bar : null;
  state.viewer.setStage(frame ? { stock, fixtures: frame.fixtures, bar } : null);
  document.body.dataset.setupShown = String(Number(document.body.dataset.setupShown ?? 0) + 1);
}

