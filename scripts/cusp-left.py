#!/usr/bin/env python3
"""What a finishing program leaves on the part beyond what its ball must (issue 60's cusp target,
measured outside swarf). The program is interpreted by LinuxCNC's rs274 and cut into a dexel
stock by ../shared/tools/gsim.py's own cutter model; the ideal is the surface a perfect ball
of the finishing tool's radius leaves (the part's heights closed by the ball: the lowest its
tip reaches, then the ball's envelope over that), so that corners the ball cannot enter do not
count. What is left above the ideal, along the ideal's normal, is summarised over the cells on
the part, the steep and the shallow apart.

usage: cusp-left.py PROGRAM.ngc --mesh PART.stl --tool flat:6 --tool ball:6 --ball 6
                    [--cell 0.1] [--stock-margin 5,1,0] [--steep 30]
"""
import argparse, json, math, os, sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "shared", "tools"))
from gcheck import run_rs274, sample  # noqa: E402
from gsim import bottom, kernel, moves_with_feed, part_heights, read_mesh  # noqa: E402


def shifted(a, di, dj, fill):
    """a shifted so that out[j, i] = a[j + dj, i + di] (fill outside)."""
    ny, nx = a.shape
    out = np.full_like(a, fill)
    ys, yd = (slice(dj, ny), slice(0, ny - dj)) if dj >= 0 else (slice(0, ny + dj), slice(-dj, ny))
    xs, xd = (slice(di, nx), slice(0, nx - di)) if di >= 0 else (slice(0, nx + di), slice(-di, nx))
    out[yd, xd] = a[ys, xs]
    return out


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("program")
    ap.add_argument("--mesh", required=True)
    ap.add_argument("--tool", action="append", required=True)
    ap.add_argument("--ball", type=float, required=True, help="the finishing ball's diameter")
    ap.add_argument("--cell", type=float, default=0.1)
    ap.add_argument("--stock-margin", default="5,1,0")
    ap.add_argument("--steep", type=float, default=30.0)
    a = ap.parse_args()
    tools = {}
    for n, spec in enumerate(a.tool, 1):
        p = spec.split(":")
        tools[n] = (p[0], float(p[1]), float(p[2]) if len(p) > 2 else 0.0)
    code, canon, errs = run_rs274(a.program, tools)
    if code != 0 or errs:
        sys.exit(f"rs274 rejected the program: {errs[0] if errs else code}")
    tris = read_mesh(a.mesh)
    lo, hi = tris.reshape(-1, 3).min(axis=0), tris.reshape(-1, 3).max(axis=0)
    mxy, mtop, mbot = (float(v) for v in a.stock_margin.split(","))
    smin, smax = lo - np.array([mxy, mxy, mbot]), hi + np.array([mxy, mxy, mtop])
    cell = a.cell
    nx, ny = int(math.ceil((smax[0] - smin[0]) / cell)), int(math.ceil((smax[1] - smin[1]) / cell))
    part = part_heights(tris, smin[0], smin[1], nx, ny, cell)
    floor = np.where(np.isfinite(part), part, smin[2])

    # The program's cut (gsim's model: each sample's cutter lowers the columns under it).
    stock = np.full((ny, nx), smax[2]).ravel()
    kernels = {n: kernel(*tools[n], cell) for n in tools}
    batch = {n: [] for n in tools}
    for kind, tool, p0, p1, arc, _ in moves_with_feed(canon):
        batch[tool if tool in tools else 1].extend(sample(kind, p0, p1, arc, cell / 2))
    for n, pts in batch.items():
        if not pts:
            continue
        di, dj, shape = kernels[n]
        P = np.asarray(pts)
        ci = np.floor((P[:, 0] - smin[0]) / cell).astype(np.int64)
        cj = np.floor((P[:, 1] - smin[1]) / cell).astype(np.int64)
        chunk = max(1, 4_000_000 // len(di))
        for k in range(0, len(P), chunk):
            I, J = ci[k:k + chunk, None] + di[None, :], cj[k:k + chunk, None] + dj[None, :]
            rho = np.hypot(smin[0] + (I + 0.5) * cell - P[k:k + chunk, 0, None], smin[1] + (J + 0.5) * cell - P[k:k + chunk, 1, None])
            Z = P[k:k + chunk, 2, None] + bottom(shape, rho)
            ok = (I >= 0) & (I < nx) & (J >= 0) & (J < ny) & np.isfinite(Z)
            np.minimum.at(stock, J[ok] * nx + I[ok], Z[ok])
    stock = stock.reshape(ny, nx)

    # The ideal: the lowest tip of a perfect ball over the part, then the ball's envelope.
    R = a.ball / 2
    n = int(math.ceil(R / cell))
    offsets = [(i, j, R - math.sqrt(max(R * R - (i * cell) ** 2 - (j * cell) ** 2, 0.0)))
               for j in range(-n, n + 1) for i in range(-n, n + 1) if math.hypot(i * cell, j * cell) <= R]
    tip = np.full((ny, nx), -np.inf)
    for i, j, dz in offsets:
        np.maximum(tip, shifted(floor, i, j, -np.inf) - dz, out=tip)
    ideal = np.full((ny, nx), np.inf)
    for i, j, dz in offsets:
        np.minimum(ideal, shifted(tip, i, j, np.inf) + dz, out=ideal)
    gy, gx = np.gradient(ideal, cell)
    slope = np.degrees(np.arctan(np.hypot(gx, gy)))
    left = np.maximum(stock - ideal, 0.0) * np.cos(np.radians(slope))
    # On the part, a ball's radius in from the stock's sides (what the finish is asked to cover).
    on = np.isfinite(part) & np.isfinite(ideal)
    out = {"cells": int(on.sum()), "cell": cell, "gouge_cells": int(np.sum(on & (stock < floor - 0.05)))}
    for name, m in (("all", on), ("steep", on & (slope > a.steep)), ("shallow", on & (slope <= a.steep))):
        v = left[m]
        if v.size:
            out[name] = {"cells": int(v.size), "p50": round(float(np.percentile(v, 50)), 4), "p90": round(float(np.percentile(v, 90)), 4),
                         "p95": round(float(np.percentile(v, 95)), 4), "max": round(float(v.max()), 4)}
    print(json.dumps(out))


if __name__ == "__main__":
    main()
