// WebGL2 view of the part (shaded) and the tool path (lines): orbit, pan, zoom. Z is up.

const MESH_VS = `#version 300 es
in vec3 position; in vec3 normal;
uniform mat4 mvp; out vec3 vNormal;
void main() { vNormal = normal; gl_Position = mvp * vec4(position, 1.0); }`;
const MESH_FS = `#version 300 es
precision highp float;
in vec3 vNormal; uniform vec3 color; uniform vec3 light; out vec4 outColor;
void main() {
  float d = abs(dot(normalize(vNormal), light));
  outColor = vec4(color * (0.35 + 0.65 * d), 1.0);
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
// blue where material is left, tan elsewhere; off the part, plain stock colour.
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
uniform vec3 light; uniform float tol; out vec4 outColor;
void main() {
  vec3 n = normalize(cross(dFdx(world), dFdy(world)));
  float d = abs(dot(n, light));
  vec3 base = vec3(0.80, 0.72, 0.58);
  if (onPart > 0.5) {
    if (left < -tol) base = vec3(0.86, 0.10, 0.10);
    else base = mix(base, vec3(0.20, 0.42, 0.85), clamp((left - 0.02) / 1.0, 0.0, 1.0));
  }
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

// Colours of the operations' cutting moves, in order (the first is the classic path blue).
export const OP_COLORS = [[0.106, 0.455, 0.82, 1], [0.62, 0.2, 0.75, 1], [0.0, 0.6, 0.55, 1], [0.75, 0.6, 0.0, 1], [0.5, 0.3, 0.15, 1]];

// Loops picked for an operation (a bright blue, apart from the outlines' green and the holes'
// orange).
export const PICKED_COLOR = [0.0, 0.75, 1.0, 1];
const PICKED_LIFT = 0.05; // mm

// The view's vertical angle (radians).
const FOV_Y = 0.7;

// Colours of the tools an octree roughing chose, by tool number (its paths and its octants).
export const TOOL_COLORS = [[0.85, 0.2, 0.15, 1], [0.1, 0.6, 0.2, 1], [0.95, 0.55, 0.0, 1], [0.45, 0.25, 0.8, 1], [0.0, 0.55, 0.75, 1], [0.8, 0.15, 0.55, 1]];
export const toolColor = (number) => TOOL_COLORS[(Math.max(1, number) - 1) % TOOL_COLORS.length];

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
    this.show = { part: true, paths: true, stock: true, octants: true };
    this.part = null;
    this.lines = {};
    this.camera = { yaw: -0.9, pitch: 0.75, distance: 200, target: [0, 0, 0] };
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
    this.dropPart();
    this.part = { position: this.buffer(part.positions), normal: this.buffer(part.normals), count: part.positions.length / 3 };
    if (frame) this.frame(part.bounds);
    this.draw();
  }

  // Cutting moves in their operation's colour (`ops`: the operation of each segment, as
  // `OP_COLORS` indexes them), or in their tool's for the operations in `byTool` (octree
  // roughing; `tools`: the tool of each segment), rapids in orange.
  setPaths(feeds, rapids, stock, ops = null, tools = null, byTool = new Set()) {
    this.dropLines((key) => key.startsWith('feeds') || key.startsWith('octants') || key === 'rapids' || key === 'stock');
    // An operation's segments (a stage's, for octree roughing) follow each other in the
    // program: take them as runs, and copy only a colour that comes back after another.
    const groups = new Map();
    const n = feeds.length / 6;
    for (let start = 0; start < n;) {
      const op = ops ? ops[start] : 0, tool = tools ? tools[start] : 0, split = tools && byTool.has(op);
      let end = start + 1;
      while (end < n && (ops ? ops[end] : 0) === op && (!split || tools[end] === tool)) end++;
      const key = split ? `t${tool}` : `${op}`;
      if (!groups.has(key)) groups.set(key, []);
      groups.get(key).push(feeds.subarray(start * 6, end * 6));
      start = end;
    }
    for (const [key, runs] of groups) {
      let data = runs[0];
      if (runs.length > 1) {
        data = new Float32Array(runs.reduce((sum, r) => sum + r.length, 0));
        runs.reduce((at, r) => { data.set(r, at); return at + r.length; }, 0);
      }
      const color = key.startsWith('t') ? toolColor(Number(key.slice(1))) : OP_COLORS[Number(key) % OP_COLORS.length];
      this.setLine(`feeds${key}`, { buffer: this.buffer(data), count: data.length / 3, color });
    }
    this.setLine('rapids', { buffer: this.buffer(rapids), count: rapids.length / 3, color: [0.85, 0.28, 0.06, 0.9] });
    if (stock) this.setLine('stock', { buffer: this.buffer(boxLines(stock)), count: 24, color: [0.35, 0.4, 0.45, 0.6] });
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
    if (frame) this.frame(d.bounds);
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

  // Where the point `p` (mm) appears on the canvas, in CSS pixels from its top left corner
  // (null behind the eye).
  project(p) {
    const m = this.matrix();
    const x = m[0] * p[0] + m[4] * p[1] + m[8] * p[2] + m[12];
    const y = m[1] * p[0] + m[5] * p[1] + m[9] * p[2] + m[13];
    const w = m[3] * p[0] + m[7] * p[1] + m[11] * p[2] + m[15];
    if (!(w > 0)) return null;
    return [((x / w + 1) / 2) * this.canvas.clientWidth, ((1 - y / w) / 2) * this.canvas.clientHeight];
  }

  clearPaths() {
    this.dropLines(() => true);
    this.dropStock();
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
    for (let k = 0; k < part.length; k++) partZ[k] = Number.isNaN(part[k]) ? -1e9 : part[k];
    this.dropStock();
    const z = gl.createBuffer();
    gl.bindBuffer(gl.ARRAY_BUFFER, z);
    gl.bufferData(gl.ARRAY_BUFFER, tops, gl.DYNAMIC_DRAW);
    const g = this.stockGrid;
    this.stock = { xy: g.xy, z, partZ: this.buffer(partZ), elements: g.elements, count: g.count, tol };
    this.draw();
  }

  updateStock(tops) {
    if (!this.stock) return;
    const gl = this.gl;
    gl.bindBuffer(gl.ARRAY_BUFFER, this.stock.z);
    gl.bufferSubData(gl.ARRAY_BUFFER, 0, tops);
    this.draw();
  }

  // Places verification found (x, y, z, kind per place) as crosses; the tool at `tool` (or none).
  setMarks(findings, tool, toolLength = 30) {
    const colors = [[0.86, 0.1, 0.1, 1], [0.75, 0.1, 0.75, 1], [0.95, 0.55, 0.05, 1]];
    for (let kind = 0; kind < 3; kind++) {
      const out = [];
      for (let k = 0; k < findings.length; k += 4) {
        if (findings[k + 3] !== kind) continue;
        const [x, y, z] = [findings[k], findings[k + 1], findings[k + 2]], s = 1.5;
        out.push(x - s, y, z, x + s, y, z, x, y - s, z, x, y + s, z, x, y, z - s, x, y, z + s);
      }
      this.setLine(`marks${kind}`, { buffer: this.buffer(new Float32Array(out)), count: out.length / 3, color: colors[kind], mark: true });
    }
    if (tool) this.setLine('tool', { buffer: this.buffer(new Float32Array([tool[0], tool[1], tool[2], tool[0], tool[1], tool[2] + toolLength])), count: 2, color: [0.1, 0.1, 0.1, 1], mark: true });
    this.draw();
  }

  // Looks at the box `b` ([minX, minY, minZ, maxX, maxY, maxZ]) from as far as its bounding
  // sphere needs to fit the view's narrower angle, whatever its proportions (a tall part, a
  // cube) and the canvas's.
  frame(b) {
    const radius = Math.max(0.5 * Math.hypot(b[3] - b[0], b[4] - b[1], b[5] - b[2]), 0.5);
    this.camera.target = [(b[0] + b[3]) / 2, (b[1] + b[4]) / 2, (b[2] + b[5]) / 2];
    const aspect = (this.canvas.clientWidth || 1) / Math.max(this.canvas.clientHeight || 1, 1);
    const half = Math.min(FOV_Y, 2 * Math.atan(Math.tan(FOV_Y / 2) * aspect)) / 2;
    this.camera.distance = (1.08 * radius) / Math.sin(half);
  }

  matrix() {
    const { yaw, pitch, distance, target } = this.camera;
    const eye = [
      target[0] + distance * Math.cos(pitch) * Math.cos(yaw),
      target[1] + distance * Math.cos(pitch) * Math.sin(yaw),
      target[2] + distance * Math.sin(pitch),
    ];
    const aspect = this.canvas.width / Math.max(this.canvas.height, 1);
    return multiply(perspective(FOV_Y, aspect, distance / 100, distance * 20), lookAt(eye, target, [0, 0, 1]));
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

  draw() {
    if (this.held) return;
    const gl = this.gl, canvas = this.canvas;
    const dpr = window.devicePixelRatio || 1;
    const w = Math.max(1, Math.round(canvas.clientWidth * dpr)), h = Math.max(1, Math.round(canvas.clientHeight * dpr));
    if (canvas.width !== w || canvas.height !== h) { canvas.width = w; canvas.height = h; }
    gl.viewport(0, 0, w, h);
    gl.clearColor(0.93, 0.945, 0.955, 1);
    gl.clear(gl.COLOR_BUFFER_BIT | gl.DEPTH_BUFFER_BIT);
    gl.enable(gl.DEPTH_TEST);
    const mvp = this.matrix();
    const l = [0.4, -0.5, 0.77], ln = Math.hypot(...l);
    const stockShown = this.stock && this.show.stock;
    if (stockShown) {
      const p = this.stockProgram, s = this.stock;
      gl.useProgram(p);
      gl.uniformMatrix4fv(gl.getUniformLocation(p, 'mvp'), false, mvp);
      gl.uniform3f(gl.getUniformLocation(p, 'light'), l[0] / ln, l[1] / ln, l[2] / ln);
      gl.uniform1f(gl.getUniformLocation(p, 'tol'), s.tol);
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
    if (this.part && this.show.part && !stockShown) {
      gl.useProgram(this.meshProgram);
      gl.uniformMatrix4fv(gl.getUniformLocation(this.meshProgram, 'mvp'), false, mvp);
      gl.uniform3f(gl.getUniformLocation(this.meshProgram, 'color'), 0.72, 0.74, 0.76);
      gl.uniform3f(gl.getUniformLocation(this.meshProgram, 'light'), l[0] / ln, l[1] / ln, l[2] / ln);
      this.attribute(this.meshProgram, 'position', this.part.position);
      this.attribute(this.meshProgram, 'normal', this.part.normal);
      gl.enable(gl.POLYGON_OFFSET_FILL);
      gl.polygonOffset(1, 1);
      gl.drawArrays(gl.TRIANGLES, 0, this.part.count);
      gl.disable(gl.POLYGON_OFFSET_FILL);
    }
    gl.useProgram(this.lineProgram);
    gl.uniformMatrix4fv(gl.getUniformLocation(this.lineProgram, 'mvp'), false, mvp);
    gl.disableVertexAttribArray(1);
    for (const line of Object.values(this.lines)) {
      if (!line.count || (!line.mark && !line.octants && !this.show.paths) || (line.octants && !this.show.octants)) continue;
      gl.uniform4fv(gl.getUniformLocation(this.lineProgram, 'color'), line.color);
      this.attribute(this.lineProgram, 'position', line.buffer);
      gl.drawArrays(gl.LINES, 0, line.count);
    }
  }

  attribute(program, name, buffer, size = 3) {
    const gl = this.gl, loc = gl.getAttribLocation(program, name);
    if (loc < 0) return;
    gl.bindBuffer(gl.ARRAY_BUFFER, buffer);
    gl.enableVertexAttribArray(loc);
    gl.vertexAttribPointer(loc, size, gl.FLOAT, false, 0, 0);
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
        cam.pitch = Math.max(-1.55, Math.min(1.55, cam.pitch + dy * 0.01));
      }
      this.draw();
    });
    c.addEventListener('wheel', (e) => {
      e.preventDefault();
      this.camera.distance *= Math.exp(e.deltaY * 0.001);
      this.draw();
    }, { passive: false });
  }
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
