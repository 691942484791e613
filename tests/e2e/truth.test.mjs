// What the page and the engine show is what the machine will do (issue 55): the view draws the
// part as the core places it, a stock box the part sticks out of is marked where it is typed,
// a click is never lost to a list refreshed under it, and an unsafe program never leaves the
// engine unless the caller asks for it.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { PATIENCE, tab, frame, openPage, addTool, plateStl, waitForGenerated } from './harness.mjs';

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
  await page.selectOption('select[name=opTool]', String(drill));
  await page.click('#find-holes');
  await page.waitForFunction(() => document.querySelectorAll('#hole-list li').length === 3);
  // The holes: three renames, each followed at once by a click on a hole.
  for (const k of [0, 1, 2]) {
    await page.fill('input[name=opName]', `drill pass ${k}`);
    await page.click(`#hole-list li:nth-child(${k + 1})`);
    await page.waitForFunction((n) => document.querySelectorAll('#hole-list li.picked').length === n, k + 1);
  }
  assert.equal(await page.evaluate(() => window.swarf.jobs.part.operations.at(-1).holes.length), 3, 'a hole was left out');
  assert.equal(await page.evaluate(() => window.swarf.jobs.part.operations.at(-1).name), 'drill pass 2');
  // The operations: rename, then click the first operation at once.
  const count = await page.locator('#op-list li').count();
  await page.fill('input[name=opName]', 'drill the three');
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
    // The roughing tool's flutes 1 mm long, stepping down 2 mm: its body rubs.
    job.tools[0].fluteLength = 1;
    job.operations = job.operations.slice(0, 1);
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
