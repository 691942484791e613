// Seed 001's die as the page's user would bring it: a binary STL of the synthetic die
// (mesh::sample::fuel_tank_die, the same surface), `nx` × `ny` cells of its 1190 × 890 mm.
export function dieStl(nx, ny) {
  const [w, h] = [1190, 890];
  return heightFieldStl(w, h, nx, ny, -250, (x, y) => {
    const [u, v] = [x / w - 0.5, y / h - 0.5];
    const r = Math.hypot(u / 0.38, v / 0.33);
    const cavity = -120 / (1 + Math.exp(-(r - 1) * -14));
    const boss = 45 * Math.exp(-((u - 0.12) ** 2 + (v + 0.05) ** 2) / 0.006);
    const inside = 1 / (1 + Math.exp((r - 1) * 14));
    const channel = -25 * Math.exp(-((u + 0.2 * v + 0.15) ** 2) / 0.002) * inside;
    return cavity + boss + channel + 6 * Math.sin(9 * u) * Math.cos(7 * v);
  });
}

// A closed solid over [0, w] × [0, h] whose top is `top(x, y)` on `nx` × `ny` cells (two
// facets each), with walls down to `bottom` and a bottom of two facets, as a binary STL (as
// mesh::sample::height_field_solid makes one in the core).
export function heightFieldStl(w, h, nx, ny, bottom, top) {
  const at = (i, j) => { const [x, y] = [(w * i) / nx, (h * j) / ny]; return [x, y, top(x, y)]; };
  const tris = [];
  for (let j = 0; j < ny; j++) for (let i = 0; i < nx; i++) {
    const [a, b, c, d] = [at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)];
    tris.push([a, b, c], [a, c, d]);
  }
  const floor = (p) => [p[0], p[1], bottom];
  const wall = (p, q) => tris.push([p, floor(p), floor(q)], [p, floor(q), q]);
  for (let i = 0; i < nx; i++) { wall(at(i + 1, 0), at(i, 0)); wall(at(i, ny), at(i + 1, ny)); }
  for (let j = 0; j < ny; j++) { wall(at(0, j), at(0, j + 1)); wall(at(nx, j + 1), at(nx, j)); }
  const c = [[0, 0, bottom], [w, 0, bottom], [w, h, bottom], [0, h, bottom]];
  tris.push([c[0], c[2], c[1]], [c[0], c[3], c[2]]);
  const buf = Buffer.alloc(84 + 50 * tris.length);
  buf.writeUInt32LE(tris.length, 80);
  tris.forEach((t, k) => t.forEach((p, v) => p.forEach((x, a) => buf.writeFloatLE(x, 84 + 50 * k + 12 + 12 * v + 4 * a))));
  return buf;
}
