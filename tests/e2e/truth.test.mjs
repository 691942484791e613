// What the page and the engine show is what the machine will do (issue 55): the view draws the
// part as the core places it, a stock box the part sticks out of is marked where it is typed,
// a click is never lost to a list refreshed under it, and an unsafe program never leaves the
// engine unless the caller asks for it.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import fs from 'node:fs';
import { PATIENCE, tab, frame, openPage, addTool, plateStl, waitForGenerated, onlyRaster, soleOperation } from './harness.mjs';

// Boxes ([min, max] each) as one binary STL, 12 triangles a box.
function boxesStl(boxes) {
  const faces = [[0, 2, 3], [0, 3, 1], [4, 5, 7], [4, 7, 6], [0, 1, 5], [0, 5, 4], [2, 6, 7], [2, 7, 3], [0, 4, 6], [0, 6, 2], [1, 3, 7], [1, 7, 5]];
  const buf = Buffer.alloc(84 + boxes.length * faces.length * 50);
  buf.writeUInt32LE(boxes.length * faces.length, 80);
  let k = 0;
  const corners = [];
  for (const [lo, hi] of boxes) {
    const v = (i) => [0, 1, 2].map((a) => ((i >> a) & 1 ? hi[a] : lo[a]));
    for (const f of faces) {
      const o = 84 + k++ * 50 + 12;
      f.forEach((i, j) => v(i).forEach((c, a) => { buf.writeFloatLE(c, o + j * 12 + a * 4); }));
      corners.push(...f.map(v));
    }
  }
  return { bytes: buf, corners };
}

// The placement the core documents (mesh::placement), written again here: the file's axis
// `up` turned to +Z, a turn of `rotation` degrees about Z, the top at Z0 centred in XY.
function place(corners, up, rotation) {
  const turn = { z: ([x, y, z]) => [x, y, z], y: ([x, y, z]) => [x, -z, y], '-y': ([x, y, z]) => [x, z, -y], x: ([x, y, z]) => [-z, y, x], '-x': ([x, y, z]) => [z, y, -x], '-z': ([x, y, z]) => [x, -y, -z] }[up];
  const quarter = { 0: ([x, y, z]) => [x, y, z], 90: ([x, y, z]) => [-y, x, z], 180: ([x, y, z]) => [-x, -y, z], 270: ([x, y, z]) => [y, -x, z] }[rotation];
  const placed = corners.map((c) => quarter(turn(c)));
  const min = [0, 1, 2].map((a) => Math.min(...placed.map((p) => p[a]))), max = [0, 1, 2].map((a) => Math.max(...placed.map((p) => p[a])));
  const shift = [-(min[0] + max[0]) / 2, -(min[1] + max[1]) / 2, -max[2]];
  const moved = placed.map((p) => p.map((v, a) => v + shift[a]));
  const mean = [0, 1, 2].map((a) => moved.reduce((s, p) => s + p[a], 0) / moved.length);
  return { bounds: [...min.map((v, a) => v + shift[a]), ...max.map((v, a) => v + shift[a])], mean };
}

const near = (a, b, what) => a.forEach((v, k) => assert.ok(Math.abs(v - b[k]) < 1e-3, `${what}: ${a} against ${b}`));

// The part drawn, once the page has shown it `after` times.
async function drawn(page, after) {
  await page.waitForFunction((n) => Number(document.body.dataset.parts ?? 0) >= n, after);
  await frame(page);
  return page.evaluate(() => ({ ...window.swarfView.part.drawn, core: window.swarf.part.bounds, shown: Number(document.body.dataset.parts) }));
}

test('the view draws the part as the core places it: every up axis and turn of a part with no symmetry, and after Generate', async () => {
  const { page, context, errors } = await openPage();
  // A block with a tower at one corner: no turn or flip leaves it as it was.
  const { bytes, corners } = boxesStl([[[0, 0, 0], [40, 20, 10]], [[0, 0, 10], [12, 6, 27]]]);
  let shown = Number(await page.evaluate(() => document.body.dataset.parts));
  await page.setInputFiles('#file', { name: 'tower.stl', mimeType: 'model/stl', buffer: bytes });
  let now = await drawn(page, shown + 1);
  near(now.mean, place(corners, 'z', 0).mean, 'as read');
  const means = new Set();
  for (const up of ['z', 'y', 'x', '-z', '-y', '-x']) {
    for (const rotation of [0, 90, 180, 270]) {
      shown = now.shown;
      // Each choice shows the part again (a turn to 0 from 270 too); the up axis first.
      if (rotation === 0) await page.selectOption('select[name=upAxis]', up);
      else await page.selectOption('select[name=rotation]', String(rotation));
      now = await drawn(page, shown + 1);
      const want = place(corners, up, rotation);
      near(now.mean, want.mean, `${up} turned ${rotation}: the mean of the drawn corners`);
      near(now.bounds, want.bounds, `${up} turned ${rotation}: the drawn bounds`);
      near(now.core, want.bounds, `${up} turned ${rotation}: the core's bounds`);
      means.add(now.mean.map((v) => v.toFixed(2)).join(' '));
    }
    if (up !== '-x') {
      shown = now.shown;
      await page.selectOption('select[name=rotation]', '0');
      now = await drawn(page, shown + 1);
    }
  }
  assert.equal(means.size, 24, 'every placement is drawn apart from the others');
  // Upside down, then Generate: the paths are drawn over the part as it is machined.
  shown = now.shown;
  await page.selectOption('select[name=upAxis]', '-z');
  now = await drawn(page, shown + 1);
  await tab(page, 'ops');
  await page.evaluate(() => { const ops = window.swarf.jobs.part.operations; ops.splice(1); });
  await page.click('#generate');
  assert.ok(['ok', 'problem'].includes(await waitForGenerated(page)), await page.textContent('#message'));
  await frame(page);
  const after = await page.evaluate(() => window.swarfView.part.drawn);
  const rot = Number(await page.inputValue('select[name=rotation]'));
  near(after.mean, place(corners, '-z', rot).mean, 'after Generate');
  assert.deepEqual(errors, []);
  await context.close();
});

test('a stock box smaller than the part is marked at its field as it is typed, by how much on which side, and Generate says so', async () => {
  const { page, context, errors } = await openPage();
  await tab(page, 'stock');
  // The sample is 90 × 60 × 25.3 mm; a 40 × 40 box under it.
  await page.fill('input[name=sizeBox]', '-20, -20, -30, 20, 20, 1');
  await page.press('input[name=sizeBox]', 'Tab');
  await page.waitForFunction(() => /sticks out of the stock/.test(document.querySelector('input[name=sizeBox]').closest('label').nextElementSibling?.textContent ?? ''));
  const said = await page.evaluate(() => document.querySelector('input[name=sizeBox]').closest('label').nextElementSibling.textContent);
  assert.match(said, /25\.000 mm at -X, 25\.000 mm at \+X, 10\.000 mm at -Y, 10\.000 mm at \+Y/);
  assert.equal(await page.getAttribute('input[name=sizeBox]', 'aria-invalid'), 'true');
  await page.click('#generate');
  await page.waitForFunction(() => document.getElementById('message').className === 'error');
  assert.match(await page.textContent('#message'), /sticks out of the stock/);
  // A box that holds it: the mark goes.
  await page.fill('input[name=sizeBox]', '-50, -35, -30, 50, 35, 1');
  await page.press('input[name=sizeBox]', 'Tab');
  await page.waitForFunction(() => document.querySelector('input[name=sizeBox]').getAttribute('aria-invalid') !== 'true');
  assert.deepEqual(errors, []);
  await context.close();
});

test('a click on a list just after typing a name lands: the operations, the holes and the tools', async () => {
  const { page, context, errors } = await openPage();
  await page.setInputFiles('#file', { name: 'plate.stl', mimeType: 'model/stl', buffer: plateStl(60, 20, 10, 20, [[10, 10, 5], [30, 10, 5], [50, 10, 5]]) });
  await page.waitForFunction(() => /plate\.stl/.test(document.body.textContent) && !document.getElementById('generate').disabled);
  await tab(page, 'tools');
  const drill = await addTool(page, 'drill', 5, 30);
  // The tools: rename the drill, then click the first tool at once.
  await page.fill('input[name=toolName]', 'jobber drill');
  await page.click('#tool-list option:nth-child(1)');
  await page.waitForFunction(() => window.swarf.selected.tool === 0);
  assert.equal(await page.evaluate((n) => window.swarf.tools.find((t) => t.number === n).name, drill), 'jobber drill');
  await tab(page, 'ops');
  await page.selectOption('#op-kind', 'drill');
  await page.click('#op-add');
  await page.selectOption('select[name=op-tool]', String(drill));
  await page.click('#find-holes');
  await page.waitForFunction(() => document.querySelectorAll('#hole-list li').length === 3);
  // The holes: three renames, each followed at once by a click on a hole.
  for (const k of [0, 1, 2]) {
    await page.fill('input[name=op-name]', `drill pass ${k}`);
    await page.click(`#hole-list li:nth-child(${k + 1})`);
    await page.waitForFunction((n) => document.querySelectorAll('#hole-list li.picked').length === n, k + 1);
  }
  assert.equal(await page.evaluate(() => window.swarf.jobs.part.operations.at(-1).holes.length), 3, 'a hole was left out');
  assert.equal(await page.evaluate(() => window.swarf.jobs.part.operations.at(-1).name), 'drill pass 2');
  // The operations: rename, then click the first operation at once.
  const count = await page.locator('#op-list li').count();
  await page.fill('input[name=op-name]', 'drill the three');
  await page.click('#op-list li:nth-child(1) .op-name');
  await page.waitForFunction(() => window.swarf.selected.part === 0);
  assert.equal(await page.locator('#op-list li').count(), count);
  assert.match(await page.textContent(`#op-list li:nth-child(${count})`), /drill the three/);
  assert.deepEqual(errors, []);
  await context.close();
});

test('an unsafe program never leaves the engine quietly: run rejects naming the problem unless allowUnsafe, whose warning fits a control\'s line', async () => {
  const { page, context, errors } = await openPage();
  const out = await page.evaluate(async () => {
    const { createEngine } = await import('./swarf.js');
    const engine = await createEngine({ workers: 1, warmUp: false });
    const job = engine.defaultJob();
    // The shallow finish alone on the stock's rectangle, its ball with 20 mm of flutes: 26 mm
    // deep in the raw block at the stock's edges, its body rubs.
    const finish = job.operations.find((o) => o.kind === 'finishRaster');
    Object.assign(finish, { boundary: 'stock', slopeMax: null, stepover: 3, grid: 0.5 });
    job.tools.find((t) => t.number === finish.tool).fluteLength = 20;
    job.operations = [finish];
    const refused = await engine.run(job, engine.sample, 'sample.stl').then(() => null, (e) => ({ name: e.name, message: e.message, problem: e.problem, summary: e.result?.summary.problem }));
    const taken = await engine.run(job, engine.sample, 'sample.stl', { allowUnsafe: true });
    engine.close();
    return { refused, problem: taken.summary.problem, head: taken.gcode.split('\n').slice(0, 12) };
  });
  assert.ok(out.refused, 'the unsafe program was handed out');
  assert.equal(out.refused.name, 'UnsafeProgramError');
  assert.match(out.refused.message, /not safe to run: .*bury the tool/);
  assert.equal(out.refused.problem, out.problem);
  assert.equal(out.refused.summary, out.problem);
  // The warning: the lines before the program's title and its "generated by swarf" line.
  const warning = out.head.slice(0, out.head.findIndex((l) => /generated by swarf/.test(l)) - 1);
  assert.match(warning[0], /^\(WARNING: NOT SAFE TO RUN: /);
  assert.ok(warning.length > 1, warning.join('\n'));
  for (const line of warning) assert.ok(line.length <= 70 && /^\(.*\)$/.test(line), `a warning line of ${line.length} characters: ${line}`);
  assert.match(warning.join(' '), /bury the tool/);
  assert.deepEqual(errors, []);
  await context.close();
});

test('under a strict Content-Security-Policy the engine starts, and a policy that blocks the wasm says so by name', async () => {
  const { page, context, errors } = await openPage();
  // Every response of the page's server with the policy `csp`, as a server sets it for a site.
  const tryPolicy = async (csp) => {
    await page.unroute('**/*');
    await page.route('**/*', async (route) => {
      const url = new URL(route.request().url());
      if (url.pathname === '/csp.html') {
        await route.fulfill({ status: 200, headers: { 'content-type': 'text/html', 'content-security-policy': csp }, body: '<!doctype html><html><body><script type="module" src="csp.js"></script></body></html>' });
        return;
      }
      if (url.pathname === '/csp.js') {
        const body = "import { createEngine } from './swarf.js';\ncreateEngine({ workers: 1, warmUp: false }).then((e) => { document.body.dataset.said = `started: ${e.defaults.job.operations.length} operations`; e.close(); }, (e) => { document.body.dataset.said = `failed: ${e.message}`; });\n";
        await route.fulfill({ status: 200, headers: { 'content-type': 'text/javascript', 'content-security-policy': csp }, body });
        return;
      }
      const response = await route.fetch();
      await route.fulfill({ response, headers: { ...response.headers(), 'content-security-policy': csp } });
    });
    await page.goto(new URL('csp.html', page.url()).href);
    await page.waitForFunction(() => document.body.dataset.said, null, { timeout: PATIENCE });
    return page.evaluate(() => document.body.dataset.said);
  };
  const strict = await tryPolicy("default-src 'none'; script-src 'self' 'wasm-unsafe-eval'; worker-src 'self'; connect-src 'self'");
  assert.match(strict, /^started: \d+ operations/);
  const noWasm = await tryPolicy("default-src 'none'; script-src 'self'; worker-src 'self'; connect-src 'self'");
  assert.match(noWasm, /^failed: blocked by the Content-Security-Policy.*wasm-unsafe-eval/);
  const noFetch = await tryPolicy("default-src 'none'; script-src 'self' 'wasm-unsafe-eval'; worker-src 'self'");
  assert.match(noFetch, /^failed: blocked by the Content-Security-Policy \(connect-src/);
  assert.deepEqual(errors, []);
  await context.close();
});

test('"Spot, drill and chamfer them" plans as a machinist: holes grouped by size, the library\'s drill that fits each, a new drill where none does, a bore where a drill would not do', async () => {
  const { page, context, errors } = await openPage();
  // φ3.175, φ6.35 and φ16 through holes in a 10 mm plate, and a φ8 recess 0.635 mm deep
  // (shallower than a spot's cone); the library: the φ6 flat and ball, a φ6.35 drill and a
  // spot drill. A hole a jobber drill makes (φ3.175) gets a drill added; a φ16 is bored.
  await page.setInputFiles('#file', { name: 'plate.stl', mimeType: 'model/stl', buffer: plateStl(80, 20, 10, 20, [[10, 10, 3.175], [30, 10, 6.35], [50, 10, 16], [70, 10, 8, 0.635]]) });
  await page.waitForFunction(() => /plate\.stl/.test(document.body.textContent) && !document.getElementById('generate').disabled);
  await tab(page, 'tools');
  const drill = await addTool(page, 'drill', 6.35, 30);
  const spot = await addTool(page, 'spotDrill', 10, 20);
  await soleOperation(page, 'drill');
  await page.click('#find-holes');
  await page.waitForFunction(() => document.querySelectorAll('#hole-list li').length === 4);
  await page.click('#hole-preset');
  await page.waitForFunction(() => window.swarf.jobs.part.operations.length > 1);
  const { ops, tools } = await page.evaluate(() => ({ ops: window.swarf.jobs.part.operations.slice(1), tools: window.swarf.tools }));
  const all = await page.evaluate(() => window.swarf.holes.items.map((h, k) => ({ k: h.loopIndex ?? k, d: h.diameter, depth: h.top - h.bottom })));
  // The recess is found as one, and left to the milling operations.
  assert.ok(all.some((h) => Math.abs(h.d - 8) < 0.01 && Math.abs(h.depth - 0.635) < 0.01), JSON.stringify(all));
  const holes = all.filter((h) => Math.abs(h.d - 8) > 0.01);
  const idx = (d) => holes.filter((h) => Math.abs(h.d - d) < 0.01).map((h) => h.k);
  const added = tools.find((t) => t.shape === 'drill' && Math.abs(t.diameter - 3.175) < 1e-9);
  assert.ok(added, `a φ3.175 drill added to the library: ${JSON.stringify(tools)}`);
  const plan = ops.map((o) => `${o.kind}:${o.cycle ?? ''}:T${o.tool}:${o.holes.join(',')}`);
  assert.deepEqual(plan, [
    `drill:spot:T${spot}:${[...idx(3.175), ...idx(6.35)].sort((a, b) => a - b).join(',')}`,
    `drill:peck:T${added.number}:${idx(3.175).join(',')}`,
    `drill:peck:T${drill}:${idx(6.35).join(',')}`,
    `bore::T1:${idx(16).join(',')}`,
    `chamfer::T${spot}:${holes.map((h) => h.k).sort((a, b) => a - b).join(',')}`,
  ]);
  assert.match(await page.textContent('#message'), /added T\d+ \(φ3\.175 drill\) to the library/);
  assert.match(await page.textContent('#message'), /left 1 recess shallower than a spot \(φ8 0\.635 mm deep\) to the milling operations/);
  // The first operation (the one the holes were found with) off: the preset's run verified clean.
  await page.evaluate(() => { window.swarf.jobs.part.operations[0].enabled = false; });
  await page.click('#op-list li:nth-child(2) .op-name');
  await page.click('#generate');
  assert.equal(await waitForGenerated(page), 'ok', await page.textContent('#message'));
  assert.deepEqual(errors, []);
  await context.close();
});

test('once the holes are found, a peck deeper than the hole and a hole deeper than the flutes are marked as they are typed', async () => {
  const { page, context, errors } = await openPage();
  // φ6.35 through holes in a 10 mm plate, a φ6.35 drill with 30 mm flutes.
  await page.setInputFiles('#file', { name: 'plate.stl', mimeType: 'model/stl', buffer: plateStl(60, 20, 10, 20, [[10, 10, 6.35], [50, 10, 6.35]]) });
  await page.waitForFunction(() => /plate\.stl/.test(document.body.textContent) && !document.getElementById('generate').disabled);
  await tab(page, 'tools');
  const drill = await addTool(page, 'drill', 6.35, 30);
  await soleOperation(page, 'drill', drill);
  await page.selectOption('select[name=op-cycle]', 'peck');
  await page.fill('input[name=op-peck]', '20');
  // Before the holes are known nothing can be said; once found, the peck is marked.
  await page.click('#find-holes');
  await page.waitForFunction(() => document.querySelectorAll('#hole-list li').length === 2);
  await page.waitForSelector('input[name=op-peck].invalid');
  assert.match(await page.textContent('#op-fields .field-error'), /^the peck \(20 mm\) is deeper than the hole at X/);
  assert.ok(await page.evaluate(() => document.querySelector('#op-list li[data-index="0"]').classList.contains('has-problem')));
  await page.fill('input[name=op-peck]', '2');
  await page.waitForFunction(() => !document.querySelector('input[name=op-peck]').classList.contains('invalid'));
  // The drill's flutes shortened in the library: the operation's tool is marked, in the page's words.
  await tab(page, 'tools');
  await page.selectOption('#tool-list', String(await page.evaluate((n) => window.swarf.tools.findIndex((t) => t.number === n), drill)));
  await page.fill('input[name=fluteLength]', '8');
  await tab(page, 'ops');
  await page.click('#op-list li:nth-child(1) .op-name');
  await page.waitForSelector('select[name=op-tool].invalid');
  assert.match(await page.textContent('#op-editor .field-error'), new RegExp(`deeper than T${drill}'s flutes \\(8 mm\\)`));
  await page.click('#generate');
  assert.equal(await waitForGenerated(page), 'failed');
  assert.match(await page.textContent('#message'), /Operations → 'drill' → Tool: the hole at X\S+ Y\S+ is 1\d\.\d\d mm deep, deeper than T\d+'s flutes/);
  assert.deepEqual(errors, []);
  await context.close();
});

test('undo and redo every change of the settings, duplicate an operation, and the keyboard: Ctrl+Z, Ctrl+Shift+Z, Ctrl+Enter, Space', async () => {
  const { page, context, errors } = await openPage();
  await tab(page, 'ops');
  const names = () => page.evaluate(() => window.swarf.jobs.part.operations.map((o) => o.name));
  const before = await names();
  assert.ok(before.length >= 2, before.join(', '));
  assert.equal(await page.isDisabled('#undo'), true, 'nothing to undo at first');
  // Duplicate the first, then remove the second: each a step back.
  await page.click('#op-list li:nth-child(1) .op-copy');
  await page.waitForFunction((n) => window.swarf.jobs.part.operations.length === n + 1, before.length);
  assert.deepEqual(await names(), [before[0], `${before[0]} copy`, ...before.slice(1)]);
  await page.click('#op-list li:nth-child(3) .op-remove');
  await page.waitForFunction((n) => window.swarf.jobs.part.operations.length === n, before.length);
  assert.match(await page.textContent('#message'), /Removed .*Undo \(Ctrl\+Z\)/);
  // A value typed in a field: one step, however many keys.
  await page.click('#op-list li:nth-child(1) .op-name');
  await page.fill('input[name=op-name]', 'roughing first');
  await page.keyboard.press('Tab');
  await page.waitForFunction(() => window.swarf.jobs.part.operations[0].name === 'roughing first');
  // Ctrl+Z outside the fields: back through the three.
  await page.click('#op-list li:nth-child(1) .swatch');
  await page.keyboard.press('Control+z');
  await page.waitForFunction((n) => window.swarf.jobs.part.operations[0].name === n, before[0]);
  assert.equal(await page.inputValue('input[name=op-name]'), before[0], 'the form follows');
  await page.keyboard.press('Control+z');
  await page.waitForFunction((n) => window.swarf.jobs.part.operations.length === n + 1, before.length);
  await page.click('#undo');
  await page.waitForFunction((n) => window.swarf.jobs.part.operations.length === n, before.length);
  assert.deepEqual(await names(), before);
  assert.equal(await page.isDisabled('#undo'), true);
  // And forward again.
  await page.keyboard.press('Control+Shift+z');
  await page.waitForFunction((n) => window.swarf.jobs.part.operations.length === n + 1, before.length);
  await page.click('#redo');
  await page.waitForFunction((n) => window.swarf.jobs.part.operations.length === n, before.length);
  assert.equal(await page.evaluate(() => JSON.parse(localStorage.getItem('swarf.jobs')).part.operations.length), before.length, 'kept across a reload');
  // Ctrl+Enter generates; Space plays the simulation; the arrows step it.
  await page.evaluate(() => { const ops = window.swarf.jobs.part.operations; ops.splice(1); });
  await page.click('#op-list li:nth-child(1) .swatch');
  await page.keyboard.press('Control+Enter');
  assert.equal(await waitForGenerated(page), 'ok', await page.textContent('#message'));
  await page.waitForSelector('#sim:not([hidden])');
  await page.evaluate(() => { const s = document.getElementById('scrub'); s.value = '0'; s.dispatchEvent(new Event('input')); });
  await page.waitForFunction(() => document.body.dataset.simMoves === '0');
  // Focus away from the fields and buttons: on the view.
  await page.click('#view', { position: { x: 5, y: 5 } });
  await page.keyboard.press('ArrowRight');
  await page.waitForFunction(() => Number(document.body.dataset.simMoves) > 0);
  await page.keyboard.press(' ');
  await page.waitForFunction(() => document.getElementById('play').textContent === '❚❚' || Number(document.getElementById('scrub').value) >= Number(document.getElementById('scrub').max) - 1e-6);
  assert.deepEqual(errors, []);
  await context.close();
});

test('the legend\'s colours never repeat within a job of forty operations, and none looks like the rapids\' or the problems\' colours', async () => {
  const { page, context } = await openPage();
  const colours = await page.evaluate(async () => {
    const { opColor, RAPID_COLOR, MARK_COLORS } = await import('./viewer.js');
    return { ops: Array.from({ length: 40 }, (_, k) => opColor(k)), marks: [RAPID_COLOR, ...MARK_COLORS] };
  });
  const rgb = (c) => c.slice(0, 3).map((v) => Math.round(v * 255));
  const apart = (a, b) => Math.hypot(...rgb(a).map((v, i) => v - rgb(b)[i]));
  for (let i = 0; i < colours.ops.length; i++) {
    for (let j = 0; j < i; j++) assert.ok(apart(colours.ops[i], colours.ops[j]) > 12, `operations ${j} and ${i}: ${rgb(colours.ops[j])} and ${rgb(colours.ops[i])}`);
    for (const m of colours.marks) assert.ok(apart(colours.ops[i], m) > 80, `operation ${i} ${rgb(colours.ops[i])} looks like ${rgb(m)}`);
  }
  await context.close();
});

test('two settings that do not fit each other are marked as they are typed: a step-down deeper than the tool\'s flutes', async () => {
  const { page, context, errors } = await openPage();
  await tab(page, 'tools');
  await page.selectOption('#tool-list', '0');
  await page.fill('input[name=fluteLength]', '1.5');
  await tab(page, 'ops');
  await page.click('#op-list li:nth-child(1) .op-name');
  await page.waitForSelector('input[name=op-stepdown].invalid');
  assert.match(await page.textContent('#op-fields .field-error'), /^the step-down \(2 mm\) is deeper than T1's flutes \(1\.5 mm\)/);
  await page.click('#generate');
  assert.equal(await waitForGenerated(page), 'failed');
  assert.match(await page.textContent('#message'), /Operations → 'rough' → Step-down: the step-down \(2 mm\) is deeper than T1's flutes/);
  // Either setting made right clears the mark.
  await page.fill('input[name=op-stepdown]', '1.5');
  await page.waitForFunction(() => !document.querySelector('input[name=op-stepdown]').classList.contains('invalid'));
  assert.deepEqual(errors, []);
  await context.close();
});

test('the page in inches: the fields, the read-outs and the view\'s grid say inches, the job and its files keep mm, the program follows, and the choice is kept for the next visit', async () => {
  const { page, context, errors } = await openPage();
  await onlyRaster(page);
  const stepover = async () => page.evaluate(() => window.swarf.jobs.part.operations[0].stepover);
  const mmStep = await stepover();
  await page.selectOption('#page-units', 'inch');
  // A length field: its label and its value in inches; typed in inches, kept in mm.
  assert.match(await page.evaluate(() => document.querySelector('input[name=op-stepover]').closest('label').textContent), /^Step-over \(in\)/);
  // To a tenth of a thousandth, as an inch machinist types it (0.19685 was shown once).
  assert.equal(await page.inputValue('input[name=op-stepover]'), String(Number((mmStep / 25.4).toFixed(4))));
  await page.fill('input[name=op-stepover]', '0.06');
  await page.fill('input[name=op-grid]', '0.02');
  assert.ok(Math.abs(await stepover() - 1.524) < 1e-9, `stepover kept as ${await stepover()} mm`);
  // A feed: in/min.
  await tab(page, 'tools');
  assert.match(await page.evaluate(() => document.querySelector('#tool-editor input[name=feedRate]').closest('label').textContent), /\(in\/min/);
  const feed = await page.evaluate(() => window.swarf.tools[0].feedRate);
  // To a tenth of an inch a minute (47.24409 was shown once).
  assert.equal(await page.inputValue('#tool-editor input[name=feedRate]'), String(Number((feed / 25.4).toFixed(1))));
  // The read-outs: the part's size (the 90 mm sample is 3.543 in), the grid, the library.
  assert.match(await page.textContent('#part-size'), /^3\.543 × \S+ × \S+ in /);
  assert.match(await page.textContent('#scale'), /^grid (0\.1|1|10) in · part 3\.543 × /);
  const d0 = await page.evaluate(() => window.swarf.tools[0].diameter);
  assert.match(await page.textContent('#tool-list'), new RegExp(`T\\d+ · ${String(Number((d0 / 25.4).toFixed(4))).replace('.', '\\.')} in `));
  // The program follows the page into inches (G20); the summary says inches.
  assert.equal(await page.evaluate(() => window.swarf.jobs.part.post.units), 'inch');
  await tab(page, 'ops');
  await page.click('#generate');
  assert.equal(await waitForGenerated(page), 'ok', await page.textContent('#message'));
  assert.match(await page.textContent('#stats'), /[\d,]+ in cutting · [\d,]+ in rapid/);
  const gcode = await page.evaluate(() => new TextDecoder().decode(window.swarf.result.gcodeBytes));
  assert.match(gcode, /^G20$/m);
  // Its head says the rapids in the program's unit too.
  assert.match(gcode, /rapids at [\d.]+ in\/min/);
  assert.doesNotMatch(gcode, /mm\/min/);
  // The saved job keeps mm.
  const [saved] = await Promise.all([page.waitForEvent('download'), page.click('#save-job')]);
  const job = JSON.parse(fs.readFileSync(await saved.path(), 'utf8'));
  assert.ok(Math.abs(job.operations[0].stepover - 1.524) < 1e-9, `the file says ${job.operations[0].stepover}`);
  // The next visit opens in inches.
  await page.reload();
  await page.waitForSelector('body[data-ready="true"]');
  assert.equal(await page.inputValue('#page-units'), 'inch');
  await tab(page, 'ops');
  await page.click('#op-list li:nth-child(1) .op-name');
  assert.equal(await page.inputValue('input[name=op-stepover]'), '0.06');
  // The engine's words in inches too: a step-over too fine for the part is refused in inches.
  await page.fill('input[name=op-stepover]', '0.0001');
  await page.click('#generate');
  assert.equal(await waitForGenerated(page), 'failed');
  const said = await page.textContent('#message');
  assert.match(said, /step-over of 0\.0001 in .*over \d+(\.\d+)? in/, said);
  assert.doesNotMatch(said, /\bmm\b/, said);
  await page.fill('input[name=op-stepover]', '0.06');
  // Back to mm: every figure in mm again, the program with it.
  await page.selectOption('#page-units', 'mm');
  assert.equal(await page.inputValue('input[name=op-stepover]'), '1.524');
  assert.match(await page.textContent('#part-size'), /^90\.0 × /);
  assert.equal(await page.evaluate(() => window.swarf.jobs.part.post.units), 'mm');
  assert.deepEqual(errors, []);
  await context.close();
});

test('a new operation takes the tool that suits its kind: the largest flat to rough, a ball to finish, a drill or a V-bit added to the library where it has none', async () => {
  const { page, context, errors } = await openPage();
  // The sample's library: T1 a φ6 flat, T2 a φ6 ball, T3 a φ3 flat. The ball selected in the
  // Tools tab.
  await tab(page, 'tools');
  const before = await page.evaluate(() => window.swarf.tools.map((t) => `${t.number}:${t.shape}:${t.diameter}`));
  assert.deepEqual(before, ['1:flat:6', '2:ball:6', '3:flat:3']);
  await page.selectOption('#tool-list', { index: 1 });
  const added = async (kind) => {
    await tab(page, 'ops');
    await page.selectOption('#op-kind', kind);
    await page.click('#op-add');
    return page.evaluate(() => { const o = window.swarf.jobs.part.operations.at(-1); return { tool: o.tool, tools: window.swarf.tools.map((t) => ({ n: t.number, shape: t.shape, d: t.diameter, angle: t.angle })) }; });
  };
  assert.equal((await added('roughAdaptive')).tool, 1, 'adaptive: the largest flat, not the ball selected');
  assert.equal((await added('finishScallop')).tool, 2, 'scallop: the ball');
  const drill = await added('drill');
  const d = drill.tools.find((t) => t.n === drill.tool);
  assert.deepEqual([d.shape, d.d, d.angle], ['drill', 5, 118], JSON.stringify(drill));
  assert.match(await page.textContent('#message'), new RegExp(`Added T${d.n}, a φ5 mm drill, to the tool library`));
  const vee = await added('chamfer');
  const v = vee.tools.find((t) => t.n === vee.tool);
  assert.deepEqual([v.shape, v.angle], ['vBit', 90]);
  // A second drilling takes the drill now in the library: nothing more added.
  const again = await added('drill');
  assert.equal(again.tool, d.n);
  assert.equal(again.tools.length, 5);
  assert.deepEqual(errors, []);
  await context.close();
});
