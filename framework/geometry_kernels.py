"""Numba kernels of the geometry pieces: inside tests for a closed triangulated surface (<tri>).

A point is inside when at least two of three rays, each close to (but not exactly along)
a coordinate axis, cross the surface an odd number of times (Uintah's TriGeometryPiece
also votes over three rays). The small tilt keeps a ray off the vertices and edges of
axis-aligned surfaces. Each ray only tests the triangles in its column: the triangles
are binned on a 2D grid across the ray's main axis (bounding boxes padded by the tilt
over the surface's extent), so a query costs about (triangles / bins) tests, not all.
"""
from __future__ import annotations

import numpy as np
from numba import njit, prange

TILT = 3.2e-4
RAYS = np.array([[1.0, 3.1415926e-4, 2.7182818e-4],
                 [1.4142136e-4, 1.0, 1.7320508e-4],
                 [2.2360680e-4, 1.6180340e-4, 1.0]])
CROSS = np.array([[1, 2], [0, 2], [0, 1]], np.int64)     # the two directions across each ray


@njit(cache=True)
def _hits(px, py, pz, dx, dy, dz, v0, e1, e2, t):
    """Does the ray p + s d (s > 0) cross triangle t (Moeller-Trumbore)?"""
    ax, ay, az = e1[t, 0], e1[t, 1], e1[t, 2]
    bx, by, bz = e2[t, 0], e2[t, 1], e2[t, 2]
    hx = dy * bz - dz * by
    hy = dz * bx - dx * bz
    hz = dx * by - dy * bx
    det = ax * hx + ay * hy + az * hz
    if det == 0.0:
        return False
    inv = 1.0 / det
    sx, sy, sz = px - v0[t, 0], py - v0[t, 1], pz - v0[t, 2]
    u = (sx * hx + sy * hy + sz * hz) * inv
    if u < 0.0 or u > 1.0:
        return False
    qx = sy * az - sz * ay
    qy = sz * ax - sx * az
    qz = sx * ay - sy * ax
    v = (dx * qx + dy * qy + dz * qz) * inv
    if v < 0.0 or u + v > 1.0:
        return False
    return (bx * qx + by * qy + bz * qz) * inv > 0.0


@njit(cache=True)
def build_bins(v0, e1, e2, cross, lo, width, nbin, pad, offsets, items):
    """CSR lists (offsets [nbin0 * nbin1 + 1], items) of the triangles whose padded bounding
    box, across the ray (directions cross[0], cross[1]), touches each bin. Call with
    items of size 0 to get the offsets (and the size items needs)."""
    count_only = items.shape[0] == 0
    fill = offsets[:-1].copy()
    if count_only:
        offsets[:] = 0
    for t in range(v0.shape[0]):
        rng = np.empty(4, np.int64)
        for q in range(2):
            d = cross[q]
            a = v0[t, d]
            b = a + e1[t, d]
            c = a + e2[t, d]
            lo_t = min(a, min(b, c)) - pad
            hi_t = max(a, max(b, c)) + pad
            i0 = int(np.floor((lo_t - lo[q]) / width[q]))
            i1 = int(np.floor((hi_t - lo[q]) / width[q]))
            rng[2 * q] = min(max(i0, 0), nbin[q] - 1)
            rng[2 * q + 1] = min(max(i1, 0), nbin[q] - 1)
        for i in range(rng[0], rng[1] + 1):
            for j in range(rng[2], rng[3] + 1):
                k = i * nbin[1] + j
                if count_only:
                    offsets[k + 1] += 1
                else:
                    items[fill[k]] = t
                    fill[k] += 1
    if count_only:
        for k in range(offsets.shape[0] - 1):
            offsets[k + 1] += offsets[k]


@njit(cache=True, parallel=True)
def inside_surface(x, v0, e1, e2, lo, hi, rays, cross, blo, bwidth, nbin, offsets, items, out):
    """out[p] = x[p] is inside the closed surface of triangles (v0, v0 + e1, v0 + e2)."""
    for p in prange(x.shape[0]):
        px, py, pz = x[p, 0], x[p, 1], x[p, 2]
        if px < lo[0] or px > hi[0] or py < lo[1] or py > hi[1] or pz < lo[2] or pz > hi[2]:
            out[p] = False
            continue
        odd = 0
        for r in range(3):
            i = int(np.floor((x[p, cross[r, 0]] - blo[r, 0]) / bwidth[r, 0]))
            j = int(np.floor((x[p, cross[r, 1]] - blo[r, 1]) / bwidth[r, 1]))
            i = min(max(i, 0), nbin[r, 0] - 1)
            j = min(max(j, 0), nbin[r, 1] - 1)
            k = i * nbin[r, 1] + j
            n = 0
            for s in range(offsets[r][k], offsets[r][k + 1]):
                if _hits(px, py, pz, rays[r, 0], rays[r, 1], rays[r, 2], v0, e1, e2, items[r][s]):
                    n += 1
            odd += n % 2
        out[p] = odd >= 2
