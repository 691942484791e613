// WebGL2 view of the part (shaded), the tool paths (lines), the simulated stock and the tool:
// orbit, pan, zoom, view presets, a grid that gives the part's size at a glance. Z is up.

const MESH_VS = `#version 300 es
in vec3 position; in vec3 normal;
uniform mat4 mvp; uniform vec3 offset; out vec3 vNormal;
void main() { vNormal = normal; gl_Position = mvp * vec4(position + offset, 1.0); }`;
const MESH_FS = `#version 300 es
precision highp float;
in vec3 vNormal; uniform vec4 color; uniform vec3 light; out vec4 outColor;
void main() {
  float d = abs(dot(normalize(vNormal), light));
  outColor = vec4(color.rgb * (0.35 + 0.65 * d), color.a);
}`;
const LINE_VS = `#version 300 es
in vec3 position; uniform mat4 mvp;
void main() { gl_Position = mvp * vec4(position, 1.0); }`;
const LINE_FS = `#version 300 es
precision highp float;
uniform vec4 color; out vec4 outColor;
void main() { outColor = color; }`;

// The simulated stock: a height field on the simulation's cells, shaded by its own slope and
// coloured by the material left above the part (+ allowance): red where it lies below (a gouge),
// blue where material is left, tan elsewhere; off the part, plain stock colour. Coloured by
// depth instead (`byDepth`, as a V-carve or a relief is judged): tan where uncut, then yellow
// through orange to violet at the part's lowest (`depthTop` less `depthSpan`); gouges red still.
// The rest areas (`restAreas`): magenta wherever more than the tolerance is left on the part,
// what a rest operation from this point on may take.
const STOCK_VS = `#version 300 es
in vec2 xy; in float z; in float partZ;
uniform mat4 mvp; out vec3 world; out float left; out float onPart;
void main() {
  world = vec3(xy, z);
  onPart = partZ > -1.0e8 ? 1.0 : 0.0;
  left = z - partZ;
  gl_Position = mvp * vec4(world, 1.0);
}`;
const STOCK_FS = `#version 300 es
precision highp float;
in vec3 world; in float left; in float onPart;
uniform vec3 light; uniform float tol; uniform bool byDepth; uniform bool restAreas; uniform float depthTop; uniform float depthSpan; out vec4 outColor;
void main() {
  vec3 n = normalize(cross(dFdx(world), dFdy(world)));
  float d = abs(dot(n, light));
  vec3 base = vec3(0.80, 0.72, 0.58);
  float t = (depthTop - world.z) / depthSpan;
  if (onPart > 0.5 && left < -tol) base = vec3(0.86, 0.10, 0.10);
  else if (restAreas && onPart > 0.5 && left > tol) base = vec3(0.85, 0.22, 0.72);
  else if (byDepth && t > 0.002) {
    t = clamp(t, 0.0, 1.0);
    base = t < 0.5 ? mix(vec3(0.98, 0.86, 0.40), vec3(0.93, 0.48, 0.16), t * 2.0) : mix(vec3(0.93, 0.48, 0.16), vec3(0.36, 0.12, 0.50), t * 2.0 - 1.0);
  } else if (onPart > 0.5) base = mix(base, vec3(0.20, 0.42, 0.85), clamp((left - 0.02) / 1.0, 0.0, 1.0));
  outColor = vec4(base * (0.35 + 0.65 * d), 1.0);
}`;

function compile(gl, vs, fs) {
  const program = gl.createProgram();
  for (const [type, source] of [[gl.VERTEX_SHADER, vs], [gl.FRAGMENT_SHADER, fs]]) {
    const shader = gl.createShader(type);
    gl.shaderSource(shader, source);
    gl.compileShader(shader);
    if (!gl.getShaderParameter(shader, gl.COMPILE_STATUS)) throw new Error(gl.getShaderInfoLog(shader));
    gl.attachShader(program, shader);
  }
  gl.linkProgram(program);
  if (!gl.getProgramParameter(program, gl.LINK_STATUS)) throw new Error(gl.getProgramInfoLog(program));
  return program;
}

// Column-major 4×4 matrices.
function multiply(a, b) {
  const out = new Float32Array(16);
  for (let c = 0; c < 4; c++) for (let r = 0; r < 4; r++) {
    let s = 0;
    for (let k = 0; k < 4; k++) s += a[k * 4 + r] * b[c * 4 + k];
    out[c * 4 + r] = s;
  }
  return out;
}
function perspective(fovy, aspect, near, far) {
  const f = 1 / Math.tan(fovy / 2), nf = 1 / (near - far);
  return new Float32Array([f / aspect, 0, 0, 0, 0, f, 0, 0, 0, 0, (far + near) * nf, -1, 0, 0, 2 * far * near * nf, 0]);
}
function lookAt(eye, target, up) {
  const sub = (a, b) => [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
  const norm = (v) => { const l = Math.hypot(...v) || 1; return v.map((x) => x / l); };
  const cross = (a, b) => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
  const dot = (a, b) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
  const z = norm(sub(eye, target)), x = norm(cross(up, z)), y = cross(z, x);
  return new Float32Array([x[0], y[0], z[0], 0, x[1], y[1], z[1], 0, x[2], y[2], z[2], 0, -dot(x, eye), -dot(y, eye), -dot(z, eye), 1]);
}

// Rapids and the places verification found are drawn in colours no operation or tool takes:
// rapids orange, gouges red, rapids through stock magenta, the tool's body in material amber.
export const RAPID_COLOR = [0.93, 0.42, 0.0, 0.9];
export const MARK_COLORS = [[0.86, 0.1, 0.1, 1], [0.85, 0.0, 0.65, 1], [0.95, 0.65, 0.0, 1]];

// Colours of the operations' cutting moves, in order (the first is the classic path blue), and
// of the tools an octree roughing chose: blues, purples, greens and greys, none near red,
// orange or magenta.
export const OP_COLORS = [[0.106, 0.455, 0.82, 1], [0.5, 0.22, 0.78, 1], [0.0, 0.6, 0.55, 1], [0.22, 0.55, 0.12, 1], [0.12, 0.2, 0.5, 1], [0.45, 0.45, 0.5, 1]];
export const TOOL_COLORS = [[0.0, 0.42, 0.62, 1], [0.35, 0.62, 0.2, 1], [0.42, 0.3, 0.7, 1], [0.0, 0.65, 0.78, 1], [0.3, 0.3, 0.35, 1], [0.55, 0.55, 0.15, 1]];
export const toolColor = (number) => TOOL_COLORS[(Math.max(1, number) - 1) % TOOL_COLORS.length];
// Past the six chosen ones, each operation gets a colour of its own, as far from every colour
// taken before it (the six, the earlier ones, the rapids' and the marks') as a palette of
// greens, cyans, blues and violets allows (hues 90° to 275°, three saturations and lightnesses,
// none near the marks),
// so that no two operations of a job share one. Made once, as many as a job may hold.
const MOST_OPERATIONS = 100;
const hsl = (hue, s, l) => {
  const c = (1 - Math.abs(2 * l - 1)) * s, h = hue / 60, x = c * (1 - Math.abs((h % 2) - 1)), m = l - c / 2;
  const [r, g, b] = h < 1 ? [c, x, 0] : h < 2 ? [x, c, 0] : h < 3 ? [0, c, x] : h < 4 ? [0, x, c] : h < 5 ? [x, 0, c] : [c, 0, x];
  return [r + m, g + m, b + m, 1];
};
const PALETTE = (() => {
  const candidates = [];
  const d = (a, b) => Math.hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]);
  const marks = [RAPID_COLOR, ...MARK_COLORS];
  for (let hue = 90; hue <= 275; hue += 5) {
    for (const s of [0.45, 0.65, 0.85]) for (const l of [0.3, 0.42, 0.55]) {
      const c = hsl(hue, s, l);
      if (marks.every((m) => d(c, m) > 0.4)) candidates.push(c);
    }
  }
  const taken = [...OP_COLORS, ...marks];
  const far = (c) => Math.min(...taken.map((t) => d(c, t)));
  const out = [...OP_COLORS];
  while (out.length < MOST_OPERATIONS) {
    let best = null, bestFar = -1;
    for (const c of candidates) { const f = far(c); if (f > bestFar) { best = c; bestFar = f; } }
    out.push(best);
    taken.push(best);
  }
  return out;
})();
export const opColor = (index) => PALETTE[index % PALETTE.length];
export const cssColor = (c) => `rgb(${c.slice(0, 3).map((v) => Math.round(v * 255)).join(',')})`;

// Loops picked for an operation (a bright blue, apart from the outlines' green and the holes'
// orange).
export const PICKED_COLOR = [0.0, 0.75, 1.0, 1];
const PICKED_LIFT = 0.05; // mm

// The view's vertical angle (radians).
const FOV_Y = 0.7;

// Segments drawn while the view moves: beyond this many, every k-th (the whole once it stops),
// so that a program of millions of moves stays orbitable without a GPU.
const MOVING_SEGMENTS = 300000;
// Segments a group of the path holds at most: each is uploaded in a task of its own (a die-sized
// program of a million segments in eight, 30-35 ms each in headless Chromium beside the workers;
// a quarter of a million held a frame 50-77 ms), its draw a call of its own.
const GROUP_SEGMENTS = 1 << 17;
// How long after the last move of the mouse or wheel the view counts as still moving (ms).
const SETTLE_MS = 180;

// What the view draws of a part, from the very coordinates uploaded: their bounds and the
// mean of its triangles' corners (a flip keeps a centred part's bounds but moves this).
function drawnShape(p) {
  const min = [Infinity, Infinity, Infinity], max = [-Infinity, -Infinity, -Infinity], sum = [0, 0, 0];
  for (let i = 0; i < p.length; i += 3) {
    for (let k = 0; k < 3; k++) {
      const v = p[i + k];
      if (v < min[k]) min[k] = v;
      if (v > max[k]) max[k] = v;
      sum[k] += v;
    }
  }
  const n = Math.max(1, p.length / 3);
  return { bounds: [...min, ...max], mean: sum.map((s) => s / n) };
}

// The runs `parts` ([start, end) of segments) cut into lists of runs of at most `size` segments.
function chunks(parts, size) {
  const out = [];
  let current = [], count = 0;
  for (let [a, b] of parts) {
    while (a < b) {
      const e = Math.min(b, a + size - count);
      current.push([a, e]);
      count += e - a;
      a = e;
      if (count === size) { out.push(current); current = []; count = 0; }
    }
  }
  if (count) out.push(current);
  return out;
}

export class Viewer {
  constructor(canvas) {
    this.canvas = canvas;
    const gl = canvas.getContext('webgl2', { antialias: true, preserveDrawingBuffer: true });
    if (!gl) throw new Error('this browser has no WebGL2');
    this.gl = gl;
    this.meshProgram = compile(gl, MESH_VS, MESH_FS);
    this.lineProgram = compile(gl, LINE_VS, LINE_FS);
    this.stockProgram = compile(gl, STOCK_VS, STOCK_FS);
    this.stock = null;
    this.show = { part: true, paths: true, stock: true, octants: true, tool: true, grid: true, depth: false, rest: false };
    this.hiddenOps = new Set();
    this.part = null;
    this.lines = {};
    this.groups = [];
    this.cutMoves = Infinity;
    this.tool = null;
    this.camera = { yaw: -0.9, pitch: 0.75, distance: 200, target: [0, 0, 0] };
    this.moving = false;
    this.bindInput();
    new ResizeObserver(() => this.draw()).observe(canvas);
  }

  buffer(data) {
    const gl = this.gl, b = gl.createBuffer();
    gl.bindBuffer(gl.ARRAY_BUFFER, b);
    gl.bufferData(gl.ARRAY_BUFFER, data, gl.STATIC_DRAW);
    return b;
  }

  setPart(part, frame = true) {
    // The same part again (a run's result on the part the view shows): kept, not uploaded
    // again (a die-sized part is tens of megabytes). The same only by the core's hash of the
    // placed triangles: a part without one is always drawn anew.
    const source = part.hash ?? null;
    if (this.part && source !== null && this.partSource === source) {
      if (frame) this.frame(part.bounds);
      this.draw();
      return;
    }
    this.dropPart();
    this.partSource = source;
    this.part = { position: this.buffer(part.positions), normal: this.buffer(part.normals), count: part.positions.length / 3, drawn: drawnShape(part.positions), positions: part.positions };
    this.setGrid(part.bounds);
    if (frame) this.frame(part.bounds);
    this.draw();
  }

  // Cutting moves in their operation's colour (`ops`: the operation of each segment), or in
  // their tool's for the operations in `byTool` (octree roughing; `tools`: the tool of each
  // segment), and rapids; `moves` and `rapidMoves` give each segment's program move, so that
  // the path already cut can be drawn apart from the path to come (`setCut`). Returned as steps
  // to run one after the other, each a task of its own if the caller likes (a step uploads at
  // most GROUP_SEGMENTS segments: a die-sized program's million segments never hold the page's
  // thread in one task).
  pathSteps({ feeds, rapids, stock, fixtures = [], ops = null, tools = null, moves = null, rapidMoves = null, byTool = new Set() }) {
    this.dropGroups();
    // The work zero is shown before a run (`setStage`); after it the paths' colours speak.
    this.dropLines((key) => key.startsWith('octants') || key === 'stock' || key === 'fixtures' || key.startsWith('zero'));
    // An operation's segments (a stage's, for octree roughing) follow each other in the
    // program: taken as runs, a colour that comes back after another copied once.
    const runs = new Map();
    const n = feeds.length / 6;
    for (let start = 0; start < n;) {
      const op = ops ? ops[start] : 0, tool = tools ? tools[start] : 0, split = tools && byTool.has(op);
      let end = start + 1;
      while (end < n && (ops ? ops[end] : 0) === op && (!split || tools[end] === tool)) end++;
      const key = split ? `${op}:${tool}` : `${op}`;
      if (!runs.has(key)) runs.set(key, { op, color: split ? toolColor(tool) : opColor(op), parts: [] });
      runs.get(key).parts.push([start, end]);
      start = end;
    }
    const total = n + rapids.length / 6;
    const every = Math.max(1, Math.ceil(total / MOVING_SEGMENTS));
    const steps = [];
    const add = (data, segmentMoves, parts, style) => {
      for (const chunk of chunks(parts, GROUP_SEGMENTS)) steps.push(() => this.addGroup(data, segmentMoves, chunk, style, every));
    };
    for (const { op, color, parts } of runs.values()) add(feeds, moves, parts, { op, color });
    add(rapids, rapidMoves, [[0, rapids.length / 6]], { op: -1, color: RAPID_COLOR, rapid: true });
    steps.push(() => {
      if (stock) this.setStockLines(stock, fixtures, false);
      this.cutMoves = Infinity;
      this.draw();
    });
    return steps;
  }

  // Before a run, as the setup on show holds the part: the stock's box, what holds the stock
  // (`stage.fixtures`, boxes) and the work zero; `null` takes them away.
  setStage(stage) {
    this.dropLines((key) => key === 'stock' || key === 'fixtures' || key.startsWith('zero'));
    this.staged = stage;
    if (stage) this.setStockLines(stage.stock, stage.fixtures, true, stage.bar);
    this.draw();
  }

  // The stock's box, what holds it (a vise's jaws, clamps: in the red of things not to touch)
  // and, before a run, the work zero.
  // A bar (`{ diameter, axis }`) is drawn as its cylinder in the stock's box.
  setStockLines(stock, fixtures, zero = true, bar = null) {
    const lines = bar ? barLines(stock, bar) : boxLines(stock);
    this.setLine('stock', { buffer: this.buffer(lines), count: lines.length / 3, color: [0.35, 0.4, 0.45, 0.6], mark: true });
    if (fixtures.length) {
      const lines = new Float32Array(fixtures.length * 72);
      fixtures.forEach((b, k) => lines.set(boxLines(b), k * 72));
      this.setLine('fixtures', { buffer: this.buffer(lines), count: 24 * fixtures.length, color: [0.75, 0.15, 0.1, 0.9], mark: true });
    }
    if (zero) this.setZero(stock);
  }

  // The work zero, the program's origin: its X, Y and Z axes a sixth of the stock long, X the
  // longest and Z the shortest, in dark grey (the view's hues say paths, problems and loops).
  zeroAxes(stock) {
    const size = Math.max(stock[3] - stock[0], stock[4] - stock[1], stock[5] - stock[2]) / 6;
    return [[1.2 * size, 0, 0], [0, 0.9 * size, 0], [0, 0, 0.7 * size]];
  }

  // Frames the part as staged (`bounds`) with its stock and the work zero's axes.
  frameStage(bounds, stock) {
    const points = [bounds.slice(0, 3), bounds.slice(3), stock.slice(0, 3), stock.slice(3), [0, 0, 0], ...this.zeroAxes(stock)];
    this.frame([0, 1, 2].map((a) => Math.min(...points.map((p) => p[a]))).concat([0, 1, 2].map((a) => Math.max(...points.map((p) => p[a])))));
  }

  setZero(stock) {
    const grey = [0.2, 0.2, 0.22, 1];
    const axes = this.zeroAxes(stock).map((v, k) => [['zero_x', 'zero_y', 'zero_z'][k], v, grey]);
    for (const [key, [x, y, z], color] of axes) this.setLine(key, { buffer: this.buffer(new Float32Array([0, 0, 0, x, y, z])), count: 2, color, mark: true });
  }

  // One colour's segments (the runs `parts` of `data`), with their moves, and every `every`-th
  // of them for drawing while the view moves.
  addGroup(data, moves, parts, style, every) {
    const count = parts.reduce((s, [a, b]) => s + b - a, 0);
    if (!count) return;
    const all = new Float32Array(count * 6), at = new Uint32Array(count);
    let k = 0;
    for (const [a, b] of parts) {
      all.set(data.subarray(a * 6, b * 6), k * 6);
      if (moves) at.set(moves.subarray(a, b), k);
      k += b - a;
    }
    const group = { ...style, buffer: this.buffer(all), count, moves: moves ? at : null };
    if (every > 1) {
      const few = Math.ceil(count / every), thin = new Float32Array(few * 6), thinMoves = new Uint32Array(few);
      for (let i = 0; i < few; i++) { thin.set(all.subarray(i * every * 6, i * every * 6 + 6), i * 6); thinMoves[i] = at[i * every]; }
      group.thin = { buffer: this.buffer(thin), count: few, moves: moves ? thinMoves : null };
    }
    this.groups.push(group);
  }

  dropGroups() {
    for (const g of this.groups) { this.gl.deleteBuffer(g.buffer); if (g.thin) this.gl.deleteBuffer(g.thin.buffer); }
    this.groups = [];
  }

  // The path up to (not including) program move `count` is drawn as cut, the rest faint
  // (Infinity: all of it as cut).
  setCut(count) {
    this.cutMoves = count;
    this.draw();
  }

  // The operations whose paths are hidden (their indices).
  setHiddenOps(hidden) {
    this.hiddenOps = new Set(hidden);
    this.draw();
  }

  // Holes (as the engine finds them) as circles at their tops, the picked ones (their indices,
  // a drawing's by loop) in orange, the others grey.
  setHoles(holes, picked = new Set()) {
    this.dropLines((key) => key.startsWith('holes'));
    const groups = { picked: [], others: [] };
    holes.forEach((h, k) => {
      const into = picked.has(h.loopIndex ?? k) ? groups.picked : groups.others;
      // A drill mark (no diameter of its own): a cross 3 mm across.
      if (h.mark) {
        const [x, y] = h.center;
        into.push(x - 1.5, y, h.top, x + 1.5, y, h.top, x, y - 1.5, h.top, x, y + 1.5, h.top);
        return;
      }
      const r = h.diameter / 2, n = 48;
      for (let i = 0; i < n; i++) {
        const a = (2 * Math.PI * i) / n, b = (2 * Math.PI * (i + 1)) / n;
        into.push(h.center[0] + r * Math.cos(a), h.center[1] + r * Math.sin(a), h.top, h.center[0] + r * Math.cos(b), h.center[1] + r * Math.sin(b), h.top);
      }
    });
    for (const [key, data] of Object.entries(groups)) {
      if (data.length) this.setLine(`holes_${key}`, { buffer: this.buffer(new Float32Array(data)), count: data.length / 3, color: key === 'picked' ? [0.9, 0.55, 0.1, 1] : [0.45, 0.48, 0.52, 1], mark: true });
    }
    this.draw();
  }

  // A part's top edges (as the engine finds them) as loops at their heights: the picked ones
  // (their indices) in orange, the other sharp ones grey, those a chamfer cannot break faint.
  setEdges(edges, picked = new Set()) {
    this.dropLines((key) => key.startsWith('edges'));
    const groups = { picked: [], sharp: [], blunt: [] };
    edges.forEach((e, k) => {
      const into = picked.has(k) ? groups.picked : e.sharp ? groups.sharp : groups.blunt;
      e.points.forEach((p, i) => {
        const q = e.points[(i + 1) % e.points.length];
        into.push(p[0], p[1], e.z, q[0], q[1], e.z);
      });
    });
    const colors = { picked: [0.9, 0.55, 0.1, 1], sharp: [0.45, 0.48, 0.52, 1], blunt: [0.78, 0.8, 0.82, 1] };
    for (const [key, data] of Object.entries(groups)) {
      if (data.length) this.setLine(`edges_${key}`, { buffer: this.buffer(new Float32Array(data)), count: data.length / 3, color: colors[key], mark: true });
    }
    this.draw();
  }

  // The octants of octree roughing's stages (as `JobResult.octants` gives them, 9 numbers a
  // box) as wire boxes: those a tool cut in its colour, the Partial ones grey.
  setOctants(octants) {
    this.dropLines((key) => key.startsWith('octants'));
    const groups = new Map();
    for (let k = 0; k + 9 <= octants.length; k += 9) {
      const key = octants[k + 2] > 0.5 ? `t${octants[k + 1]}` : 'partial';
      if (!groups.has(key)) groups.set(key, []);
      groups.get(key).push(...boxLines(Array.from(octants.subarray(k + 3, k + 9))));
    }
    for (const [key, data] of groups) {
      const color = key === 'partial' ? [0.62, 0.64, 0.66, 1] : toolColor(Number(key.slice(1)));
      this.setLine(`octants_${key}`, { buffer: this.buffer(new Float32Array(data)), count: data.length / 3, color, octants: true });
    }
    this.draw();
  }

  // A drawing (as loadDrawing gives it): outer loops green, holes orange, open chains red, as
  // lines at Z0. It takes the part's place.
  setDrawing(d, frame = true) {
    this.dropPart();
    const colors = { outer: [0.12, 0.55, 0.24, 1], holes: [0.85, 0.45, 0.05, 1], open: [0.86, 0.1, 0.1, 1] };
    for (const key of Object.keys(colors)) {
      const data = new Float32Array(d[key]);
      this.setLine(`drawing_${key}`, { buffer: this.buffer(data), count: data.length / 3, color: colors[key], mark: true });
    }
    this.setGrid(d.bounds);
    if (frame) { this.frame(d.bounds); this.view('top', false); }
    this.draw();
  }

  // The loops picked for an operation, drawn over the drawing in a colour of their own (line
  // segments at Z0 as xyz pairs; empty: none).
  setPicked(data) {
    // A hair above Z0, so that they win the depth test against the loops' own lines.
    const lifted = Float32Array.from(data, (v, k) => (k % 3 === 2 ? v + PICKED_LIFT : v));
    this.setLine('drawing_picked', { buffer: this.buffer(lifted), count: lifted.length / 3, color: PICKED_COLOR, mark: true });
    this.draw();
  }

  // A grid under the box `b` ([minX, minY, minZ, maxX, maxY, maxZ]) whose spacing is a power of
  // ten of the page's unit (`unit` mm: 1, 10, 100 mm, or 0.1, 1, 10 in) giving it 2 to 20 cells
  // across: with the size the page states, a part read in the wrong unit looks wrong at a
  // glance. Returns the spacing (mm).
  setGrid(b = this.gridBox, unit = this.gridUnit ?? 1) {
    if (!b) return null;
    this.gridBox = b;
    this.gridUnit = unit;
    const span = Math.max(b[3] - b[0], b[4] - b[1], 1e-6);
    const spacing = unit * 10 ** Math.floor(Math.log10(span / unit / 2));
    const x0 = Math.floor(b[0] / spacing) * spacing, x1 = Math.ceil(b[3] / spacing) * spacing;
    const y0 = Math.floor(b[1] / spacing) * spacing, y1 = Math.ceil(b[4] / spacing) * spacing;
    const z = b[2], out = [];
    for (let x = x0; x <= x1 + spacing * 1e-6; x += spacing) out.push(x, y0, z, x, y1, z);
    for (let y = y0; y <= y1 + spacing * 1e-6; y += spacing) out.push(x0, y, z, x1, y, z);
    this.setLine('grid', { buffer: this.buffer(new Float32Array(out)), count: out.length / 3, color: [0.6, 0.65, 0.7, 0.55], mark: true, grid: true });
    this.gridSpacing = spacing;
    return spacing;
  }

  // The tool as a solid of revolution (`{ shape, diameter, cornerRadius, fluteLength,
  // shankDiameter, stickOut }`), its tip at `setToolAt`; null: no tool.
  setTool(tool) {
    if (this.tool) { this.gl.deleteBuffer(this.tool.position); this.gl.deleteBuffer(this.tool.normal); }
    this.tool = null;
    if (tool) {
      const { positions, normals } = toolMesh(tool);
      this.tool = { position: this.buffer(positions), normal: this.buffer(normals), count: positions.length / 3, at: this.tool?.at ?? null };
    }
    this.draw();
  }

  setToolAt(at) {
    if (this.tool) this.tool.at = at;
    this.draw();
  }

  // Where the point `p` (mm) appears on the canvas, in CSS pixels from its top left corner
  // (null behind the eye).
  project(p) {
    const [x, y, w] = toCanvas(this.matrix(), p[0], p[1], p[2], this.canvas.clientWidth, this.canvas.clientHeight);
    return w > 0 ? [x, y] : null;
  }

  // The point of the part under the canvas point (x, y) in CSS pixels, nearest the eye, in
  // the part's coordinates as drawn (mm), or null off the part: each facet projected, the
  // point found in it by its screen barycentres corrected for perspective.
  pickSurface(x, y) {
    const p = this.part?.positions;
    if (!p) return null;
    const m = this.matrix(), W = this.canvas.clientWidth, H = this.canvas.clientHeight;
    const clip = (k) => toCanvas(m, p[k], p[k + 1], p[k + 2], W, H);
    let best = null, nearest = Infinity;
    for (let k = 0; k + 9 <= p.length; k += 9) {
      const a = clip(k), b = clip(k + 3), c = clip(k + 6);
      if (!(a[2] > 0 && b[2] > 0 && c[2] > 0)) continue;
      const d = (b[1] - c[1]) * (a[0] - c[0]) + (c[0] - b[0]) * (a[1] - c[1]);
      if (Math.abs(d) < 1e-12) continue;
      const l0 = ((b[1] - c[1]) * (x - c[0]) + (c[0] - b[0]) * (y - c[1])) / d;
      const l1 = ((c[1] - a[1]) * (x - c[0]) + (a[0] - c[0]) * (y - c[1])) / d;
      const l2 = 1 - l0 - l1;
      if (l0 < 0 || l1 < 0 || l2 < 0) continue;
      // Perspective-correct weights, and the depth (the eye's w) they give.
      const q = [l0 / a[2], l1 / b[2], l2 / c[2]], sum = q[0] + q[1] + q[2], depth = 1 / sum;
      if (depth >= nearest) continue;
      nearest = depth;
      best = [0, 1, 2].map((i) => (q[0] * p[k + i] + q[1] * p[k + 3 + i] + q[2] * p[k + 6 + i]) / sum);
    }
    return best;
  }

  clearPaths() {
    this.dropGroups();
    this.dropLines((key) => !key.startsWith('drawing') && key !== 'grid');
    this.dropStock();
    this.setTool(null);
    this.draw();
  }

  // Sets the line set `key` (its old buffer deleted).
  setLine(key, line) {
    this.dropLines((k) => k === key);
    this.lines[key] = line;
  }

  // Deletes the line sets whose key `which` accepts, with their buffers.
  dropLines(which) {
    for (const [key, line] of Object.entries(this.lines)) {
      if (!which(key)) continue;
      if (line.buffer) this.gl.deleteBuffer(line.buffer);
      delete this.lines[key];
    }
  }

  dropPart() {
    if (this.part) { this.gl.deleteBuffer(this.part.position); this.gl.deleteBuffer(this.part.normal); }
    this.part = null;
    this.partSource = null;
    this.dropLines((key) => key.startsWith('drawing'));
  }

  dropStock() {
    if (this.stock) { this.gl.deleteBuffer(this.stock.z); this.gl.deleteBuffer(this.stock.partZ); }
    this.stock = null;
  }

  // The simulated stock: grid = [originX, originY, spacing, nx, ny, bottom, top, tolerance], part
  // heights per cell (NaN off the part), and the stock's heights per cell.
  setStock(grid, part, tops) {
    const gl = this.gl;
    const [ox, oy, sp, nx, ny, , , tol] = grid;
    // The cells' places and triangles depend on the grid alone: kept for the next stock on it.
    const key = `${ox} ${oy} ${sp} ${nx} ${ny}`;
    if (this.stockGrid?.key !== key) {
      if (this.stockGrid) { gl.deleteBuffer(this.stockGrid.xy); gl.deleteBuffer(this.stockGrid.elements); }
      const xy = new Float32Array(nx * ny * 2);
      for (let j = 0, k = 0; j < ny; j++) for (let i = 0; i < nx; i++, k += 2) { xy[k] = ox + i * sp; xy[k + 1] = oy + j * sp; }
      const index = new Uint32Array((nx - 1) * (ny - 1) * 6);
      for (let j = 0, n = 0; j + 1 < ny; j++) for (let i = 0; i + 1 < nx; i++, n += 6) {
        const a = j * nx + i;
        index[n] = a; index[n + 1] = a + 1; index[n + 2] = a + nx + 1;
        index[n + 3] = a; index[n + 4] = a + nx + 1; index[n + 5] = a + nx;
      }
      const elements = gl.createBuffer();
      gl.bindBuffer(gl.ELEMENT_ARRAY_BUFFER, elements);
      gl.bufferData(gl.ELEMENT_ARRAY_BUFFER, index, gl.STATIC_DRAW);
      this.stockGrid = { key, xy: this.buffer(xy), elements, count: index.length };
    }
    const partZ = new Float32Array(part.length);
    let lowest = Infinity;
    for (let k = 0; k < part.length; k++) {
      partZ[k] = Number.isNaN(part[k]) ? -1e9 : part[k];
      if (!Number.isNaN(part[k])) lowest = Math.min(lowest, part[k]);
    }
    // Depth is coloured from the stock's top down to the part's lowest (else the stock's bottom).
    const [, , , , , bottom, top] = grid;
    const depthSpan = top - (lowest < top - 1e-3 ? lowest : bottom);
    this.dropStock();
    const z = gl.createBuffer();
    gl.bindBuffer(gl.ARRAY_BUFFER, z);
    gl.bufferData(gl.ARRAY_BUFFER, tops, gl.DYNAMIC_DRAW);
    const g = this.stockGrid;
    this.stock = { xy: g.xy, z, partZ: this.buffer(partZ), elements: g.elements, count: g.count, tol, depthTop: top, depthSpan: Math.max(depthSpan, 1e-3), part, tops, cell: sp * sp };
    this.draw();
  }

  // The area (mm²) where the stock shown stands more than the tolerance above the part: the
  // rest areas.
  restArea() {
    const s = this.stock;
    if (!s) return 0;
    let n = 0;
    for (let k = 0; k < s.part.length; k++) if (s.tops[k] - s.part[k] > s.tol) n++;
    return n * s.cell;
  }

  updateStock(tops) {
    if (!this.stock) return;
    this.stock.tops = tops;
    const gl = this.gl;
    gl.bindBuffer(gl.ARRAY_BUFFER, this.stock.z);
    gl.bufferSubData(gl.ARRAY_BUFFER, 0, tops);
    this.draw();
  }

  // Places verification found (x, y, z, kind per place) as crosses.
  setMarks(findings) {
    for (let kind = 0; kind < 3; kind++) {
      const out = [];
      for (let k = 0; k < findings.length; k += 4) {
        if (findings[k + 3] !== kind) continue;
        const [x, y, z] = [findings[k], findings[k + 1], findings[k + 2]], s = 1.5;
        out.push(x - s, y, z, x + s, y, z, x, y - s, z, x, y + s, z, x, y, z - s, x, y, z + s);
      }
      this.setLine(`marks${kind}`, { buffer: this.buffer(new Float32Array(out)), count: out.length / 3, color: MARK_COLORS[kind], mark: true });
    }
    this.draw();
  }

  // Looks at the box `b` ([minX, minY, minZ, maxX, maxY, maxZ]) from as far as its bounding
  // sphere needs to fit the view's narrower angle, whatever its proportions (a tall part, a
  // cube) and the canvas's.
  frame(b) {
    this.framed = b;
    const radius = Math.max(0.5 * Math.hypot(b[3] - b[0], b[4] - b[1], b[5] - b[2]), 0.5);
    this.camera.target = [(b[0] + b[3]) / 2, (b[1] + b[4]) / 2, (b[2] + b[5]) / 2];
    const aspect = (this.canvas.clientWidth || 1) / Math.max(this.canvas.clientHeight || 1, 1);
    const half = Math.min(FOV_Y, 2 * Math.atan(Math.tan(FOV_Y / 2) * aspect)) / 2;
    this.camera.distance = (1.08 * radius) / Math.sin(half);
  }

  // A preset view: from above (`top`), the front (−Y), the right side (+X), at an angle
  // (`iso`), or the part framed again (`fit`).
  view(name, draw = true) {
    const presets = { top: [-Math.PI / 2, 1.5695], front: [-Math.PI / 2, 0], side: [0, 0], iso: [-0.9, 0.62] };
    if (name === 'fit') { if (this.framed) this.frame(this.framed); }
    else if (presets[name]) [this.camera.yaw, this.camera.pitch] = presets[name];
    if (draw) this.draw();
  }

  matrix() {
    const { yaw, pitch, distance, target } = this.camera;
    const eye = [
      target[0] + distance * Math.cos(pitch) * Math.cos(yaw),
      target[1] + distance * Math.cos(pitch) * Math.sin(yaw),
      target[2] + distance * Math.sin(pitch),
    ];
    const aspect = this.canvas.width / Math.max(this.canvas.height, 1);
    // Looking straight down, "up" on the screen is +Y.
    const up = Math.abs(pitch) > 1.5 ? [-Math.cos(yaw), -Math.sin(yaw), 0] : [0, 0, 1];
    return multiply(perspective(FOV_Y, aspect, distance / 100, distance * 20), lookAt(eye, target, up));
  }

  // Runs `fn` (which may set the part, paths, stock and marks) and draws once after it: each
  // draw renders the whole scene, and an upload that follows a draw waits until the GPU has
  // rendered it, which on a large part without a GPU (software rendering) holds the page's
  // thread for seconds.
  batch(fn) {
    this.held = (this.held ?? 0) + 1;
    let result;
    try {
      result = fn();
    } finally {
      // An async `fn` holds the view until it settles.
      const release = () => { this.held -= 1; if (!this.held) this.draw(); };
      if (result instanceof Promise) result = result.finally(release); else release();
    }
    return result;
  }

  // Draws at the next frame (once, however often asked for before it).
  draw() {
    if (this.held || this.pending) return;
    this.pending = requestAnimationFrame(() => { this.pending = 0; this.render(); });
  }

  render() {
    const gl = this.gl, canvas = this.canvas;
    const dpr = window.devicePixelRatio || 1;
    const w = Math.max(1, Math.round(canvas.clientWidth * dpr)), h = Math.max(1, Math.round(canvas.clientHeight * dpr));
    if (canvas.width !== w || canvas.height !== h) { canvas.width = w; canvas.height = h; }
    gl.viewport(0, 0, w, h);
    gl.clearColor(0.93, 0.945, 0.955, 1);
    gl.clear(gl.COLOR_BUFFER_BIT | gl.DEPTH_BUFFER_BIT);
    gl.enable(gl.DEPTH_TEST);
    gl.enable(gl.BLEND);
    gl.blendFunc(gl.SRC_ALPHA, gl.ONE_MINUS_SRC_ALPHA);
    const mvp = this.matrix();
    const l = [0.4, -0.5, 0.77], ln = Math.hypot(...l);
    const stockShown = this.stock && this.show.stock;
    if (stockShown) {
      const p = this.stockProgram, s = this.stock;
      gl.useProgram(p);
      gl.uniformMatrix4fv(gl.getUniformLocation(p, 'mvp'), false, mvp);
      gl.uniform3f(gl.getUniformLocation(p, 'light'), l[0] / ln, l[1] / ln, l[2] / ln);
      gl.uniform1f(gl.getUniformLocation(p, 'tol'), s.tol);
      gl.uniform1i(gl.getUniformLocation(p, 'byDepth'), this.show.depth ? 1 : 0);
      gl.uniform1i(gl.getUniformLocation(p, 'restAreas'), this.show.rest ? 1 : 0);
      gl.uniform1f(gl.getUniformLocation(p, 'depthTop'), s.depthTop);
      gl.uniform1f(gl.getUniformLocation(p, 'depthSpan'), s.depthSpan);
      this.attribute(p, 'xy', s.xy, 2);
      this.attribute(p, 'z', s.z, 1);
      this.attribute(p, 'partZ', s.partZ, 1);
      gl.bindBuffer(gl.ELEMENT_ARRAY_BUFFER, s.elements);
      gl.enable(gl.POLYGON_OFFSET_FILL);
      gl.polygonOffset(1, 1);
      gl.drawElements(gl.TRIANGLES, s.count, gl.UNSIGNED_INT, 0);
      gl.disable(gl.POLYGON_OFFSET_FILL);
      for (const loc of [0, 1, 2]) gl.disableVertexAttribArray(loc);
    }
    const mesh = (m, color, offset = [0, 0, 0]) => {
      gl.useProgram(this.meshProgram);
      gl.uniformMatrix4fv(gl.getUniformLocation(this.meshProgram, 'mvp'), false, mvp);
      gl.uniform4fv(gl.getUniformLocation(this.meshProgram, 'color'), color);
      gl.uniform3fv(gl.getUniformLocation(this.meshProgram, 'offset'), offset);
      gl.uniform3f(gl.getUniformLocation(this.meshProgram, 'light'), l[0] / ln, l[1] / ln, l[2] / ln);
      this.attribute(this.meshProgram, 'position', m.position);
      this.attribute(this.meshProgram, 'normal', m.normal);
      gl.enable(gl.POLYGON_OFFSET_FILL);
      gl.polygonOffset(1, 1);
      gl.drawArrays(gl.TRIANGLES, 0, m.count);
      gl.disable(gl.POLYGON_OFFSET_FILL);
      gl.disableVertexAttribArray(1);
    };
    if (this.part && this.show.part && !stockShown) mesh(this.part, [0.72, 0.74, 0.76, 1]);
    gl.useProgram(this.lineProgram);
    gl.uniformMatrix4fv(gl.getUniformLocation(this.lineProgram, 'mvp'), false, mvp);
    gl.disableVertexAttribArray(1);
    const colorLoc = gl.getUniformLocation(this.lineProgram, 'color');
    for (const line of Object.values(this.lines)) {
      if (!line.count || (!line.mark && !line.octants && !this.show.paths) || (line.octants && !this.show.octants) || (line.grid && !this.show.grid)) continue;
      gl.uniform4fv(colorLoc, line.color);
      this.attribute(this.lineProgram, 'position', line.buffer);
      gl.drawArrays(gl.LINES, 0, line.count);
    }
    if (this.show.paths) {
      for (const g of this.groups) {
        if (this.hiddenOps.has(g.op) || (g.rapid && this.hiddenOps.has('rapids'))) continue;
        const d = this.moving && g.thin ? g.thin : g;
        // The segments before the first of move `cutMoves` are cut: drawn full; the rest faint.
        const split = d.moves && Number.isFinite(this.cutMoves) ? lowerBound(d.moves, this.cutMoves) : d.count;
        this.attribute(this.lineProgram, 'position', d.buffer);
        if (split > 0) { gl.uniform4fv(colorLoc, g.color); gl.drawArrays(gl.LINES, 0, split * 2); }
        if (split < d.count) {
          gl.uniform4fv(colorLoc, [g.color[0], g.color[1], g.color[2], 0.22]);
          gl.drawArrays(gl.LINES, split * 2, (d.count - split) * 2);
        }
      }
    }
    if (this.tool?.at && this.show.tool) {
      gl.depthMask(false);
      mesh(this.tool, [0.55, 0.58, 0.62, 0.55], this.tool.at);
      gl.depthMask(true);
    }
    this.rendered = (this.rendered ?? 0) + 1;
  }

  attribute(program, name, buffer, size = 3) {
    const gl = this.gl, loc = gl.getAttribLocation(program, name);
    if (loc < 0) return;
    gl.bindBuffer(gl.ARRAY_BUFFER, buffer);
    gl.enableVertexAttribArray(loc);
    gl.vertexAttribPointer(loc, size, gl.FLOAT, false, 0, 0);
  }

  // The view is moving: draw the thinned paths until it settles, then the whole.
  moved() {
    this.moving = true;
    clearTimeout(this.settle);
    this.settle = setTimeout(() => { this.moving = false; this.draw(); }, SETTLE_MS);
    this.draw();
  }

  bindInput() {
    const c = this.canvas;
    let drag = null;
    c.addEventListener('contextmenu', (e) => e.preventDefault());
    c.addEventListener('pointerdown', (e) => { drag = { x: e.clientX, y: e.clientY, moved: 0, pan: e.shiftKey || e.button === 2 }; c.setPointerCapture(e.pointerId); });
    // A press and release that barely moved is a click: `onPick(x, y)` gets where (CSS pixels
    // from the canvas's top left corner).
    c.addEventListener('pointerup', (e) => {
      if (drag && drag.moved < 4 && e.button === 0 && this.onPick) {
        const r = c.getBoundingClientRect();
        this.onPick(e.clientX - r.left, e.clientY - r.top);
      }
      drag = null;
    });
    c.addEventListener('pointermove', (e) => {
      if (!drag) return;
      const dx = e.clientX - drag.x, dy = e.clientY - drag.y;
      drag.moved += Math.abs(dx) + Math.abs(dy);
      drag.x = e.clientX; drag.y = e.clientY;
      const cam = this.camera;
      if (drag.pan) {
        const s = cam.distance / c.clientHeight;
        const right = [-Math.sin(cam.yaw), Math.cos(cam.yaw), 0];
        const up = [-Math.sin(cam.pitch) * Math.cos(cam.yaw), -Math.sin(cam.pitch) * Math.sin(cam.yaw), Math.cos(cam.pitch)];
        for (let i = 0; i < 3; i++) cam.target[i] += (-dx * right[i] + dy * up[i]) * s;
      } else {
        cam.yaw -= dx * 0.01;
        cam.pitch = Math.max(-1.5695, Math.min(1.5695, cam.pitch + dy * 0.01));
      }
      this.moved();
    });
    c.addEventListener('wheel', (e) => {
      e.preventDefault();
      this.camera.distance *= Math.exp(e.deltaY * 0.001);
      this.moved();
    }, { passive: false });
  }
}

// Where the point (x, y, z) (mm) falls on a canvas W × H CSS pixels under the view matrix `m`:
// [x, y] from its top left corner, and the eye's w (not above 0: behind the eye).
function toCanvas(m, x, y, z, W, H) {
  const w = m[3] * x + m[7] * y + m[11] * z + m[15];
  return [((m[0] * x + m[4] * y + m[8] * z + m[12]) / w + 1) / 2 * W, (1 - (m[1] * x + m[5] * y + m[9] * z + m[13]) / w) / 2 * H, w];
}

// The first index of the sorted `values` not below `x`.
function lowerBound(values, x) {
  let lo = 0, hi = values.length;
  while (lo < hi) { const mid = (lo + hi) >> 1; if (values[mid] < x) lo = mid + 1; else hi = mid; }
  return lo;
}

function boxLines(b) {
  const [x0, y0, z0, x1, y1, z1] = b;
  const p = [[x0, y0], [x1, y0], [x1, y1], [x0, y1]];
  const out = [];
  for (let i = 0; i < 4; i++) {
    const [a, c] = [p[i], p[(i + 1) % 4]];
    out.push(a[0], a[1], z0, c[0], c[1], z0, a[0], a[1], z1, c[0], c[1], z1, a[0], a[1], z0, a[0], a[1], z1);
  }
  return new Float32Array(out);
}

// A round bar in the box `b` along its `axis` ('x', 'y' or 'z'): its two end circles (48 sides)
// and four lines along it, as line segments.
function barLines(b, { diameter, axis = 'z' }) {
  const k = { x: 0, y: 1, z: 2 }[axis] ?? 2, [u, v] = [0, 1, 2].filter((i) => i !== k);
  const c = [(b[0] + b[3]) / 2, (b[1] + b[4]) / 2, (b[2] + b[5]) / 2], r = diameter / 2, n = 48;
  const at = (end, a) => { const p = [...c]; p[k] = end; p[u] += r * Math.cos(a); p[v] += r * Math.sin(a); return p; };
  const out = [];
  for (const end of [b[k], b[k + 3]]) {
    for (let i = 0; i < n; i++) out.push(...at(end, (2 * Math.PI * i) / n), ...at(end, (2 * Math.PI * (i + 1)) / n));
  }
  for (let i = 0; i < 4; i++) out.push(...at(b[k], (Math.PI * i) / 2), ...at(b[k + 3], (Math.PI * i) / 2));
  return new Float32Array(out);
}

// A tool as triangles: its profile (radius at each height above the tip) turned about Z. The
// cutting part is its shape (a ball's half sphere, a bull nose's corner, a flat end's face, a
// drill's or V-bit's cone) up
// to its flute length, then the shank (its own diameter where given) up to the stick-out, or a
// shank as long again as the flutes, then its holder where it has one.
export function toolMesh(tool) {
  const r = tool.diameter / 2;
  const corner = tool.shape === 'ball' ? r : tool.shape === 'bullNose' ? Math.min(tool.cornerRadius ?? 0, r) : 0;
  const flutes = Math.max(tool.fluteLength ?? tool.diameter * 3, corner);
  const shankR = (tool.shankDiameter ?? tool.diameter) / 2;
  const top = Math.max(tool.stickOut ?? flutes * 2, flutes + 1e-3);
  const profile = [[0, 0]];
  const arc = 8;
  // A cone (drill, spot drill, V-bit): from its tip (a point, or a V-bit's flat) out to the full
  // diameter at its point angle.
  const cone = ['drill', 'spotDrill', 'vBit'].includes(tool.shape);
  const angle = tool.angle ?? (tool.shape === 'drill' ? 118 : 90);
  const tip = tool.shape === 'vBit' ? (tool.tipDiameter ?? 0) / 2 : 0;
  if (cone) profile.push([tip, 0], [r, (r - tip) / Math.tan((angle * Math.PI) / 360)]);
  else if (corner > 0) for (let k = 1; k <= arc; k++) { const a = (k / arc) * (Math.PI / 2); profile.push([r - corner + corner * Math.sin(a), corner - corner * Math.cos(a)]); }
  else profile.push([r, 0]);
  profile.push([r, flutes], [shankR, flutes], [shankR, top]);
  // Its holder, section by section from the nut's face up (a cone to its top diameter).
  let height = top;
  for (const s of tool.holder?.sections ?? []) {
    profile.push([s.diameter / 2, height], [(s.topDiameter ?? s.diameter) / 2, height + s.length]);
    height += s.length;
  }
  profile.push([0, height]);
  const sides = 24, positions = [], normals = [];
  for (let i = 0; i + 1 < profile.length; i++) {
    const [r0, z0] = profile[i], [r1, z1] = profile[i + 1];
    // The normal of the profile's piece in the (r, z) plane, turned with it.
    const [nr, nz] = [z1 - z0, -(r1 - r0)], nl = Math.hypot(nr, nz) || 1;
    for (let s = 0; s < sides; s++) {
      const a0 = (s / sides) * 2 * Math.PI, a1 = ((s + 1) / sides) * 2 * Math.PI;
      const p = (rr, z, a) => [rr * Math.cos(a), rr * Math.sin(a), z];
      const n = (a) => [(nr / nl) * Math.cos(a), (nr / nl) * Math.sin(a), nz / nl];
      const quad = [[p(r0, z0, a0), n(a0)], [p(r1, z1, a0), n(a0)], [p(r1, z1, a1), n(a1)], [p(r0, z0, a0), n(a0)], [p(r1, z1, a1), n(a1)], [p(r0, z0, a1), n(a1)]];
      for (const [pos, nor] of quad) { positions.push(...pos); normals.push(...nor); }
    }
  }
  return { positions: new Float32Array(positions), normals: new Float32Array(normals), height };
}
