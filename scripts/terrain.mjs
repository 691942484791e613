// Issue 61's generated terrain: a closed height-field solid over 100 × 100 mm of N × N cells
// (scripts/die-stl.mjs' heightFieldStl), hills and hollows from a few smooth bumps on a gentle
// wave, 2 to about 22 mm high, its bottom at z 0. N = 273 (the default) gives 151,244 facets,
// 137 38,636 and 68 9,794: the same shape at three sizes. Writes a binary STL.
//
//   node scripts/terrain.mjs OUT.stl [N]
import fs from 'node:fs';
import { heightFieldStl } from './die-stl.mjs';

const n = Number(process.argv[3] ?? 273);
const bumps = [[30, 35, 14, 12], [70, 60, 12, 9], [50, 80, 8, -5], [20, 75, 10, 7], [75, 20, 9, 10], [50, 45, 6, -4]];
const top = (x, y) => Math.max(2, bumps.reduce((z, [cx, cy, s, a]) => z + a * Math.exp(-((x - cx) ** 2 + (y - cy) ** 2) / (2 * s * s)), 8 + 2 * Math.sin(x / 7) * Math.cos(y / 9)));
const stl = heightFieldStl(100, 100, n, n, 0, top);
fs.writeFileSync(process.argv[2], stl);
console.log(`${stl.readUInt32LE(80)} facets`);
