"""Convected boundary domain integration (CBDI) of pressure loads, Uintah's
`<MPM><use_CBDI_boundary_condition>true</use_CBDI_boundary_condition>`.

A pressure BC's particle force is applied on the loaded face of the particle's deformed domain
instead of at its centre: each step

* the face is the side of the domain F p.size (Uintah's p.size in cells, times dx) whose
  half-vector d_i is (anti)parallel to the load's normal n (|cos| within 0.1; n flipped where
  <outward_normal>false); its centre is x_p +- d_i, its four corners the centre
  +-(d_j -+ d_k)/2 of the other two half-vectors (Uintah's PressureBC::getForceVectorCBDI);
* p.externalforce = n p(t) A / N / 4 * |F-face area| / |initial face area|, one quarter for each
  corner, scaled with the face's area;
* particle-to-grid (000 eq. 22): fext_i = sum over the corners of p.externalforce S_i(corner)
  with linear weights, for the particles whose first p.loadCurveID is set; the other particles
  give no external force to the grid, as in Uintah's SerialMPM.

As Uintah: torque loads keep their force at the particle centre (TorqueBC's getForceVectorCBDI
is never called) and reach the grid only through the corners of a pressure load on the same
particle; a particle whose domain has no side along n has no corners (Uintah leaves them at
DBL_MAX) and gives the grid no external force.
"""
import numpy as np
from numba import njit

NO_CORNER = np.finfo(np.float64).max      # Uintah's Point(): a corner never set


def cells_size(size, dx):
    """Uintah's p.size (n, 3, 3) in cells from pysus's half-widths (n, 3) or half-vector matrix
    (n, 3, 3) in metres (p.size or p.sizeMatrix): row d of 2 H divided by dx_d."""
    if size.ndim == 2:
        out = np.zeros((len(size), 3, 3))
        for d in range(3):
            out[:, d, d] = 2.0 * size[:, d] / dx[d]
        return out
    return 2.0 * size / np.asarray(dx)[None, :, None]


@njit(cache=True)
def corner_loads(sel, x, force, normal, outward, F, psize, dx, f_out, corners):
    """Adds the CBDI force of one pressure BC to f_out and sets the corners (n, 4, 3) of its
    particles sel: force the BC's n p(t) A / N at the particle centre, normal its n (both (len(sel), 3)),
    psize Uintah's p.size in cells (Uintah's PressureBC::getForceVectorCBDI)."""
    sgn = 1.0 if outward else -1.0
    for s in range(sel.shape[0]):
        p = sel[s]
        n0 = normal[s, 0] * sgn
        n1 = normal[s, 1] * sgn
        n2 = normal[s, 2] * sgn
        nlen = np.sqrt(n0 * n0 + n1 * n1 + n2 * n2)
        D = np.empty((3, 3))            # F p.size, Uintah's dsize (cells)
        for r in range(3):
            for c in range(3):
                D[r, c] = F[p, r, 0] * psize[p, 0, c] + F[p, r, 1] * psize[p, 1, c] + F[p, r, 2] * psize[p, 2, c]
        c0 = c1 = c2 = NO_CORNER
        i1 = i2 = 0
        for i in range(3):              # the side along n; a later match wins, as in Uintah
            h0 = D[0, i] * dx[0] * 0.5
            h1 = D[1, i] * dx[1] * 0.5
            h2 = D[2, i] * dx[2] * 0.5
            cosine = (n0 * h0 + n1 * h1 + n2 * h2) / (nlen * np.sqrt(h0 * h0 + h1 * h1 + h2 * h2))
            if abs(cosine - 1.0) < 0.1:
                c0, c1, c2 = x[p, 0] + h0, x[p, 1] + h1, x[p, 2] + h2
                i1, i2 = (i + 1) % 3, (i + 2) % 3
            elif abs(cosine + 1.0) < 0.1:
                c0, c1, c2 = x[p, 0] - h0, x[p, 1] - h1, x[p, 2] - h2
                i1, i2 = (i + 1) % 3, (i + 2) % 3
        centre = (c0, c1, c2)
        for d in range(3):
            a = D[d, i1] * dx[d]
            b = D[d, i2] * dx[d]
            corners[p, 0, d] = centre[d] - 0.5 * (a - b)
            corners[p, 1, d] = centre[d] + 0.5 * (a - b)
            corners[p, 2, d] = centre[d] - 0.5 * (a + b)
            corners[p, 3, d] = centre[d] + 0.5 * (a + b)
        ini = _cross_length(psize[p, 0, i1], psize[p, 1, i1], psize[p, 2, i1],
                            psize[p, 0, i2], psize[p, 1, i2], psize[p, 2, i2])
        cur = _cross_length(D[0, i1], D[1, i1], D[2, i1], D[0, i2], D[1, i2], D[2, i2])
        for d in range(3):
            f_out[p, d] += force[s, d] * 0.25 * (cur / ini)


@njit(cache=True, inline="always")
def _cross_length(a0, a1, a2, b0, b1, b2):
    c0 = a1 * b2 - a2 * b1
    c1 = a2 * b0 - a0 * b2
    c2 = a0 * b1 - a1 * b0
    return np.sqrt(c0 * c0 + c1 * c1 + c2 * c2)


@njit(cache=True)
def corners_to_grid(act, own, ghost, runs, anchor, dx, node_low, gfext):
    """fext_i += sum_c p.externalforce S_i(corner c) (linear weights, Uintah's LinearInterpolator:
    (x - anchor) / dx) of the particles whose first p.loadCurveID is set: own and ghost sources
    (p.loadCurveID, p.externalforce, corners), run by run in the merged ID order as p2g; shares on
    nodes beyond the arrays, and corners never set, are dropped. An inactive axis (act) has one
    node layer of weight 1."""
    sh = gfext.shape
    base = np.zeros((4, 3), np.int64)
    frac = np.zeros((4, 3))
    ok = np.ones(4, np.bool_)
    for r in range(runs.shape[0]):
        lcid, fext, corners = own if runs[r, 0] == 0 else ghost
        for p in range(runs[r, 1], runs[r, 2]):
            if lcid[p, 0] <= 0:
                continue
            for c in range(4):
                ok[c] = True
                for d in range(3):
                    if act & (1 << d):
                        u = (corners[p, c, d] - anchor[d]) / dx[d]
                        if not (node_low[d] - 2.0 < u < node_low[d] + sh[d] + 2.0):     # also: never set
                            ok[c] = False
                            continue
                        i = int(np.floor(u))
                        base[c, d] = i - node_low[d]
                        frac[c, d] = u - i
            for a in range(2 if act & 1 else 1):
                for b in range(2 if act & 2 else 1):
                    for e in range(2 if act & 4 else 1):
                        for c in range(4):
                            if not ok[c]:
                                continue
                            i, j, k = base[c, 0] + a, base[c, 1] + b, base[c, 2] + e
                            if not (0 <= i < sh[0] and 0 <= j < sh[1] and 0 <= k < sh[2]):
                                continue
                            fx = frac[c, 0] if a else 1.0 - frac[c, 0]
                            fy = frac[c, 1] if b else 1.0 - frac[c, 1]
                            fz = frac[c, 2] if e else 1.0 - frac[c, 2]
                            S = fx * fy * fz
                            gfext[i, j, k, 0] += fext[p, 0] * S
                            gfext[i, j, k, 1] += fext[p, 1] * S
                            gfext[i, j, k, 2] += fext[p, 2] * S

