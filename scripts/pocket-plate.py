#!/usr/bin/env python3
"""Issue 61's generated pocket plate: a 229 x 165 x 16 mm plate (top at z = 0) with an
octagonal pocket stepping down in four terraces (floors at -4, -7, -10 and -13), bosses standing
on the terraces to other heights (round, square, octagonal, one with a pocket of its own) and two
slots: 13 flat heights, the bottom among them, with true vertical walls (an
exact solid built by manifold3d's booleans, circles as 64-gons). Like the plate Kiri:Moto took
2-3 s on. Writes a binary STL.

    python3 scripts/pocket-plate.py OUT.stl      (needs manifold3d and numpy)
"""
import math
import sys

import manifold3d as m
import numpy as np
from solid_stl import write_stl

W, H, T = 229.0, 165.0, 16.0


def octagon(x0, y0, x1, y1, c):
    """An octagon in the box [x0, x1] x [y0, y1] with its corners cut c at 45 degrees."""
    pts = [(x0 + c, y0), (x1 - c, y0), (x1, y0 + c), (x1, y1 - c), (x1 - c, y1), (x0 + c, y1), (x0, y1 - c), (x0, y0 + c)]
    return m.CrossSection([pts])


def inset(k, c):
    return octagon(k, k, W - k, H - k, c)


def prism(section, z0, z1):
    return section.extrude(z1 - z0).translate((0, 0, z0))


def circle(x, y, r):
    return m.CrossSection.circle(r, 64).translate((x, y))


def rect(x, y, w, h):
    return m.CrossSection.square((w, h)).translate((x, y))


def plate():
    solid = m.Manifold.cube((W, H, T)).translate((0, 0, -T))
    # The terraces: each octagon is cut down to its floor.
    for k, c, floor in [(8, 30, -4), (20, 26, -7), (34, 20, -10), (50, 14, -13)]:
        solid -= prism(inset(k, c), floor, 1)
    # Bosses standing on the terraces, each to its own height.
    bosses = [
        (circle(30, 30, 8), -13, -1),  # on the -4 terrace, up to -1
        (circle(W - 30, 30, 8), -13, -2),
        (circle(30, H - 30, 6), -13, -2),
        (rect(W - 40, H - 40, 14, 14), -13, -1),
        (circle(45, H / 2, 7), -13, -5),  # on the -7 terrace
        (rect(W - 55, H / 2 - 8, 12, 16), -13, -5),
        (circle(W / 2 - 40, 45, 5), -13, -8),  # on the -10 terrace
        (circle(W / 2 + 40, H - 45, 5), -13, -8),
        (octagon(W / 2 - 28, H / 2 - 20, W / 2 + 28, H / 2 + 20, 10), -13, -2),  # the centre
        (circle(W / 2 - 50, H / 2, 6), -13, -11),  # on the -13 floor
        (circle(W / 2 + 50, H / 2, 6), -13, -11),
    ]
    for section, z0, z1 in bosses:
        solid += prism(section, z0 - 0.5, z1)
    # The centre boss's own pocket, with an island, and two slots across the top's rim.
    solid -= prism(octagon(W / 2 - 18, H / 2 - 11, W / 2 + 18, H / 2 + 11, 6), -6, 1)
    solid += prism(circle(W / 2, H / 2, 4), -6.5, -3)
    solid -= prism(rect(W / 2 - 40, 2, 80, 4), -3, 1)
    solid -= prism(rect(W / 2 - 40, H - 6, 80, 4), -3, 1)
    return solid


if __name__ == "__main__":
    part = plate()
    levels = sorted({round(float(z), 6) for z in np.asarray(part.to_mesh().vert_properties)[:, 2]})
    n = write_stl(part, sys.argv[1], b'swarf pocket plate')
    print(f"{sys.argv[1]}: {n} facets, volume {part.volume():.0f} mm^3, {len(levels)} heights {levels}", file=sys.stderr)
    assert math.isfinite(part.volume()) and part.genus() >= 0
