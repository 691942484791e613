"""What ezdxf (the Python DXF library, a trusted reader) makes of DXF drawings: for each file
named on the command line, one JSON object on its own line with the drawing's bounds, the length
of its lines and curves, and the areas of its closed loops, all in millimetres (by $INSUNITS),
in the XY plane as swarf reads it. Entities whose own plane (their extrusion) is not XY's are
counted as left out, as swarf leaves them. tests/dxf_spec.rs compares swarf's reading with this.

Usage: python3 ezdxf_read.py GAP FILE...   (GAP: the chaining tolerance, mm)
"""
import json
import math
import sys

import ezdxf
from ezdxf import edgeminer as em
from ezdxf import edgesmith as es
from ezdxf import path as P
from ezdxf import recover, units
from ezdxf.math import Vec3

KINDS = ("LINE", "ARC", "CIRCLE", "LWPOLYLINE", "POLYLINE", "ELLIPSE", "SPLINE")
OWN_PLANE = ("ARC", "CIRCLE", "LWPOLYLINE", "POLYLINE", "ELLIPSE")


def out_of_plane(e):
    if e.dxftype() not in OWN_PLANE:
        return False
    if e.dxftype() == "POLYLINE" and not e.is_2d_polyline:
        return False
    n = Vec3(e.dxf.get("extrusion", (0, 0, 1)))
    if n.magnitude == 0:
        return False
    return abs(abs(n.normalize().z) - 1.0) > 1e-12


def points(e, d):
    return [(v.x, v.y) for v in P.make_path(e).flattening(d)]


def length(pts):
    return sum(math.dist(a, b) for a, b in zip(pts, pts[1:]))


def shoelace(pts):
    return 0.5 * sum(a[0] * b[1] - b[0] * a[1] for a, b in zip(pts, pts[1:] + pts[:1]))


def read(name, gap_mm):
    try:
        doc = ezdxf.readfile(name)
    except Exception:
        doc, _ = recover.readfile(name)
    code = doc.header.get("$INSUNITS", 0)
    f = units.conversion_factor(code, units.MM) if code else 1.0
    d = 1e-5 / f  # flattening distance: 0.01 µm, in the file's units
    kept, left_out = [], 0
    for e in doc.modelspace():
        if e.dxftype() not in KINDS:
            continue
        if e.dxftype() == "POLYLINE" and (e.is_polygon_mesh or e.is_poly_face_mesh):
            continue
        if out_of_plane(e):
            left_out += 1
            continue
        kept.append(e)
    lo, hi = [math.inf, math.inf], [-math.inf, -math.inf]
    total = 0.0
    loops = []
    flats = {}
    for e in kept:
        pts = points(e, d)
        flats[id(e)] = pts
        for x, y in pts:
            lo = [min(lo[0], x), min(lo[1], y)]
            hi = [max(hi[0], x), max(hi[1], y)]
        total += length(pts)
        if es.is_closed_entity(e):
            loops.append(abs(shoelace(pts)))
    edges = list(es.edges_from_entities_2d(kept, gap_tol=gap_mm / f))
    if edges:
        for chain in em.find_all_simple_chains(em.Deposit(edges, gap_tol=gap_mm / f)):
            if not em.is_loop(chain, gap_tol=gap_mm / f):
                continue
            ring = []
            for edge in chain:
                pts = flats[id(edge.payload)]
                ring += list(reversed(pts)) if edge.is_reverse else pts
            loops.append(abs(shoelace(ring)))
    return {
        "file": name,
        "bounds": [lo[0] * f, hi[0] * f, lo[1] * f, hi[1] * f] if kept else None,
        "length": total * f,
        "loops": sorted(a * f * f for a in loops),
        "leftOut": left_out,
    }


gap = float(sys.argv[1])
for name in sys.argv[2:]:
    print(json.dumps(read(name, gap)))
