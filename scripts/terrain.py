#!/usr/bin/env python3
"""Issue 61's generated terrain: a closed height-field solid over 100 x 100 mm of N x N cells
(two facets each; walls and a fanned bottom close it), hills and hollows from a few smooth
bumps on a gentle wave, 2 to about 22 mm high. N = 273 (the default) gives 152,334 facets,
137 39,182 and 68 10,064: the same shape at three sizes. Writes a binary STL.

    python3 scripts/terrain.py OUT.stl [N]
"""
import math, struct, sys
N = int(sys.argv[2]) if len(sys.argv) > 2 else 273
L = 100.0
bumps = [(30, 35, 14, 12), (70, 60, 12, 9), (50, 80, 8, -5), (20, 75, 10, 7), (75, 20, 9, 10), (50, 45, 6, -4)]
def h(x, y):
    z = 8.0 + 2.0 * math.sin(x / 7.0) * math.cos(y / 9.0)
    for cx, cy, s, a in bumps:
        z += a * math.exp(-((x - cx) ** 2 + (y - cy) ** 2) / (2 * s * s))
    return max(z, 2.0)
P = [[(i * L / N, j * L / N, h(i * L / N, j * L / N)) for i in range(N + 1)] for j in range(N + 1)]
tris = []
for j in range(N):
    for i in range(N):
        a, b, c, d = P[j][i], P[j][i + 1], P[j + 1][i + 1], P[j + 1][i]
        tris += [(a, b, c), (a, c, d)]
# Walls down to z 0 and the bottom, fanned from the border's points.
def wall(pts):
    for p, q in zip(pts, pts[1:]):
        p0, q0 = (p[0], p[1], 0.0), (q[0], q[1], 0.0)
        tris.extend([(p, p0, q0), (p, q0, q)])
south = [P[0][i] for i in range(N + 1)]
east = [P[j][N] for j in range(N + 1)]
north = [P[N][i] for i in range(N, -1, -1)]
west = [P[j][0] for j in range(N, -1, -1)]
for side in (south, east, north, west):
    wall(side)
border = south + east[1:] + north[1:] + west[1:-1]
c = (L / 2, L / 2, 0.0)
for p, q in zip(border, border[1:] + border[:1]):
    tris.append((c, (q[0], q[1], 0.0), (p[0], p[1], 0.0)))
def normal(a, b, c):
    u = [b[k] - a[k] for k in range(3)]; v = [c[k] - a[k] for k in range(3)]
    n = (u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0])
    l = math.sqrt(sum(x * x for x in n)) or 1.0
    return [x / l for x in n]
with open(sys.argv[1], 'wb') as f:
    f.write(b'terrain'.ljust(80, b' '))
    f.write(struct.pack('<I', len(tris)))
    for t in tris:
        f.write(struct.pack('<12fH', *normal(*t), *t[0], *t[1], *t[2], 0))
print(len(tris), 'facets')
