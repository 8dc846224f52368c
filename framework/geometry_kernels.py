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


# -- analytic pieces: Uintah's inside tests, one point at a time ----------------------------------

@njit(cache=True)
def inside_parallelepiped(x, p1, to_unit, out):
    """Uintah's parallelepiped: r = T (x - p1) with T the inverse of [p2-p1, p3-p1, p4-p1];
    inside when min(r) > 0 and max(r) <= 1 (NaaBoxGeometryPiece::inside)."""
    for p in range(x.shape[0]):
        dx, dy, dz = x[p, 0] - p1[0], x[p, 1] - p1[1], x[p, 2] - p1[2]
        lo, hi = np.inf, -np.inf
        for i in range(3):
            r = to_unit[i, 0] * dx + to_unit[i, 1] * dy + to_unit[i, 2] * dz
            lo = min(lo, r)
            hi = max(hi, r)
        out[p] = lo > 0.0 and hi <= 1.0


@njit(cache=True)
def inside_ellipsoid(x, origin, m, tol, out):
    """Uintah's ellipsoid: (x - o) . M (x - o) - 1 < tol, M = U S U^T with S = diag(1/r_k^2)."""
    for p in range(x.shape[0]):
        d0, d1, d2 = x[p, 0] - origin[0], x[p, 1] - origin[1], x[p, 2] - origin[2]
        q = (d0 * (m[0, 0] * d0 + m[0, 1] * d1 + m[0, 2] * d2)
             + d1 * (m[1, 0] * d0 + m[1, 1] * d1 + m[1, 2] * d2)
             + d2 * (m[2, 0] * d0 + m[2, 1] * d1 + m[2, 2] * d2))
        out[p] = q - 1.0 < tol


@njit(cache=True)
def inside_cone(x, bottom, top, r_bottom, r_top, out):
    """Uintah's cone (a frustum): t = axis position in 0..1, inside when the distance from the
    axis is at most r_bottom (1 - t) + r_top t (ConeGeometryPiece::inside)."""
    a0, a1, a2 = top[0] - bottom[0], top[1] - bottom[1], top[2] - bottom[2]
    h2 = a0 * a0 + a1 * a1 + a2 * a2
    for p in range(x.shape[0]):
        t = (a0 * (x[p, 0] - bottom[0]) + a1 * (x[p, 1] - bottom[1]) + a2 * (x[p, 2] - bottom[2])) / h2
        if t < 0.0 or t > 1.0:
            out[p] = False
            continue
        rad = r_bottom * (1.0 - t) + r_top * t
        n0 = x[p, 0] - (bottom[0] * (1.0 - t) + top[0] * t)
        n1 = x[p, 1] - (bottom[1] * (1.0 - t) + top[1] * t)
        n2 = x[p, 2] - (bottom[2] * (1.0 - t) + top[2] * t)
        out[p] = np.sqrt(n0 * n0 + n1 * n1 + n2 * n2) <= rad


@njit(cache=True)
def inside_torus(x, center, major, minor, axis, theta, out):
    """Uintah's torus about the x (axis 0), y (1) or z (2) axis through center, first turned by
    -theta in the plane Uintah names (TorusGeometryPiece::inside): (R - rho)^2 + h^2 < r^2."""
    c, s = np.cos(-theta), np.sin(-theta)
    for p in range(x.shape[0]):
        u, v, w = x[p, 0] - center[0], x[p, 1] - center[1], x[p, 2] - center[2]
        if axis == 2:          # z: x, z turned; ring in x-y, height z
            u, w = u * c - w * s, u * s + w * c
            rho, h = np.sqrt(u * u + v * v), w
        elif axis == 1:        # y: y, z turned; ring in x-z, height y
            v, w = v * c - w * s, v * s + w * c
            rho, h = np.sqrt(u * u + w * w), v
        else:                  # x: x, y turned; ring in y-z, height x
            u, v = u * c - v * s, u * s + v * c
            rho, h = np.sqrt(v * v + w * w), u
        out[p] = (major - rho) * (major - rho) + h * h < minor * minor


@njit(cache=True)
def inside_halfspaces(x, normals, offsets, lo, hi, tol, out):
    """Uintah's convex polyhedron: inside its vertices' box (lower bound closed, upper open, as
    Uintah's Box::contains) and, for every plane, -n.x - d < tol (n unit, pointing inwards)."""
    for p in range(x.shape[0]):
        ok = True
        for d in range(3):
            if x[p, d] < lo[d] or x[p, d] >= hi[d]:
                ok = False
        k = 0
        while ok and k < normals.shape[0]:
            proj = -(normals[k, 0] * x[p, 0] + normals[k, 1] * x[p, 1] + normals[k, 2] * x[p, 2])
            ok = proj - offsets[k] < tol
            k += 1
        out[p] = ok


@njit(cache=True)
def inside_smooth_cylinder(x, bottom, top, r_outer, r_inner, cap, out):
    """Uintah's smoothcyl: within r_outer of the axis between the end caps (the cylinder
    lengthened by cap at both ends), and farther than r_inner from the axis
    (SmoothCylGeomPiece::inside)."""
    a0, a1, a2 = top[0] - bottom[0], top[1] - bottom[1], top[2] - bottom[2]
    length = np.sqrt(a0 * a0 + a1 * a1 + a2 * a2)
    c0, c1, c2 = a0 * (cap / length), a1 * (cap / length), a2 * (cap / length)
    b0, b1, b2 = bottom[0] - c0, bottom[1] - c1, bottom[2] - c2
    f0, f1, f2 = top[0] + c0 - b0, top[1] + c1 - b1, top[2] + c2 - b2
    height = length + 2.0 * cap
    height2 = height * height
    for p in range(x.shape[0]):
        q0, q1, q2 = x[p, 0] - b0, x[p, 1] - b1, x[p, 2] - b2
        h = q0 * f0 + q1 * f1 + q2 * f2
        ok = not (h < 0.0 or h > height2)
        k0, k1, k2 = f1 * q2 - f2 * q1, f2 * q0 - f0 * q2, f0 * q1 - f1 * q0
        if (k0 * k0 + k1 * k1 + k2 * k2) / height2 > r_outer * r_outer:
            ok = False
        if ok:
            q0, q1, q2 = x[p, 0] - bottom[0], x[p, 1] - bottom[1], x[p, 2] - bottom[2]
            k0, k1, k2 = a1 * q2 - a2 * q1, a2 * q0 - a0 * q2, a0 * q1 - a1 * q0
            ok = (k0 * k0 + k1 * k1 + k2 * k2) / (length * length) > r_inner * r_inner
        out[p] = ok
