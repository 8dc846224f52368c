"""Numba kernels of the geometry pieces: inside tests for a closed triangulated surface (<tri>)."""
from __future__ import annotations

import numpy as np
from numba import njit, prange

# Three rays, each close to (but not exactly along) a coordinate axis, so that a ray
# through a vertex or along an edge of an axis-aligned surface is unlikely; a point is
# inside when at least two rays cross the surface an odd number of times (as Uintah's
# TriGeometryPiece, which votes over three rays).
RAYS = np.array([[1.0, 3.1415926e-4, 2.7182818e-4],
                 [1.4142136e-4, 1.0, 1.7320508e-4],
                 [2.2360680e-4, 1.6180340e-4, 1.0]])


@njit(cache=True)
def _crossings(px, py, pz, dx, dy, dz, v0, e1, e2):
    """Number of triangles the ray p + t d (t > 0) crosses (Moeller-Trumbore)."""
    n = 0
    for t in range(v0.shape[0]):
        ax, ay, az = e1[t, 0], e1[t, 1], e1[t, 2]
        bx, by, bz = e2[t, 0], e2[t, 1], e2[t, 2]
        hx = dy * bz - dz * by
        hy = dz * bx - dx * bz
        hz = dx * by - dy * bx
        det = ax * hx + ay * hy + az * hz
        if det == 0.0:
            continue
        inv = 1.0 / det
        sx, sy, sz = px - v0[t, 0], py - v0[t, 1], pz - v0[t, 2]
        u = (sx * hx + sy * hy + sz * hz) * inv
        if u < 0.0 or u > 1.0:
            continue
        qx = sy * az - sz * ay
        qy = sz * ax - sx * az
        qz = sx * ay - sy * ax
        v = (dx * qx + dy * qy + dz * qz) * inv
        if v < 0.0 or u + v > 1.0:
            continue
        if (bx * qx + by * qy + bz * qz) * inv > 0.0:
            n += 1
    return n


@njit(cache=True, parallel=True)
def inside_surface(x, v0, e1, e2, lo, hi, rays, out):
    """out[p] = x[p] is inside the closed surface of triangles (v0, v0 + e1, v0 + e2)."""
    for p in prange(x.shape[0]):
        px, py, pz = x[p, 0], x[p, 1], x[p, 2]
        if px < lo[0] or px > hi[0] or py < lo[1] or py > hi[1] or pz < lo[2] or pz > hi[2]:
            out[p] = False
            continue
        odd = 0
        for r in range(3):
            odd += _crossings(px, py, pz, rays[r, 0], rays[r, 1], rays[r, 2], v0, e1, e2) % 2
        out[p] = odd >= 2
