// Screenshots of the page as a user sees it, for reviewing the layout by eye: the sample part and
// the sample drawing, before and after Generate, at 1280×720 and 1920×1080 (and any size given
// as WxH arguments). Writes target/screenshots/*.png.
//   node scripts/screenshots.mjs [1400x900 ...]
import fs from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { chromium } from 'playwright-core';
import { serveWww } from './serve-www.mjs';

const out = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '../target/screenshots');
fs.mkdirSync(out, { recursive: true });
const sizes = (process.argv.slice(2).length ? process.argv.slice(2) : ['1280x720', '1920x1080']).map((s) => s.split('x').map(Number));

const { server, base } = await serveWww();
const browser = await chromium.launch({
  executablePath: process.env.CHROMIUM || '/usr/bin/chromium',
  headless: true,
  args: ['--no-sandbox', '--disable-background-networking', '--disable-component-update', '--no-first-run', '--disable-sync', '--disable-dev-shm-usage'],
});
try {
  for (const [width, height] of sizes) {
    const context = await browser.newContext({ viewport: { width, height } });
    const page = await context.newPage();
    page.on('pageerror', (e) => console.log(`page error: ${e}`));
    page.on('console', (m) => { if (m.type() === 'error' || m.type() === 'warning') console.log(`console: ${m.text()}`); });
    await page.goto(base);
    await page.waitForSelector('body[data-ready="true"]');
    const shot = async (name) => { await page.screenshot({ path: path.join(out, `${name}-${width}x${height}.png`) }); console.log(`${name}-${width}x${height}.png`); };
    const generate = async () => {
      await page.evaluate(() => { delete document.body.dataset.generated; });
      await page.click('#generate');
      await page.waitForFunction(() => ['ok', 'problem', 'failed'].includes(document.body.dataset.generated), null, { timeout: 600000 });
    };
    await shot('part');
    await generate();
    await shot('part-generated');
    await page.click('#result-tabs [data-result="gcode"]');
    await page.fill('#scrub', '600');
    await page.dispatchEvent('#scrub', 'input');
    await page.waitForTimeout(500);
    await shot('part-scrubbed');
    await page.click('#use-sample-drawing');
    await page.waitForFunction(() => document.body.dataset.kind === 'drawing');
    await shot('drawing');
    await generate();
    await shot('drawing-generated');
    await context.close();
  }
} finally {
  await browser.close();
  server.close();
}
