"""A manifold3d solid written as a binary STL (the generated parts of scripts/pocket-plate.py
and scripts/mould-core.py)."""
import struct

import numpy as np


def write_stl(solid, path, header):
    """Writes `solid`'s triangles to `path` with `header` (at most 80 bytes); returns how many."""
    mesh = solid.to_mesh()
    v = np.asarray(mesh.vert_properties)[:, :3]
    tris = v[np.asarray(mesh.tri_verts)]
    n = np.cross(tris[:, 1] - tris[:, 0], tris[:, 2] - tris[:, 0])
    n /= np.maximum(np.linalg.norm(n, axis=1), 1e-30)[:, None]
    rec = np.zeros(len(tris), dtype=[("n", "<f4", 3), ("v", "<f4", (3, 3)), ("a", "<u2")])
    rec["n"], rec["v"] = n, tris
    with open(path, "wb") as f:
        f.write(header.ljust(80, b" "))
        f.write(struct.pack("<I", len(tris)))
        f.write(rec.tobytes())
    return len(tris)
