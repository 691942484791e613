// The page a machinist can trust (issue 36): a part's units are its own, a file cut short is an
// error, every entry reads jobs strictly, bad values are marked where they are typed, warnings
// look like warnings, every control is in reach at the usual screen sizes, the words are a
// machinist's, and the simulation shows the tool, the path cut and the program's lines.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { execFileSync } from 'node:child_process';
import { root, shots, PATIENCE, browser, base, waitForGenerated, generated, tab, frame, openPage, onlyRaster, toolTable, pixelCounts, pathPixels, boxStl, mrrLabels } from './harness.mjs';

const size = (page) => page.textContent('#part-size');

test('units, scale and orientation belong to the part: a new file and a reload start from the format\'s own, and any axis can point up', async () => {
  const { page, context, errors } = await openPage();
  assert.match(await size(page), /^90\.0 × 60\.0 × 25\.3 mm/);
  await page.selectOption('select[name=partUnits]', 'inch');
  await page.selectOption('select[name=upAxis]', 'y');
  await page.fill('input[name=partScale]', '100');
  await page.press('input[name=partScale]', 'Tab');
  // Shown live, beside the size: the settings that are not the format's own.
  await page.waitForFunction(() => /read in inch, scaled × 100, \+Y up/.test(document.getElementById('part-size').textContent));
  assert.doesNotMatch(await size(page), /^90\.0 ×/);
  // A new file starts from its format's own units, scale 1, Z up.
  await page.setInputFiles('#file', { name: 'box.stl', mimeType: 'model/stl', buffer: boxStl([10, 20, 5]) });
  await page.waitForFunction(() => /box\.stl/.test(document.getElementById('part-name').textContent));
  assert.match(await size(page), /^10\.0 × 20\.0 × 5\.00 mm .*read in mm, as STL says nothing/);
  assert.equal(await page.locator('#part-size .override').count(), 0);
  assert.deepEqual([await page.inputValue('select[name=partUnits]'), await page.inputValue('input[name=partScale]'), await page.inputValue('select[name=upAxis]')], ['auto', '1', 'z']);
  // −Y up then a quarter turn: (x, y, z) → (x, z, −y) → X 5, Y 10, Z 20; the grid and its size
  // under the view say so too.
  await page.selectOption('select[name=upAxis]', '-y');
  await page.waitForFunction(() => /^10\.0 × 5\.00 × 20\.0 mm/.test(document.getElementById('part-size').textContent));
  await page.selectOption('select[name=rotation]', '90');
  await page.waitForFunction(() => /^5\.00 × 10\.0 × 20\.0 mm/.test(document.getElementById('part-size').textContent));
  assert.match(await page.textContent('#scale'), /grid \d+ mm · part 5\.00 × 10\.0 × 20\.0 mm/);
  assert.match(await size(page), /−Y up, turned 90°/);
  // A reload shows the sample as it is, whatever the last part was read as.
  await page.selectOption('select[name=partUnits]', 'inch');
  await page.reload();
  await page.waitForSelector('body[data-ready="true"]');
  await page.waitForFunction(() => /sample part/.test(document.getElementById('part-name').textContent));
  assert.match(await size(page), /^90\.0 × 60\.0 × 25\.3 mm/);
  assert.equal(await page.inputValue('select[name=partUnits]'), 'auto');
  assert.deepEqual(errors, []);
  await context.close();
});

test('a file that ends early is an error in every format, with where it ends, and keeps the part on show; a part with holes is warned of', async () => {
  const { page, context, errors } = await openPage();
  const facet = (k) => `facet normal 0 0 1\nouter loop\nvertex ${k} 0 0\nvertex ${k + 1} 0 0\nvertex ${k} 1 0.5\nendloop\nendfacet\n`;
  let ascii = 'solid cut\n';
  for (let k = 0; k < 40; k++) ascii += facet(k);
  ascii += 'endsolid cut\n';
  let obj = '';
  for (let k = 0; k < 30; k++) obj += `v ${k}.125 0.5 1.75\nv ${k}.5 1.25 0.5\nv ${k}.75 0.25 2.5\n`;
  for (let k = 0; k < 30; k++) obj += `f ${3 * k + 1} ${3 * k + 2} ${3 * k + 3}\n`;
  for (const [name, text, said] of [
    ['half.stl', ascii.slice(0, ascii.length / 2), /ASCII STL ends (at|inside) line \d+/],
    ['nosolidend.stl', ascii.slice(0, ascii.lastIndexOf('endsolid')), /ends at line 281 without the endsolid/],
    ['cut.obj', obj.slice(0, obj.length - 2), /OBJ ends inside line 120 \('f 88 89 9'\)/],
  ]) {
    await page.setInputFiles('#file', { name, mimeType: 'application/octet-stream', buffer: Buffer.from(text) });
    await page.waitForFunction((n) => document.getElementById('message').textContent.startsWith(n), name);
    const message = await page.textContent('#message');
    assert.match(message, said, message);
    assert.match(message, /cut short/);
    assert.equal(await page.getAttribute('#message', 'class'), 'error');
    assert.equal(await page.textContent('#part-name'), 'sample part');
    assert.equal(await page.isEnabled('#generate'), true);
  }
  // The whole OBJ reads. A surface with holes is read, and warned of, in amber, with how many
  // open edges: a cutter goes down through them.
  const holed = boxStl([30, 20, 10]);
  const open = Buffer.concat([holed.subarray(0, 84 + 50 * 2), holed.subarray(84 + 50 * 3)]);
  open.writeUInt32LE(11, 80);
  await page.setInputFiles('#file', { name: 'holed.stl', mimeType: 'model/stl', buffer: open });
  await page.waitForFunction(() => /holed\.stl/.test(document.getElementById('part-name').textContent));
  assert.match(await page.textContent('#part-notes .warning'), /^3 edges of the part's surface border one triangle only: it has holes/);
  assert.equal(await page.getAttribute('#message', 'class'), 'warning');
  assert.deepEqual(errors, []);
  await context.close();
});

test('every entry reads jobs strictly: a portal\'s misspelt field or wrong type is named by its path, and the core\'s checks are a call away', async () => {
  const context = await browser.newContext();
  context.setDefaultTimeout(PATIENCE);
  const page = await context.newPage();
  await page.goto(`${base}embed.html`);
  await page.waitForSelector('body[data-ready="true"]');
  const said = await page.evaluate(async () => {
    const engine = window.engine;
    const attempt = async (edit) => {
      const job = engine.defaultJob();
      job.operations = job.operations.filter((op) => op.kind === 'finishRaster').slice(0, 1);
      edit(job);
      try { await engine.run(job, engine.sample, 'sample.stl'); return 'ran'; } catch (e) { return e.message; }
    };
    const misspelt = await attempt((job) => { job.operations[0].stepOver = job.operations[0].stepover; delete job.operations[0].stepover; });
    const typed = await attempt((job) => { job.stock.marginXy = '5'; });
    const project = await engine.writeProject({ ...engine.defaultJob(), colour: 'red' }, 'x.stl', engine.sample).then(() => 'written', (e) => e.message);
    const problems = await engine.checkJob({ tools: [{ number: 1, shape: 'flat', diameter: -3 }], operations: [{ kind: 'roughZlevel', tool: 1, stepdown: -1 }] });
    return { misspelt, typed, project, problems };
  });
  assert.match(said.misspelt, /^unknown field: operations\[0\]\.stepOver \(did you mean stepover\?\)$/);
  assert.equal(said.typed, 'stock.marginXy: expected a number, got "5"');
  assert.match(said.project, /unknown field: colour/);
  assert.deepEqual(said.problems.map((p) => p.path), ['tools[0].diameter', 'operations[0].stepdown']);
  // A message does not repeat its path (issue 55): a portal shows it at its field.
  for (const p of said.problems) assert.ok(!p.message.includes(p.path) && !/^tools\[|^operations\[/.test(p.message), JSON.stringify(p));
  assert.match(said.problems[0].message, /^the cutter diameter must/);
  await context.close();
});

test('bad values are marked at their fields as they are typed, by the core\'s own checks; Generate and a loaded job say so at once', async () => {
  const { page, context, errors } = await openPage();
  await tab(page, 'ops');
  // The mould job's roughing: a step-down of −1.
  await page.click('#op-list li:nth-child(1) .op-name');
  await page.fill('input[name=op-stepdown]', '-1');
  await page.waitForSelector('input[name=op-stepdown].invalid');
  const note = await page.textContent('#op-fields .field-error');
  // At its field the message names no path (issue 55): the field is where it stands.
  assert.equal(note, "must be a positive number, at most 10000 (got -1) ('rough')");
  assert.doesNotMatch(note, /job file/);
  assert.ok(await page.locator('#op-list li:nth-child(1).has-problem').count());
  assert.ok(await page.locator('#tabs [data-tab="ops"].has-problem').count());
  await page.click('#generate');
  assert.equal(await waitForGenerated(page), 'failed');
  // Beside Generate, in the page's words: where the setting is, not its path in the job file.
  assert.match(await page.textContent('#message'), /^1 setting needs attention: Operations → 'rough' → Step-down: must be a positive number/);
  assert.equal(await page.getAttribute('#message', 'class'), 'error');
  await page.fill('input[name=op-stepdown]', '2');
  await page.waitForFunction(() => !document.querySelector('input[name=op-stepdown]').classList.contains('invalid') && !document.querySelector('#tabs .has-problem'));
  // A value that does not read at all is marked too, and the job keeps its last good one.
  await page.fill('input[name=op-stepdown]', '');
  await page.waitForSelector('input[name=op-stepdown].invalid');
  assert.equal(await page.evaluate(() => window.swarf.jobs.part.operations[0].stepdown), 2);
  await page.fill('input[name=op-stepdown]', '2');
  // A tool's flute shorter than nothing, in the tools' tab.
  await tab(page, 'tools');
  await page.fill('input[name=fluteLength]', '0');
  await page.waitForSelector('input[name=fluteLength].invalid');
  assert.match(await page.textContent('#tool-editor .field-error'), /flute length must be positive/);
  await page.fill('input[name=fluteLength]', '30');
  await page.waitForFunction(() => !document.querySelector('#tabs .has-problem'));
  // A job file whose values do not fit says so as it loads, and its fields are marked.
  const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'swarf-e2e-check-'));
  const [saved] = await Promise.all([page.waitForEvent('download'), page.click('#save-job')]);
  const file = path.join(dir, 'job.json');
  await saved.saveAs(file);
  const job = JSON.parse(fs.readFileSync(file, 'utf8'));
  // The roughing's step-over is a fraction of the diameter, under its own name.
  assert.equal(job.operations[0].stepoverFraction, 0.4);
  assert.equal(job.operations[0].stepover, undefined);
  assert.equal(job.operations[1].stepover, 0.5);
  job.stock.marginXy = -2;
  fs.writeFileSync(file, JSON.stringify(job));
  await page.setInputFiles('#load-job', file);
  await page.waitForFunction(() => /^Loaded the job from job\.json, but 1 setting needs attention/.test(document.getElementById('message').textContent));
  assert.match(await page.textContent('#message'), /Stock → Stock around the part, X and Y: must be zero or more mm, at most 10000 \(got -2\)/);
  await tab(page, 'stock');
  await page.waitForSelector('input[name=marginXy].invalid');
  assert.deepEqual(errors, []);
  await context.close();
});

// Installs `window.cutLists(elements)` in the page: every choice of every list among them
// that would not show whole, as the list holding only that choice at its own width (its text
// and its arrow) against the list as drawn.
async function installCutLists(page) {
  await page.evaluate(() => {
    window.cutLists = (elements) => {
      const bad = [];
      for (const sel of elements.filter((el) => el.tagName === 'SELECT' && el.offsetParent !== null)) {
        for (const option of sel.options) {
          const probe = sel.cloneNode(false);
          probe.style.cssText = 'width:auto;min-width:0;max-width:none;flex:none;position:absolute;visibility:hidden';
          probe.append(option.cloneNode(true));
          sel.parentElement.append(probe);
          const needed = probe.getBoundingClientRect().width;
          probe.remove();
          if (needed > sel.getBoundingClientRect().width + 0.5) bad.push(`${sel.name || sel.id}: "${option.text}" cut (${Math.round(needed)} px wanted, ${Math.round(sel.getBoundingClientRect().width)} drawn)`);
        }
      }
      return bad;
    };
  });
}

// Every button, field, list and section heading of the side panel, in every tab (its folded
// sections opened): inside the window's width and the one that gets a click at its middle
// (after scrolling the panel to it).
async function reachable(page) {
  await installCutLists(page);
  const out = [];
  for (const name of ['part', 'stock', 'tools', 'ops', 'post']) {
    await tab(page, name);
    const found = await page.evaluate(() => {
      const bad = [];
      // Every section folded away (an operation's heights) opened: its controls must be in
      // reach too, and its heading is one of the controls.
      for (const d of document.querySelectorAll('#panel details')) d.open = true;
      const all = [...document.querySelectorAll('#panel button, #panel input, #panel select, #panel label.button, #panel summary')].filter((el) => el.offsetParent !== null && !(el.type === 'file'));
      for (const el of all) {
        el.scrollIntoView({ block: 'nearest', inline: 'nearest' });
        const r = el.getBoundingClientRect();
        const x = r.left + r.width / 2, y = r.top + r.height / 2;
        const hit = document.elementFromPoint(x, y);
        const ok = r.left >= 0 && r.right <= window.innerWidth && r.width > 0 && hit && (hit === el || el.contains(hit) || hit.contains(el) || hit.closest('label') === el.closest('label'));
        if (!ok) bad.push(`${el.id || el.name || el.textContent.trim().slice(0, 20)} at ${Math.round(r.left)}–${Math.round(r.right)} of ${window.innerWidth} (hit ${hit?.id || hit?.tagName})`);
      }
      bad.push(...window.cutLists(all));
      return { bad, count: all.length, scroll: document.scrollingElement.scrollWidth - window.innerWidth, panel: document.getElementById('panel').scrollWidth - document.getElementById('panel').clientWidth };
    });
    out.push({ tab: name, ...found });
  }
  return out;
}

test('every control of the side panel is in reach at 1280×720, 1400×900 and 1920×1080, before and after Generate, and the results never displace the settings', async () => {
  for (const [width, height] of [[1280, 720], [1400, 900], [1920, 1080]]) {
    const context = await browser.newContext({ acceptDownloads: true, viewport: { width, height } });
    context.setDefaultTimeout(PATIENCE);
    const page = await context.newPage();
    await page.goto(base);
    await page.waitForSelector('body[data-ready="true"]');
    await page.waitForFunction(() => !document.getElementById('generate').disabled);
    const settings = async () => page.evaluate(() => document.getElementById('settings').getBoundingClientRect().height);
    const before = await settings();
    for (const t of await reachable(page)) {
      assert.deepEqual(t.bad, [], `${width}×${height}, ${t.tab} tab: out of reach`);
      assert.ok(t.count > 5, `${width}×${height}, ${t.tab}: ${t.count} controls`);
      assert.ok(t.scroll <= 0 && t.panel <= 0, `${width}×${height}, ${t.tab}: scrolls sideways (${t.scroll}, ${t.panel})`);
    }
    await page.click('#generate');
    assert.equal(await waitForGenerated(page), 'ok');
    await page.screenshot({ path: path.join(shots, `reach-${width}x${height}.png`) });
    // The operations' names on the removal-rate plot whole and apart.
    const labels = await mrrLabels(page);
    assert.deepEqual(labels.map((l) => l.text), labels.map((l) => l.name), `${width}×${height}: names shortened`);
    assert.equal(labels.length, 3, `${width}×${height}: ${JSON.stringify(labels)}`);
    for (const t of await reachable(page)) assert.deepEqual(t.bad, [], `${width}×${height} after Generate, ${t.tab} tab: out of reach`);
    // The results have a pane of their own: the settings keep their height.
    assert.equal(await settings(), before, `${width}×${height}: the settings lost height after Generate`);
    await context.close();
  }
});

test('the words are a machinist\'s: no paper symbol or section in the forms, the paper named in a tooltip', async () => {
  const { page, context } = await openPage();
  // At the narrowest screen the reach test uses, every kind's lists show their choices whole.
  await page.setViewportSize({ width: 1280, height: 720 });
  await installCutLists(page);
  const words = () => page.evaluate(() => {
    const visible = (el) => [...el.childNodes].map((n) => (n.nodeType === 3 ? n.textContent : n.tagName === 'SELECT' ? [...n.options].map((o) => o.text).join(' ') : n.tagName === 'INPUT' ? '' : n.textContent)).join(' ');
    return [...document.querySelectorAll('#settings label, #settings .hint, #settings option, #op-kind option, #run, #sim, #view-tools')].map(visible);
  });
  const texts = await words();
  // Every kind's form (made when an operation of it is picked).
  await tab(page, 'ops');
  for (const kind of await page.$$eval('#op-kind option', (os) => os.map((o) => o.value))) {
    await page.selectOption('#op-kind', kind);
    await page.click('#op-add');
    await page.waitForFunction((k) => document.querySelector('#op-fields').dataset.kind === k, kind);
    texts.push(...(await words()));
    assert.deepEqual(await page.evaluate(() => window.cutLists([...document.querySelectorAll('#panel select')])), [], `${kind}: lists cut at 1280 px`);
    // The paper behind a setting is one hover away.
    if (kind === 'finishRaster') assert.match(await page.getAttribute('#op-fields label:has([name=op-builder])', 'title'), /seed 001 §3\.3/);
  }
  assert.ok(texts.length > 100, `${texts.length} texts`);
  for (const t of texts) assert.doesNotMatch(t, /seed \d|§|δ|γ|CL z-map|octant/i, t);
  await context.close();
});

test('a sheet\'s tabs and lead arcs are set in the page, a through cut\'s depth is shown, and the tab height is measured from the sheet\'s bottom', async () => {
  const { page, context, errors } = await openPage();
  await page.click('#use-sample-drawing');
  await page.waitForFunction(() => document.body.dataset.kind === 'drawing');
  await tab(page, 'ops');
  assert.equal(await page.textContent('#through-depth'), '6.20 mm');
  await page.fill('input[name=op-tabs-width]', '6');
  await page.fill('input[name=op-tabs-height]', '2');
  await page.fill('input[name=op-leadRadius]', '2.5');
  await tab(page, 'part');
  await page.fill('input[name=thickness]', '10');
  await page.press('input[name=thickness]', 'Tab');
  await tab(page, 'ops');
  assert.equal(await page.textContent('#through-depth'), '10.20 mm');
  const op = await page.evaluate(() => window.swarf.jobs.drawing.operations[0]);
  assert.deepEqual([op.tabs.width, op.tabs.height, op.leadRadius], [6, 2, 2.5]);
  await page.click('#generate');
  await generated(page);
  // The tab stands 2 mm over the 10 mm sheet's bottom: its top at Z−8.
  const zs = [...(await page.evaluate(() => window.swarf.gcode)).matchAll(/Z(-?[\d.]+)/g)].map((m) => Number(m[1]));
  assert.ok(zs.includes(-10.2) && zs.includes(-8), `depths ${[...new Set(zs)].sort((a, b) => a - b).slice(0, 6)}`);
  assert.deepEqual(errors, []);
  await context.close();
});

test('the program written again in inches after Generate, without planning again: G20, the same moves, rs274 reads it', async () => {
  const { page, context, errors } = await openPage();
  await onlyRaster(page);
  await page.fill('input[name=op-stepover]', '3');
  await page.click('#generate');
  await generated(page);
  const mm = await page.evaluate(() => window.swarf.gcode);
  await tab(page, 'post');
  const before = await page.evaluate(() => Number(document.body.dataset.posted ?? 0));
  await page.selectOption('select[name=gcodeUnits]', 'inch');
  await page.waitForFunction((n) => Number(document.body.dataset.posted ?? 0) > n, before);
  assert.equal(await page.textContent('#stage'), 'done', 'no Generate ran again');
  assert.match(await page.textContent('#message'), /written again for LinuxCNC in inches/);
  const [download] = await Promise.all([page.waitForEvent('download'), page.click('#download')]);
  const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'swarf-e2e-inch-'));
  const program = path.join(dir, download.suggestedFilename());
  await download.saveAs(program);
  const inch = fs.readFileSync(program, 'utf8');
  assert.match(inch, /^G20$/m);
  // The same moves: LinuxCNC reads every feed of the inch program where the mm program's is,
  // over 25.4, to the inch's resolution.
  const tbl = path.join(dir, 'tool.tbl');
  fs.writeFileSync(tbl, toolTable(await page.evaluate(() => window.swarf.tools)));
  const feeds = (file) => execFileSync('rs274', ['-g', '-t', tbl, file], { cwd: dir, env: { ...process.env, HOME: dir }, encoding: 'utf8', maxBuffer: 1 << 28 })
    .split('\n').filter((l) => l.includes('STRAIGHT_FEED(')).map((l) => l.match(/\(([^)]*)\)/)[1].split(',').slice(0, 3).map(Number));
  fs.writeFileSync(path.join(dir, 'mm.ngc'), mm);
  const [a, b] = [feeds(path.join(dir, 'mm.ngc')), feeds(program)];
  // (Moves shorter than the inch's last digit are not written: a few hundred of the raster's
  // steps at cliffs.)
  const slack = Math.abs(a.length - b.length) + 5;
  assert.ok(a.length > 1000 && slack < a.length / 50, `${a.length} and ${b.length} feeds`);
  for (let k = 0; k < b.length; k += 7) {
    const at = Math.round((k * a.length) / b.length);
    const near = a.slice(Math.max(0, at - slack), at + slack).some((p) => p.every((v, i) => Math.abs(v / 25.4 - b[k][i]) <= 0.00011));
    assert.ok(near, `feed ${k}: ${b[k]} in, the mm program's ${a[at]} mm`);
  }
  assert.deepEqual(errors, []);
  await context.close();
});

test('the simulation a machinist expects: the tool shown, the path cut apart from the path to come, a move at a time, each operation shown or hidden, view presets, the program\'s lines following the scrubber, a real removal rate, a cycle time that adds up', async () => {
  const { page, context, errors } = await openPage();
  await page.click('#generate');
  await generated(page);
  const view = (fn, arg) => page.evaluate(fn, arg);
  // The tool: its shape at the scrubber's place, drawn over the stock.
  const toolShown = async (on) => {
    await view((v) => { window.swarfView.show.tool = v; window.swarfView.draw(); }, on);
    return pixelCounts(page);
  };
  const moves = await page.evaluate(() => window.swarf.result.sim.times.length - 1);
  await page.evaluate(() => { const s = document.getElementById('scrub'); s.value = String(Number(s.max) / 3); s.dispatchEvent(new Event('input')); });
  await page.waitForFunction((n) => Number(document.body.dataset.simMoves) > 0 && Number(document.body.dataset.simMoves) < n, moves);
  assert.ok(await view(() => window.swarfView.tool?.at !== null && window.swarfView.tool !== null));
  const [withTool, without] = [await toolShown(true), await toolShown(false)];
  assert.notDeepEqual(withTool, without, 'the tool is drawn');
  await toolShown(true);
  // The path to come is faint: a little way into the roughing, few of its lines are in its full
  // colour, and all are at the end (the stock, whose material left is blue too, and the later
  // operations hidden).
  await view(() => { window.swarfView.show.stock = false; window.swarfView.setHiddenOps([1, 2]); });
  await page.evaluate(() => { const s = document.getElementById('scrub'); s.value = String(window.swarf.result.sim.times[window.swarf.result.summary.operationStarts[1]] / 20); s.dispatchEvent(new Event('input')); });
  await page.waitForFunction((n) => Number(document.body.dataset.simMoves) < n / 20, moves);
  const early = await pathPixels(page);
  await page.evaluate(() => { const s = document.getElementById('scrub'); s.value = s.max; s.dispatchEvent(new Event('input')); });
  await page.waitForFunction((n) => Number(document.body.dataset.simMoves) === n, moves);
  const end = await pathPixels(page);
  assert.ok(end > 2 * early, `the roughing's pixels in its full colour early on ${early}, at the end ${end}`);
  await view(() => { window.swarfView.show.stock = true; window.swarfView.setHiddenOps([]); });
  // A move at a time, back and on.
  await page.evaluate(() => { const s = document.getElementById('scrub'); s.value = String(Number(s.max) / 2); s.dispatchEvent(new Event('input')); });
  await page.waitForFunction((n) => Number(document.body.dataset.simMoves) > 0.3 * n && Number(document.body.dataset.simMoves) < 0.7 * n, moves);
  const at = Number(await page.evaluate(() => document.body.dataset.simMoves));
  await page.click('#step-on');
  await page.waitForFunction((n) => Number(document.body.dataset.simMoves) === n + 1, at);
  await page.click('#step-back');
  await page.click('#step-back');
  await page.waitForFunction((n) => Number(document.body.dataset.simMoves) === n - 1, at);
  // The program's pane follows: its marked line is the line of the move the tool is at the end
  // of (the last one done).
  await page.click('#result-tabs [data-result="gcode"]');
  await page.waitForSelector('#gcode .line.current');
  const current = await page.evaluate(() => {
    const k = Number(document.body.dataset.simMoves) - 1, r = window.swarf.result;
    return { shown: document.querySelector('#gcode .line.current').textContent, line: r.gcode.split('\n')[r.moveLines[k]], n: r.moveLines[k] };
  });
  assert.ok(current.shown.endsWith(current.line), `${current.shown} against line ${current.n + 1}: ${current.line}`);
  // A click on a line takes the scrubber to its move: a line drawn, not the current one, that
  // holds a move. (Found by its line number: Playwright scrolls it into sight before the click,
  // the pane draws its rows anew, and a locator by position would then name another line.)
  const clicked = await page.evaluate(() => {
    const moves = new Set(window.swarf.result.moveLines);
    return [...document.querySelectorAll('#gcode .line:not(.current)')].map((row) => Number(row.dataset.line)).filter((k) => moves.has(k))[3];
  });
  assert.ok(Number.isInteger(clicked), 'a line with a move is drawn in the pane');
  // Clicked where it is drawn: a pointer click would first scroll the pane, which draws its
  // rows anew under the pointer (on a busy machine the click then met another row or none).
  await page.evaluate((n) => document.querySelector(`#gcode .line[data-line="${n}"]`).click(), clicked);
  await page.waitForFunction((n) => document.querySelector('#gcode .line.current')?.dataset.line === String(n), clicked);
  // (to the end of the first move written on that line or after it)
  const [moved, before] = await page.evaluate(() => { const k = Number(document.body.dataset.simMoves) - 1, l = window.swarf.result.moveLines; return [l[k], k > 0 ? l[k - 1] : -1]; });
  assert.ok(moved >= clicked && before < clicked, `the move's line ${moved} (the one before it ${before}) against the clicked ${clicked}`);
  // Each operation can be hidden from the legend; rapids and gouges in colours of their own.
  assert.match(await page.textContent('#legend'), /rough \(T1\)[\s\S]*finish shallow \(T2\)[\s\S]*rapids[\s\S]*gouge/);
  await page.evaluate(() => { const s = document.getElementById('scrub'); s.value = s.max; s.dispatchEvent(new Event('input')); });
  await page.waitForFunction((n) => Number(document.body.dataset.simMoves) === n, moves);
  await view(() => { window.swarfView.show.stock = false; });
  const shown = await pathPixels(page);
  await page.uncheck('#legend input[data-op="0"]');
  const hidden = await pathPixels(page);
  assert.ok(hidden < shown / 4, `the roughing hidden: ${hidden} of its colour's pixels against ${shown}`);
  const colours = await page.evaluate(async () => {
    const { OP_COLORS, TOOL_COLORS, RAPID_COLOR, MARK_COLORS } = await import('./viewer.js');
    return { ops: [...OP_COLORS, ...TOOL_COLORS], rapid: RAPID_COLOR, marks: MARK_COLORS };
  });
  for (const c of colours.ops) for (const other of [colours.rapid, ...colours.marks]) {
    assert.ok(Math.abs(c[0] - other[0]) + Math.abs(c[1] - other[1]) + Math.abs(c[2] - other[2]) > 0.45, `${c} is near ${other}`);
  }
  // View presets.
  await page.click('#view-tools [data-view="top"]');
  assert.ok(await view(() => window.swarfView.camera.pitch > 1.5));
  await page.click('#view-tools [data-view="front"]');
  assert.ok(await view(() => Math.abs(window.swarfView.camera.pitch) < 1e-9));
  // The removal rate is one the tools can cut at: no higher than a full slot as deep as the
  // roughing's flutes (it once read 739,947 mm³/min on a finishing job).
  const peak = Number((await page.evaluate(() => window.swarf.result.summary.operations.map((o) => o.mrrMax))).reduce((a, b) => Math.max(a, b), 0));
  const tools = await page.evaluate(() => window.swarf.tools);
  const slot = Math.max(...tools.map((t) => t.diameter * t.fluteLength * t.feedRate));
  assert.ok(peak > 1000 && peak <= slot, `peak ${peak} mm³/min against a slot's ${slot}`);
  // The cycle time adds up: the summary's parts sum to its total, which is the program head's.
  const summary = await page.evaluate(() => window.swarf.result.summary);
  const [, head, format] = (await page.evaluate(() => window.swarf.gcode)).match(/\(cycle time ([\d:]+) (m:ss|h:mm:ss)/);
  assert.equal(format, head.split(':').length === 2 ? 'm:ss' : 'h:mm:ss');
  const clock = (s) => s.split(':').reduce((a, v) => a * 60 + Number(v), 0);
  assert.equal(summary.time.reduce((a, t) => a + t.seconds, 0), clock(head));
  assert.match(await page.textContent('#stats'), new RegExp(`cycle time\\s*${head} ${format}[\\s\\S]*total\\s*${head}`));
  assert.match(await page.textContent('#sim-time'), new RegExp(`/ ${head} ${format}`));
  assert.deepEqual(errors, []);
  await context.close();
});

test('malformed drawings are answered at once in the page, the tab alive and the settings kept: nesting past any drawing, numbers past any machine, curves that would never end, a file cut short', async () => {
  const { page, context, errors } = await openPage();
  await tab(page, 'stock');
  await page.fill('input[name=marginTop]', '2.5');
  const svg = (inner) => `<svg xmlns="http://www.w3.org/2000/svg" width="100mm" height="100mm" viewBox="0 0 100 100"><rect x="10" y="10" width="60" height="40"/>${inner}</svg>`;
  const dxf = (extra, end) => `0\nSECTION\n2\nENTITIES\n0\nCIRCLE\n8\n0\n10\n20\n20\n20\n40\n8\n${extra}0\nENDSEC\n${end}`;
  for (const [name, text, said] of [
    ['deep.svg', svg('<g>'.repeat(100000) + '</g>'.repeat(100000)), /elements nest deeper than 256/],
    ['scale.svg', svg('<g transform="scale(1e200) scale(1e200)"><circle r="5"/></g>'), /larger than any machine/],
    ['ellipse.dxf', dxf('0\nELLIPSE\n8\n0\n10\n5\n20\n5\n11\n2\n21\n0\n40\n0.5\n41\n0\n42\n1e300\n', '0\nEOF\n'), /ELLIPSE whose start or end parameter .* is not an angle/],
    ['cut.dxf', dxf('', ''), /without its EOF marker.*cut short/],
  ]) {
    await page.setInputFiles('#file', { name, mimeType: 'application/octet-stream', buffer: Buffer.from(text) });
    await page.waitForFunction((n) => document.getElementById('message').textContent.startsWith(n), name, { timeout: PATIENCE });
    const message = await page.textContent('#message');
    assert.match(message, said, message);
    assert.equal(await page.getAttribute('#message', 'class'), 'error');
    assert.equal(await page.textContent('#part-name'), 'sample part');
    assert.equal(await page.isEnabled('#generate'), true);
    assert.equal(await page.inputValue('input[name=marginTop]'), '2.5');
  }
  // A drawing with a circle of radius 0 is read, and the left-out circle named.
  await page.setInputFiles('#file', { name: 'zero.dxf', mimeType: 'application/octet-stream', buffer: Buffer.from(dxf('0\nCIRCLE\n8\nHOLES\n10\n5\n20\n5\n40\n0\n', '0\nEOF\n')) });
  await page.waitForFunction(() => /left out/.test(document.getElementById('drawing-size').textContent), null, { timeout: PATIENCE });
  assert.match(await page.textContent('#drawing-size'), /left out: 1 circles with a radius ≤ 0 on layer HOLES/);
  assert.match(await page.textContent('#message'), /^The drawing left out: 1 circles with a radius ≤ 0 on layer HOLES/);
  assert.equal(await page.getAttribute('#message', 'class'), 'warning');
  // A drawing 3 mm across, in a file that names no unit: a note beside its size says what it
  // would be in inches, until it is read in inches.
  await page.setInputFiles('#file', { name: 'tiny.dxf', mimeType: 'application/octet-stream', buffer: Buffer.from('0\nSECTION\n2\nENTITIES\n0\nCIRCLE\n8\n0\n10\n5\n20\n5\n40\n1.5\n0\nENDSEC\n0\nEOF\n') });
  await page.waitForFunction(() => /Read in inches it would be/.test(document.getElementById('drawing-notes').textContent), null, { timeout: PATIENCE });
  assert.match(await page.textContent('#drawing-notes'), /the drawing is 3 × 3 mm, under 5 mm across: is the file in another unit\? Read in inches it would be 76\.2 mm across/);
  await tab(page, 'part');
  await page.selectOption('select[name=drawingUnits]', 'inch');
  await page.waitForFunction(() => document.getElementById('drawing-notes').textContent === '' && /76\.2 × 76\.2/.test(document.getElementById('drawing-size').textContent), null, { timeout: PATIENCE });
  assert.deepEqual(errors, []);
  await context.close();
});

// What each case of ../shared/data/bad/ must answer, by its number (tests/bad_cases.tsv, which
// tests/bad_input.rs reads too): an error holding the words, or a program with a warning.
const BAD = fs.readFileSync(path.resolve(root, '../tests/bad_cases.tsv'), 'utf8').trim().split('\n').slice(1).map((row) => {
  // The page says where a setting is in its own words (issue 55), where the table gives them.
  const [tags, level, words, page] = row.split('\t');
  return { tags: tags.split(' '), level, words: page || words };
});

test('every case of the shared bad files and jobs is answered in the page: the message in its colour, the tab alive, the settings kept', async (t) => {
  const dir = path.resolve(root, '../../shared/data/bad');
  if (!fs.existsSync(path.join(dir, 'MANIFEST.tsv'))) return t.skip('../shared/data/bad is absent');
  const { page, context, errors } = await openPage();
  let crashed = false;
  page.on('crash', () => { crashed = true; });
  const said = () => page.evaluate(() => ({ text: document.getElementById('message').textContent, level: document.getElementById('message').className, name: document.getElementById('part-name').textContent, drawing: document.getElementById('drawing-size').textContent }));
  // The page's answer to a file or a job: its count of answers (`data-answered`) goes up.
  const answer = async (input, file) => {
    const before = await page.evaluate(() => Number(document.body.dataset.answered ?? 0));
    await page.setInputFiles(input, file);
    await page.waitForFunction((n) => Number(document.body.dataset.answered ?? 0) > n, before);
    return said();
  };
  const take = (file) => answer('#file', file);
  const loadJob = (file) => answer('#load-job', file);
  // Two cases kept out of the folder: the Khronos Duck, 1.7 m long by its glTF, under the
  // sample's mould job (its roughing's levels would read 24 billion level-map nodes, and its
  // raster finish millions of points: refused before the work, naming the settings), and kiri_pocket-test's facets 3,000 times over (read once, a note).
  const duck = path.resolve(dir, '../meshes/tm_Duck.glb');
  if (fs.existsSync(duck)) {
    const read = await take(duck);
    assert.notEqual(read.level, 'error', read.text);
    await page.click('#generate');
    assert.equal(await waitForGenerated(page), 'failed');
    assert.match(await page.textContent('#message'), /a step-down of 2 mm.*million level-map nodes.*check the part's units/s);
  }
  const pocket = fs.readFileSync(path.resolve(dir, '../meshes/kiri_pocket-test.stl'), 'utf8');
  const facets = pocket.slice(pocket.indexOf('facet'), pocket.lastIndexOf('endsolid'));
  const copies = path.join(fs.mkdtempSync(path.join(os.tmpdir(), 'swarf-e2e-copies-')), 'copies.stl');
  fs.writeFileSync(copies, `solid copies\n${facets.repeat(3000)}endsolid copies\n`);
  const read = await take(copies);
  assert.equal(read.name, 'copies.stl', read.text);
  await tab(page, 'part');
  assert.match(await page.textContent('#part-notes'), /triangles were copies/);
  assert.equal(await page.evaluate(() => 1 + 1), 2);
  const rows = fs.readFileSync(path.join(dir, 'MANIFEST.tsv'), 'utf8').split('\n').slice(1).filter((l) => l.trim());
  const failures = [];
  for (const row of rows) {
    const [file, job] = row.split('\t');
    const { level, words } = BAD.find(({ tags }) => tags.includes(file.slice(0, 3))) ?? {};
    if (!words) { failures.push(`${file}: a new case; say what it must answer`); continue; }
    const start = Date.now();
    let got;
    if (job.startsWith('job_')) {
      // The row's job, a setting of the user's, then the file.
      await loadJob(path.join(dir, job));
      await tab(page, 'post');
      await page.selectOption('select[name=dialect]', 'grbl');
      got = await take(path.join(dir, file));
      if (got.level !== 'error') {
        await page.click('#generate');
        const state = await waitForGenerated(page);
        const after = await said();
        got = { ...after, text: `${got.text}\n${after.text}\n${got.drawing}\n${await page.textContent('#warnings')}`, level: state === 'ok' ? got.level : 'error' };
      }
      if (await page.inputValue('select[name=dialect]') !== 'grbl') failures.push(`${file}: the controller chosen was not kept`);
    } else {
      // The job is the case, run on the part its row names.
      const part = path.resolve(dir, job.split('part: ')[1].replace(/\)$/, ''));
      const read = await take(part);
      if (read.level === 'error') { failures.push(`${file}: its part ${part} did not read: ${read.text}`); continue; }
      got = await loadJob(path.join(dir, file));
      if (got.level !== 'error' || !got.text.includes(words)) {
        await page.click('#generate');
        const state = await waitForGenerated(page);
        got = { ...(await said()), level: state === 'ok' ? 'ok' : 'error' };
      }
    }
    const took = (Date.now() - start) / 1000;
    if (crashed) { failures.push(`${file}: the tab died`); break; }
    if (got.level !== level || !got.text.includes(words)) failures.push(`${file}: ${got.level}: ${got.text.slice(0, 300)}`);
    // Alive: the page answers at once, and Generate is offered again.
    assert.equal(await page.evaluate(() => 1 + 1), 2);
    assert.equal(await page.isEnabled('#generate'), true, file);
    console.log(`${file}: ${got.level} in ${took.toFixed(1)} s`);
  }
  assert.deepEqual(failures, []);
  assert.deepEqual(errors, []);
  await context.close();
});

test('at 1280×720 the settings have most of the side panel, and a long message is shown whole over the view', async () => {
  const context = await browser.newContext({ viewport: { width: 1280, height: 720 } });
  context.setDefaultTimeout(PATIENCE);
  const page = await context.newPage();
  await page.goto(base);
  await page.waitForSelector('body[data-ready="true"]');
  await page.waitForFunction(() => !document.getElementById('generate').disabled);
  await tab(page, 'ops');
  // Once 264 px of 720 (the header, the drop zone, two rows of buttons and the message box
  // took the rest): now at least 60 % of the window.
  const settings = await page.evaluate(() => document.getElementById('settings').getBoundingClientRect().height);
  assert.ok(settings >= 0.6 * 720, `the settings pane is ${settings} px of 720`);
  // The run bar's buttons on one row, inside the panel.
  const row = await page.evaluate(() => ({ panel: document.getElementById('panel').getBoundingClientRect().right, buttons: ['generate', 'cancel', 'download', 'undo', 'redo'].map((id) => document.getElementById(id).getBoundingClientRect()).map((r) => [r.top, r.right]) }));
  assert.ok(row.buttons.every(([top, right]) => Math.abs(top - row.buttons[0][0]) < 2 && right <= row.panel - 8), JSON.stringify(row));
  // A long message (a refused file's) over the view, whole, clear of the panel.
  const before = settings;
  await page.setInputFiles('#file', { name: 'broken.stl', mimeType: 'model/stl', buffer: Buffer.from(`solid x\n${'facet normal 0 0 1\n outer loop\n vertex 0 0 0\n'.repeat(3)}`) });
  await page.waitForFunction(() => document.getElementById('message').textContent.length > 0);
  const m = await page.evaluate(() => { const e = document.getElementById('message'); const r = e.getBoundingClientRect(); return { text: e.textContent, left: r.left, bottom: r.bottom, whole: e.scrollHeight <= e.clientHeight + 1, panel: document.getElementById('panel').getBoundingClientRect().right }; });
  assert.ok(m.whole && m.left >= m.panel && m.bottom <= 720, JSON.stringify(m));
  assert.equal(await page.evaluate(() => document.getElementById('settings').getBoundingClientRect().height), before, 'a message takes nothing from the settings');
  await context.close();
});
