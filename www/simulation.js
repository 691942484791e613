// The simulated program under the view: the scrubber over the program's time (its clock the
// program head's, tool changes included), play at a chosen speed, a step a move back or on, the
// tool drawn where it is, the path already cut apart from the path to come, the G-code line of
// the move in the pane, and the material removal rate over the program.
import { $, state, hooks, clock, clockFormat, ops } from './state.js';
import { opColor } from './viewer.js';
import * as units from './units.js';

export const sim = { data: null, time: 0, playing: false, busy: false, wanted: null, shown: -1, target: 0, marks: [], buckets: null, peak: 1, pane: null };

// The move running at time `t`: `k`, the first move with times[k] <= t < times[k + 1], and how
// far into it (`f`); past the end, the last move, finished.
export function moveAt(t) {
  const times = sim.data.times, n = times.length - 1;
  if (n <= 0) return { k: 0, f: 1, done: 0 };
  if (t >= times[n]) return { k: n - 1, f: 1, done: n };
  let lo = 0, hi = n - 1;
  while (lo < hi) { const mid = (lo + hi + 1) >> 1; if (times[mid] <= t) lo = mid; else hi = mid - 1; }
  const span = times[lo + 1] - times[lo];
  const f = span > 0 ? Math.min(1, Math.max(0, (t - times[lo]) / span)) : 1;
  return { k: lo, f, done: f >= 1 ? lo + 1 : lo };
}

// The stock after the moves done at `t`, the tool a fraction into the move running then (or at
// the end of move `end`, where given: moves that take no time share their time with the next);
// one request to the worker at a time, the latest wanted after it.
async function seek(t, end = null) {
  if (sim.busy) { sim.wanted = [t, end]; return; }
  sim.busy = true;
  try {
    const { k, f, done } = end === null ? moveAt(t) : { k: end, f: 1, done: end + 1 };
    const r = await state.engine.call({ type: 'seek', count: done, at: k, f, setup: state.shownSetup });
    if (done !== sim.shown) state.viewer?.updateStock(r.tops);
    sim.shown = done;
    showRestArea();
    if (r.tool.length) {
      state.viewer?.setToolAt(r.tool.slice(0, 3));
      if (r.tool[3] !== sim.toolNumber) {
        sim.toolNumber = r.tool[3];
        state.viewer?.setTool(state.tools.find((t) => t.number === sim.toolNumber) ?? null);
        state.viewer?.setToolAt(r.tool.slice(0, 3));
      }
    }
    state.viewer?.setCut(done >= sim.data.times.length - 1 ? Infinity : done);
    document.body.dataset.simMoves = String(done);
    const lines = state.result?.moveLines;
    if (lines?.length) sim.pane?.setCurrent(lines[Math.min(k, lines.length - 1)]);
  } catch (e) {
    if (e.message !== 'cancelled by the user') hooks.error?.(e.message);
  } finally {
    sim.busy = false;
  }
  if (sim.wanted !== null) { const next = sim.wanted; sim.wanted = null; seek(...next); }
}

// The rest areas' extent under the scrubber, while they are shown (and on the page's body for
// its tests, with the move it was measured after).
export function showRestArea() {
  const on = Boolean(state.viewer?.show.rest && state.viewer.stock);
  $('rest-area').hidden = !on;
  if (!on) return;
  const area = state.viewer.restArea();
  $('rest-area').textContent = `${units.area(area)} left`;
  document.body.dataset.restArea = String(area);
  document.body.dataset.restAreaAt = String(sim.shown);
}

// The rest areas the operation `index` starts from: the stock scrubbed to its first move, the
// places where more than the tolerance is left shown.
export function showRestAreas(index) {
  const mark = sim.marks.find((m) => m.index === index);
  if (!mark || !state.viewer) return;
  $('show-rest').checked = true;
  state.viewer.show.rest = true;
  if (mark.start > 0) setTime(mark.t, mark.start - 1);
  else setTime(0);
}

export function setTime(t, end = null) {
  if (!sim.data) return;
  const total = sim.data.times[sim.data.times.length - 1];
  // (The scrubber's value is text: the end may come back a hair short of it.)
  sim.time = total - t < 1e-9 * Math.max(1, total) ? total : Math.max(0, t);
  $('scrub').value = sim.time;
  $('sim-time').textContent = `${clock(sim.time)} / ${clock(total)} ${clockFormat(total)}`;
  drawMrr();
  // The moves done once this request is seen to (before it is: a second step counts from it).
  sim.target = end === null ? moveAt(sim.time).done : end + 1;
  seek(sim.time, end);
}

// One move back or on: the stock and the tool at the end of the move after the last one done,
// or of the one before it (by move, not by time: some moves take no time at all).
export function step(direction) {
  if (!sim.data) return;
  const times = sim.data.times, n = times.length - 1;
  const end = Math.max(-1, Math.min(n - 1, sim.target - 1 + direction));
  if (end < 0) setTime(0);
  else setTime(times[end + 1], end);
}

// The end of the move whose G-code is on line `line` (a click in the program's pane).
export function toLine(line) {
  const lines = state.result?.moveLines;
  if (!sim.data || !lines?.length) return;
  let lo = 0, hi = lines.length - 1;
  while (lo < hi) { const mid = (lo + hi) >> 1; if (lines[mid] < line) lo = mid + 1; else hi = mid; }
  setTime(sim.data.times[lo + 1], lo);
}

export function play() {
  if (!sim.data) return;
  const total = sim.data.times[sim.data.times.length - 1];
  if (!sim.playing && sim.time >= total) sim.time = 0;
  sim.playing = !sim.playing;
  $('play').textContent = sim.playing ? '❚❚' : '▶';
  let last = performance.now();
  const frame = (now) => {
    if (!sim.playing) return;
    const dt = (now - last) / 1000;
    last = now;
    setTime(sim.time + dt * Number($('speed').value));
    if (sim.time >= total) {
      sim.playing = false;
      $('play').textContent = '▶';
      // A setup's program over, the next setup's plays on from the stock it left.
      const next = state.shownSetup == null ? null : state.shownSetup + 1;
      if (next !== null && state.results?.[next]) hooks.playSetup?.(next);
      return;
    }
    requestAnimationFrame(frame);
  };
  requestAnimationFrame(frame);
}

// The measured engagement's colour on the removal rate's plot.
const ENGAGEMENT = 'rgb(174, 62, 201)';

export function drawMrr() {
  const c = $('mrr');
  if (!sim.data) return;
  const dpr = window.devicePixelRatio || 1, w = Math.max(1, Math.round(c.clientWidth * dpr)), h = Math.round(60 * dpr);
  if (c.width !== w || c.height !== h) { c.width = w; c.height = h; sim.buckets = null; }
  const { times, mrr } = sim.data, total = times[times.length - 1] || 1;
  if (!sim.buckets) {
    const b = new Float32Array(w);
    for (let k = 0; k < mrr.length; k++) {
      const x = Math.min(w - 1, Math.floor((times[k] / total) * w));
      if (mrr[k] > b[x]) b[x] = mrr[k];
    }
    sim.buckets = b;
    sim.peak = b.reduce((m, v) => Math.max(m, v), 0) || 1;
    // Each operation's measured engagement (degrees), its least and most per column.
    for (const m of sim.marks) {
      if (!m.engagement) continue;
      const lo = new Float32Array(w).fill(Infinity), hi = new Float32Array(w).fill(-Infinity);
      m.engagement.moves.forEach((a, i) => {
        const t = times[m.start + i];
        if (a == null || t == null) return;
        const x = Math.min(w - 1, Math.floor((t / total) * w));
        lo[x] = Math.min(lo[x], a);
        hi[x] = Math.max(hi[x], a);
      });
      m.columns = { lo, hi };
    }
  }
  const g = c.getContext('2d');
  g.clearRect(0, 0, w, h);
  g.fillStyle = '#6b8fb8';
  for (let x = 0; x < w; x++) { const v = (sim.buckets[x] / sim.peak) * (h - 14 * dpr); g.fillRect(x, h - v, 1, v); }
  g.fillStyle = '#394550';
  g.font = `${11 * dpr}px system-ui`;
  g.fillText(`material removal rate, peak ${units.volume(sim.peak)}/min`, 4 * dpr, 11 * dpr);
  // Operations that hold a load (seed 004): the reference rate at a full step-down, dashed,
  // and the plain path's rate before the correction (its windows spread over the operation's
  // time), faint: the paper's Fig. 14.
  sim.marks.forEach((m, k) => {
    if (!m.load) return;
    const end = k + 1 < sim.marks.length ? sim.marks[k + 1].t : total;
    const [x0, x1] = [(m.t / total) * w, (end / total) * w];
    const y = (v) => h - (v / sim.peak) * (h - 14 * dpr);
    const plain = m.load.plain;
    if (plain.length) {
      g.strokeStyle = 'rgba(57, 69, 80, 0.35)';
      g.lineWidth = dpr;
      g.beginPath();
      plain.forEach((r, i) => { const x = x0 + ((x1 - x0) * i) / plain.length, v = y(Math.min(r * m.load.rate, sim.peak)); if (i) g.lineTo(x, v); else g.moveTo(x, v); });
      g.stroke();
    }
    g.strokeStyle = '#2b8a3e';
    g.lineWidth = dpr;
    g.setLineDash([4 * dpr, 3 * dpr]);
    g.beginPath();
    g.moveTo(x0, y(m.load.rate));
    g.lineTo(x1, y(m.load.rate));
    g.stroke();
    g.setLineDash([]);
    g.fillStyle = '#2b8a3e';
    g.fillText(`even load ${Math.round(m.load.rate).toLocaleString()}`, x0 + 3 * dpr, Math.max(11 * dpr, y(m.load.rate) - 3 * dpr));
  });
  // Operations that hold an engagement (adaptive clearing): each cutting move's engagement as
  // the simulation measured it (0–90° over the plot's height; a column spans its least and
  // most), the target dashed, and how much of the cut keeps within ±10 % of it.
  sim.marks.forEach((m, k) => {
    const e = m.engagement;
    if (!e || !m.columns) return;
    const end = k + 1 < sim.marks.length ? sim.marks[k + 1].t : total;
    const [x0, x1] = [(m.t / total) * w, (end / total) * w];
    const y = (deg) => h - (Math.min(deg, 90) / 90) * (h - 14 * dpr);
    g.fillStyle = ENGAGEMENT;
    for (let x = 0; x < w; x++) {
      if (!(m.columns.hi[x] >= 0)) continue;
      const top = y(m.columns.hi[x]);
      g.fillRect(x, top - dpr, 1, Math.max(2 * dpr, y(m.columns.lo[x]) - top + dpr));
    }
    g.strokeStyle = ENGAGEMENT;
    g.lineWidth = dpr;
    g.setLineDash([4 * dpr, 3 * dpr]);
    g.beginPath();
    g.moveTo(x0, y(e.target));
    g.lineTo(x1, y(e.target));
    g.stroke();
    g.setLineDash([]);
    const text = `engagement (target ${e.target.toFixed(1)}°): ${Math.round(100 * e.within)} % within ±10 %, peak ${Math.round(e.peak)}°`;
    g.fillStyle = 'rgba(255, 255, 255, 0.85)';
    g.fillRect(x0 + 2 * dpr, 14 * dpr, g.measureText(text).width + 2 * dpr, 13 * dpr);
    g.fillStyle = ENGAGEMENT;
    g.fillText(text, x0 + 3 * dpr, 25 * dpr);
  });
  // The operations: a line in each one's colour where it starts, and its name on a light
  // ground, in the lowest of two rows where it clears the names before it; where neither row
  // has room before the next operation's line, shortened with an ellipsis (its whole name in
  // the plot's tooltip). Where the names went is kept on the canvas for the page tests.
  const rows = [h - 3 * dpr, h - 17 * dpr], ends = [-Infinity, -Infinity], labels = [];
  sim.marks.forEach((m, k) => {
    const mx = Math.round((m.t / total) * w), c = opColor(m.index).slice(0, 3).map((v) => Math.round(v * 255));
    g.fillStyle = `rgb(${c.join(',')})`;
    g.fillRect(mx, 0, dpr, h);
    if (sim.marks.length < 2) return;
    const x0 = mx + 3 * dpr, next = k + 1 < sim.marks.length ? (sim.marks[k + 1].t / total) * w : w;
    let text = m.name, width = g.measureText(text).width;
    const free = ends.map((end) => end + 4 * dpr <= x0), rooms = [Math.max(0, next - 2 * dpr - x0), w - x0];
    const row = free[0] && width <= rooms[0] ? 0 : free[1] && width <= rooms[1] ? 1 : free[0] ? 0 : free[1] ? 1 : -1;
    if (row < 0) return;
    while (width > rooms[row] && text.length > 1) {
      text = `${text.replace(/…$/, '').slice(0, -1)}…`;
      width = g.measureText(text).width;
    }
    if (width > rooms[row]) return;
    g.fillStyle = 'rgba(255, 255, 255, 0.85)';
    g.fillRect(x0 - dpr, rows[row] - 11 * dpr, width + 2 * dpr, 13 * dpr);
    g.fillStyle = `rgb(${c.join(',')})`;
    g.fillText(text, x0, rows[row]);
    ends[row] = x0 + width;
    labels.push({ name: m.name, text, row, x0: x0 / dpr, x1: (x0 + width) / dpr });
  });
  c.dataset.labels = JSON.stringify(labels);
  c.title = sim.marks.map((m) => m.name).join(' · ');
  const x = (sim.time / total) * w;
  g.fillStyle = '#d9480f';
  g.fillRect(x - dpr, 0, 2 * dpr, h);
}

// The simulation of a run (`data`: the result's `sim`, `summary` its summary), or none.
export function showSimulation(data, summary = null) {
  sim.data = data;
  // Where each operation starts in program time, for the marks on the plot.
  sim.marks = data && summary
    ? summary.operationStarts.map((m, k) => ({ t: data.times[m], start: m, name: summary.operations[k].name, index: summary.operations[k].index, load: summary.operations[k].load, engagement: summary.operations[k].engagement }))
    : [];
  sim.buckets = null;
  sim.playing = false;
  sim.toolNumber = null;
  $('play').textContent = '▶';
  $('sim').hidden = !data;
  if (!data) return;
  const total = data.times[data.times.length - 1];
  $('scrub').max = total;
  const r = data.report;
  $('sim-report').textContent = units.words(r.text.trim());
  $('sim-report').className = r.gougeCount + r.rapidCollisionCount + r.bodyCollisionCount + r.holderCollisionCount + r.fixtureCollisionCount > 0 ? 'result problem' : 'result';
  // A V-carve is judged by its depths: coloured so from the start (the box turns it off).
  const carved = ops().some((o) => o.kind === 'vcarve' && o.enabled !== false);
  $('show-depth').checked = carved;
  if (state.viewer) state.viewer.show.depth = carved;
  state.viewer?.setStock(data.grid, data.part, data.start);
  state.lastSimGrid = data.grid;
  // The stock as the run sent it: after the last move.
  sim.shown = data.times.length - 1;
  document.body.dataset.simMoves = String(sim.shown);
  state.viewer?.setMarks(data.findings);
  // Show the finished cut first; the scrubber goes back from there.
  setTime(total);
}
