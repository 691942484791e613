"""Where a z-level roughing program's time goes, and the most removal efficiency its levels allow.

Issue 12's removal efficiency is volume removed / (cycle time x feed x step-over x step-down).
This script simulates a flat end's program on a height grid of its own (independent of swarf's
simulation, 0.1 mm cells, the stock the part's box) and, for the moves at a constant height
(level cutting):

- the plan area swept where material stood (each cell whose top a level move lowers, once per
  level) and the volume removed: with the radial engagement held to the step-over w, sweeping
  area A takes at least A / w of feed, so no program cutting these levels without slotting can
  exceed an efficiency of V / (A x step-down) (the mean thickness removed over the step-down);
- the level feed by engagement (new plan area per mm of feed): how much cut nothing, how much
  under half the step-over, ...

    python3 -m venv /tmp/venv && /tmp/venv/bin/pip install numpy numpy-stl
    /tmp/venv/bin/python scripts/rough-bound.py PROGRAM.ngc PART.stl [DIAMETER STEPOVER STEPDOWN]

Defaults: issue 12's settings, a 6 mm flat end, step-over 2.4 mm, step-down 2 mm. Reads G0-G3
(arcs in the XY plane, I and J relative), millimetres, absolute coordinates.
"""
import math
import re
import sys

import numpy as np
from stl import mesh as stlmesh

program, part = sys.argv[1], sys.argv[2]
diameter, stepover, stepdown = (float(a) for a in (sys.argv[3:6] if len(sys.argv) >= 6 else (6, 2.4, 2)))
r, cell, sample = diameter / 2, 0.1, 0.1
vertices = stlmesh.Mesh.from_file(part).vectors.reshape(-1, 3)
lo, hi = vertices.min(0), vertices.max(0)
nx, ny = int((hi[0] - lo[0]) / cell) + 1, int((hi[1] - lo[1]) / cell) + 1
top = np.full((ny, nx), hi[2])
k = int(math.ceil(r / cell))
swept = removed = removed_descending = 0.0


def cut(x, y, z, level):
    """The tool's disc at (x, y) with its tip at z: lowers the cells above z; at a level, counts
    the area of cells lowered by more than 0.01 mm."""
    global swept, removed, removed_descending
    i, j = int(round((x - lo[0]) / cell)), int(round((y - lo[1]) / cell))
    i0, i1, j0, j1 = max(i - k, 0), min(i + k + 1, nx), max(j - k, 0), min(j + k + 1, ny)
    if i0 >= i1 or j0 >= j1:
        return
    cx, cy = lo[0] + np.arange(i0, i1) * cell, lo[1] + np.arange(j0, j1) * cell
    block = top[j0:j1, i0:i1]
    hit = ((cx[None, :] - x) ** 2 + (cy[:, None] - y) ** 2 <= r * r) & (block > z + 1e-9)
    if not hit.any():
        return
    depth = block[hit] - z
    if level:
        swept += (depth > 0.01).sum() * cell * cell
        removed += depth.sum() * cell * cell
    else:
        removed_descending += depth.sum() * cell * cell
    block[hit] = z


def points(start, end, mode, words):
    """Points every `sample` mm along a move, its end included; and its length."""
    if mode in (2, 3) and ("I" in words or "J" in words):
        cx, cy = start[0] + words.get("I", 0.0), start[1] + words.get("J", 0.0)
        a0 = math.atan2(start[1] - cy, start[0] - cx)
        a1 = math.atan2(end[1] - cy, end[0] - cx)
        radius = math.hypot(start[0] - cx, start[1] - cy)
        while mode == 2 and a1 >= a0 - 1e-12:
            a1 -= 2 * math.pi
        while mode == 3 and a1 <= a0 + 1e-12:
            a1 += 2 * math.pi
        length = abs(a1 - a0) * radius
        n = max(1, int(length / sample))
        return [(cx + radius * math.cos(a0 + (a1 - a0) * s / n), cy + radius * math.sin(a0 + (a1 - a0) * s / n), start[2] + (end[2] - start[2]) * s / n) for s in range(1, n + 1)], length
    length = math.dist(start, end)
    n = max(1, int(length / sample))
    return [tuple(start[q] + (end[q] - start[q]) * s / n for q in range(3)) for s in range(1, n + 1)], length


at, mode, fed, level_moves = [0.0, 0.0, hi[2] + 10.0], 0, 0.0, []
for line in open(program):
    line = line.split("(")[0].split(";")[0].strip().upper()
    for g in re.findall(r"G0*(\d+)", line):
        if g in ("0", "1", "2", "3"):
            mode = int(g)
    words = {a: float(b) for a, b in re.findall(r"([XYZIJ])\s*(-?[\d.]+)", line)}
    if not any(a in words for a in "XYZ"):
        continue
    end = [words.get("X", at[0]), words.get("Y", at[1]), words.get("Z", at[2])]
    if mode != 0:
        pts, length = points(at, end, mode, words)
        fed += length
        level = abs(end[2] - at[2]) < 1e-6
        before = swept
        for p in pts:
            cut(*p, level)
        if level and length > 0:
            level_moves.append(((swept - before) / length, length))
    at = end

moves = np.array(level_moves)
print(f"{program}: fed {fed / 1000:.2f} m, of it {moves[:, 1].sum() / 1000:.2f} m at a level; removed {removed:.0f} mm3 at levels, {removed_descending:.0f} mm3 descending")
print(f"  area swept where material stood {swept:.0f} mm2: at least {swept / stepover / 1000:.2f} m of level feed at the step-over")
print(f"  mean thickness removed {removed / swept:.2f} mm of {stepdown:g}: removal efficiency at most {removed / (swept * stepdown):.3f} without slotting")
print("  level feed by engagement (mm of new plan area per mm of feed):")
for a, b in [(0, 0.05), (0.05, stepover / 2), (stepover / 2, 0.85 * stepover), (0.85 * stepover, 1.1 * stepover), (1.1 * stepover, 0.7 * diameter), (0.7 * diameter, diameter + 1)]:
    inside = (moves[:, 0] >= a) & (moves[:, 0] < b)
    print(f"    {a:5.2f} to {b:5.2f}: {moves[inside, 1].sum() / 1000:6.2f} m, {np.dot(moves[inside, 0], moves[inside, 1]):8.0f} mm2")
idle = moves[moves[:, 0] < 0.05]
print(f"  moves cutting nothing: {idle[:, 1].sum() / 1000:.2f} m, {(idle[:, 1] > 3).sum()} over 3 mm long ({idle[idle[:, 1] > 3, 1].sum() / 1000:.2f} m)")
