// The tool library: a list to pick from, a form for the picked tool, tools added, copied,
// deleted, exported and imported as JSON (read by the core, as a job's tools are).
import { $, state, hooks, selectedTool, store, downloadText, buildJob, toolsOf } from './state.js';
import { fillFields, message, sized, fieldError } from './forms.js';
import * as units from './units.js';
import { zipStored } from './zip.js';

const shapeName = (t) => ({ ball: 'ball', flat: 'flat', bullNose: `bull nose r${t.cornerRadius}`, drill: `drill ${t.angle ?? 118}°`, spotDrill: `spot drill ${t.angle ?? 90}°`, vBit: `V-bit ${t.angle ?? 90}°`, threadMill: 'thread mill' }[t.shape] || t.shape);
export const toolLabel = (t) => `T${t.number} · ${units.exact(t.diameter)} ${units.lengthUnit()} ${shapeName(t)}${t.name ? ` · ${t.name}` : ''}`;

export function fillTools() {
  const list = $('tool-list');
  const options = sized(list, state.tools.length, () => new Option());
  state.tools.forEach((t, i) => { options[i].text = toolLabel(t); options[i].value = String(i); });
  state.selected.tool = Math.max(0, Math.min(state.selected.tool, state.tools.length - 1));
  list.value = String(state.selected.tool);
  const t = selectedTool();
  $('tool-editor').hidden = !t;
  if (t) fillFields($('tool-editor'), t);
  document.querySelector('#tool-editor [name=cornerRadius]').closest('label').hidden = t?.shape !== 'bullNose';
  document.querySelector('#tool-editor [name=pointAngle]').closest('label').hidden = !['drill', 'spotDrill', 'vBit'].includes(t?.shape);
  document.querySelector('#tool-editor [name=tipDiameter]').closest('label').hidden = t?.shape !== 'vBit';
  fillHolder(t);
  fillToolChoices();
  showSpeeds();
}

// The picked tool's speeds and feeds as the job cuts them, with how they were worked out (the
// core's, from the stock's material or as typed); the fields show the figures it runs at.
let asked = 0;
export async function showSpeeds() {
  const t = selectedTool(), k = ++asked;
  if (!t || !state.engine) return;
  let data;
  try {
    data = (await state.engine.cuttingData({ ...buildJob({ all: true }), tools: [t] }))[0];
  } catch {
    return;
  }
  if (k !== asked || !data) return;
  const hint = $('tool-speeds');
  hint.textContent = data.fromMaterial ? `${units.words(data.reason)}. Source: ${data.source}.` : `Speeds and feeds ${data.reason}.`;
  hint.dataset.fromMaterial = String(data.fromMaterial);
  // The figures it runs at, in the fields (kept as typed in the tool for when it goes back).
  if (data.fromMaterial) {
    for (const [name, v] of [['spindleRpm', data.spindleRpm], ['feedRate', data.feedRate], ['plungeRate', data.plungeRate]]) {
      const el = document.querySelector(`#tool-editor [name=${name}]`);
      if (document.activeElement !== el) el.value = name === 'spindleRpm' ? String(v) : units.fieldText(v, 'feed');
    }
  }
}

// ---- holders ------------------------------------------------------------------------------
// A tool's holder: none, one of the core's built-in ones (ER collet chucks, a router's nut), or
// the tool's own (imported, or its sections edited), its sections said as "34 × 19.5, 40 × 40"
// (a cone "20 × 8 to 28"), diameters and lengths in the page's units.
const mmText = (v) => units.fieldText(v);
export const sectionsText = (h) => h.sections.map((s) => `${mmText(s.diameter)} × ${mmText(s.length)}${s.topDiameter != null ? ` to ${mmText(s.topDiameter)}` : ''}`).join(', ');

function fillHolder(t) {
  const select = document.querySelector('#tool-editor [name=holder]');
  if (select.options.length === 1) for (const h of state.defaults?.holders ?? []) select.append(new Option(h.name, h.name));
  select.querySelector('[value=own]')?.remove();
  const builtin = t?.holder && state.defaults.holders.find((h) => JSON.stringify(h) === JSON.stringify(t.holder));
  if (t?.holder && !builtin) select.append(new Option(`its own: ${t.holder.name}`, 'own'));
  select.value = !t?.holder ? '' : builtin ? builtin.name : 'own';
  const sections = document.querySelector('#tool-editor [name=holderSections]');
  sections.closest('label').hidden = !t?.holder;
  if (t?.holder && document.activeElement !== sections) sections.value = sectionsText(t.holder);
}

// The holder chosen, or its sections typed.
export function onHolderField(el) {
  const t = selectedTool();
  if (!t) return;
  if (el.name === 'holder') {
    if (el.value === 'own') return;
    const h = state.defaults.holders.find((x) => x.name === el.value);
    t.holder = h ? structuredClone(h) : null;
  } else {
    const sections = [];
    for (const part of el.value.split(',').map((p) => p.trim()).filter(Boolean)) {
      const m = part.match(/^([\d.]+)\s*[x×*]\s*([\d.]+)(?:\s*to\s*([\d.]+))?$/i);
      if (!m || [m[1], m[2], m[3]].some((v) => v !== undefined && !(Number(v) > 0))) { fieldError(el, `"${part}": give a section as diameter × length, a cone as diameter × length to its top diameter`); return; }
      sections.push({ diameter: units.fromPage(Number(m[1])), length: units.fromPage(Number(m[2])), topDiameter: m[3] === undefined ? null : units.fromPage(Number(m[3])) });
    }
    if (!sections.length) { fieldError(el, 'a holder needs at least one section (or choose none)'); return; }
    fieldError(el, '');
    t.holder = { name: t.holder?.name ?? 'holder', sections };
    if (state.defaults.holders.some((h) => h.name === t.holder.name && JSON.stringify(h.sections) !== JSON.stringify(sections))) t.holder.name = `${t.holder.name} (edited)`;
  }
  store();
  fillTools();
  hooks.changed?.();
}

// The library's tools, to choose an operation's tool from (where its form has one).
export function fillToolChoices() {
  const opTool = document.querySelector('#op-editor [name=op-tool]');
  if (!opTool) return;
  const choices = sized(opTool, state.tools.length, () => new Option());
  state.tools.forEach((u, i) => { choices[i].text = toolLabel(u); choices[i].value = String(u.number); });
}

export function addTool(copy) {
  const base = copy && selectedTool() ? selectedTool() : state.defaults.tool;
  const t = structuredClone(base);
  t.number = Math.max(0, ...state.tools.map((u) => u.number)) + 1;
  if (!copy) t.name = '';
  state.tools.push(t);
  state.selected.tool = state.tools.length - 1;
  store();
  fillTools();
  hooks.changed?.();
}

export function deleteTool() {
  const t = selectedTool();
  if (!t) return;
  const users = Object.values(state.jobs).flatMap((j) => j.operations).filter((op) => (op.kind === 'roughOctree' ? op.tools ?? [] : [op.tool]).includes(t.number));
  if (users.length) { message(`T${t.number} is used by ${users.map((o) => `'${o.name}'`).join(', ')}: give them another tool first`, 'error'); return; }
  state.tools.splice(state.selected.tool, 1);
  store();
  fillTools();
  hooks.changed?.();
}

// A tool's number changed: the operations using it follow.
export function renumber(from, to) {
  for (const j of Object.values(state.jobs)) {
    for (const op of j.operations) {
      if (op.tool === from) op.tool = to;
      if (op.tools) op.tools = op.tools.map((n) => (n === from ? to : n));
    }
  }
}

export async function exportTools() {
  const format = $('tool-export-format').value;
  if (format === 'swarf') { downloadText('swarf-tools.json', JSON.stringify({ tools: state.tools }, null, 2), 'application/json'); return; }
  try {
    if (format === 'freecad') {
      // A library and a bit a tool, in the folders of FreeCAD's Tools folder, as one zip.
      const [library, ...bits] = await state.engine.writeFreecadLibrary(state.tools, 'swarf-tools');
      const files = [{ name: `Tools/Library/${library.name}`, text: library.text }, ...bits.map((b) => ({ name: `Tools/Bit/${b.name}`, text: b.text }))];
      downloadText('swarf-tools-freecad.zip', zipStored(files), 'application/zip');
      message(`Exported ${bits.length} tool(s) as a FreeCAD library: unzip it into FreeCAD's folder that holds Tools. A FreeCAD bit holds no speeds or holder (its tool controller does): they are not in it.`, 'ok');
      return;
    }
    const text = await state.engine.writeToolLibrary(state.tools, format);
    downloadText(format === 'fusion' ? 'swarf-tools.fusion.json' : 'swarf-tools.tbl', text, format === 'fusion' ? 'application/json' : 'text/plain');
  } catch (e) {
    message(e.message, 'error');
  }
}

// Imported tools replace those of the same number and join the rest. swarf's own JSON is read
// by the core as a job's tools are (a misspelt field is named); the libraries machinists keep
// (Fusion's, a LinuxCNC tool table, FreeCAD's bits and libraries) are read by the core too,
// and what they hold that swarf does not take is said.
// The operations of every job and setup that use tool `number`, by name.
function usedBy(number) {
  const all = Object.values(state.jobs).filter(Boolean).flatMap((j) => [...(j.operations ?? []), ...(j.setups ?? []).flatMap((s) => s.operations ?? [])]);
  return all.filter((op) => toolsOf(op).includes(number)).map((op) => op.name);
}

// Imported tools into the library: each replacing the one of its number, or added.
function takeTools(tools, said, level) {
  for (const t of tools) {
    const k = state.tools.findIndex((u) => u.number === t.number);
    if (k >= 0) state.tools[k] = t; else state.tools.push(t);
  }
  $('tool-import-review').hidden = true;
  store();
  fillTools();
  hooks.changed?.();
  message(said, level);
}

// An import that would replace tools the library has: shown side by side, with the operations
// that use each, and taken only when the user says which.
function reviewImport(tools, replaced, name, said) {
  const added = tools.filter((t) => !state.tools.some((u) => u.number === t.number));
  const kept = tools.length - replaced.length - added.length;
  $('tool-import-said').textContent = `${name}: ${tools.length} tool(s), ${added.length} new${kept ? `, ${kept} as the library has them` : ''}; ${replaced.length} would replace the library's of the same number:`;
  $('tool-import-changes').replaceChildren(...replaced.map((t) => {
    const li = document.createElement('li');
    const old = state.tools.find((u) => u.number === t.number), users = usedBy(t.number);
    li.textContent = `${toolLabel(old)} → ${toolLabel(t)}${users.length ? ` (used by ${users.join(', ')})` : ''}`;
    return li;
  }));
  $('tool-import-review').hidden = false;
  message(`${name}: replaces ${replaced.length} tool(s) of the library: Replace them, Add only the new, or Cancel.`, 'warning');
  $('tool-import-replace').onclick = () => takeTools(tools, `Imported ${tools.length} tool(s) from ${name}, replacing ${replaced.map((t) => `T${t.number}`).join(', ')}.${said}`, 'warning');
  $('tool-import-new').onclick = () => takeTools(added, `Imported the ${added.length} new tool(s) from ${name}; the library's ${replaced.map((t) => `T${t.number}`).join(', ')} kept.${said}`, 'ok');
  $('tool-import-cancel').onclick = () => { $('tool-import-review').hidden = true; message(`${name}: nothing imported.`, 'note'); };
}

export async function importTools(files) {
  const name = files.map((f) => f.name).join(', ');
  try {
    let tools, notes = [];
    const text = files.length === 1 && /\.json$/i.test(files[0].name) ? await files[0].text() : null;
    const parsed = text ? JSON.parse(text) : null;
    if (parsed && (Array.isArray(parsed) || Array.isArray(parsed.tools))) {
      tools = (await state.engine.readJob(JSON.stringify({ tools: Array.isArray(parsed) ? parsed : parsed.tools }))).tools;
    } else {
      const read = await state.engine.readToolLibrary(await Promise.all(files.map(async (f) => ({ name: f.name, bytes: new Uint8Array(await f.arrayBuffer()) }))), { inches: $('tool-import-inches').checked });
      ({ tools, notes } = read);
    }
    const same = (a, b) => JSON.stringify(a) === JSON.stringify(b);
    const replaced = tools.filter((t) => state.tools.some((u) => u.number === t.number && !same(u, t)));
    const said = notes.length ? ` Notes: ${notes.join('; ')}.` : '';
    if (replaced.length) {
      reviewImport(tools, replaced, name, said);
      return;
    }
    takeTools(tools, `Imported ${tools.length} tool(s) from ${name}.${said}`, notes.length ? 'warning' : 'ok');
  } catch (e) {
    message(`${name}: ${e.message}`, 'error');
  }
}
