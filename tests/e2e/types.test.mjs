// The module's TypeScript definitions (www/swarf.d.ts and the types generated from the Rust
// serde types, www/types/) compile, and a portal's code written against them type-checks in
// strict mode (including a use that must not).
import { test } from 'node:test';
import assert from 'node:assert/strict';
import path from 'node:path';
import { spawnSync } from 'node:child_process';
import { fileURLToPath } from 'node:url';

const repo = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '../..');

test('a portal\'s TypeScript against swarf.js type-checks in strict mode', () => {
  const tsc = path.join(repo, 'node_modules/.bin/tsc');
  const r = spawnSync(tsc, ['--noEmit', '--strict', '--target', 'es2022', '--module', 'es2022', '--moduleResolution', 'bundler', '--lib', 'es2022,dom', 'tests/types/portal.ts'], { cwd: repo, encoding: 'utf8' });
  assert.equal(r.status, 0, `${r.stdout}${r.stderr}`);
});
