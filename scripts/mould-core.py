#!/usr/bin/env python3
"""Issue 61's generated mould core, for the page's ten-operation job
(scripts/bench-page-generate.mjs --mould): a 100 x 100 x 30 mm block (top at z = 0) whose
parting face stands at z = -15, with a core rising from it to z = 0: a 60 x 44 mm rounded
rectangle (at the parting face) drafted 5 degrees a side, domed on top by a sphere through its
corners' diagonal 4 mm below the top: the dome's shallow top for raster finishing, the drafted
walls for waterline. In the parting
face: four 8 mm holes through at the corners (x, y = +-40), two 5 mm holes through beside the
core (x = +-40, y = 0) and a 12 mm counterbore 8 deep at (0, +-36). An exact solid by
manifold3d's booleans, circles as 64-gons. Writes a binary STL.

    python3 scripts/mould-core.py OUT.stl      (needs manifold3d and numpy)
"""
import math
import sys

import manifold3d as m
from solid_stl import write_stl

SIDE, T, PARTING = 100.0, 30.0, -15.0
CORE_W, CORE_H, CORE_R = 60.0, 44.0, 8.0
DOME = 4.0
DRAFT = math.radians(5.0)


def rounded(w, h, r):
    """A w x h rectangle centred on the origin with its corners rounded r."""
    core = m.CrossSection.square((w - 2 * r, h - 2 * r), center=True)
    return core.offset(r, m.JoinType.Round, circular_segments=64)


def circle(x, y, r):
    return m.CrossSection.circle(r, 64).translate((x, y))


def core():
    # The drafted walls, from under the parting face to over the dome: the section shrinks by
    # the draft over their height.
    z0, z1 = PARTING - 0.5, 0.5
    shrink = (z1 - z0) * math.tan(DRAFT)
    scale = ((CORE_W - 2 * shrink) / CORE_W, (CORE_H - 2 * shrink) / CORE_H)
    walls = rounded(CORE_W, CORE_H, CORE_R).extrude(z1 - z0, scale_top=scale).translate((0, 0, z0))
    # The dome: a sphere standing DOME above the ends of the core's diagonal, its top at z = 0.
    half = math.hypot(CORE_W, CORE_H) / 2
    radius = (half * half + DOME * DOME) / (2 * DOME)
    sphere = m.Manifold.sphere(radius, 256).translate((0, 0, -radius))
    return walls ^ sphere


def part():
    solid = m.Manifold.cube((SIDE, SIDE, T), center=True).translate((0, 0, -T / 2))
    # Down to the parting face around the core, then the core back.
    solid -= m.Manifold.cube((SIDE + 2, SIDE + 2, 20), center=True).translate((0, 0, PARTING + 10))
    solid += core()
    for x, y, r in [(-40, -40, 4), (40, -40, 4), (-40, 40, 4), (40, 40, 4), (-40, 0, 2.5), (40, 0, 2.5)]:
        solid -= circle(x, y, r).extrude(T + 2).translate((0, 0, -T - 1))
    for y in (-36, 36):
        solid -= circle(0, y, 6).extrude(9).translate((0, 0, PARTING - 8))
    return solid


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    solid = part()
    if solid.status() != m.Error.NoError:
        sys.exit(f"manifold3d: {solid.status()}")
    print(f"{sys.argv[1]}: {write_stl(solid, sys.argv[1], b'swarf mould core')} facets, volume {solid.volume():.0f} mm3")
