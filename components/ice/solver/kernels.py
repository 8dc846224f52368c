"""Per-patch numba kernels of the pressure solver (stencil, CG vectors, fine-level multigrid).

Stencil layout A[i, j, k, :] = [kap, aW, aE, aS, aN, aB, aT]; the operator is
(A p)_c = kap p_c + sum_f a_f (p_c - p_nb). Extra (boundary) cells of every solver
vector are zero, so a face with a non-zero coefficient on the domain boundary is a
Dirichlet face (delta p = 0 outside); walls and zero-gradient faces have a_f = 0.
`g0` is the global index of local cell (0, 0, 0): global = local + g0.
"""
from __future__ import annotations

import numpy as np
from numba import njit


@njit(cache=True)
def _unit(d):
    if d == 0:
        return 1, 0, 0
    if d == 1:
        return 0, 1, 0
    return 0, 0, 1


@njit(cache=True)
def _face_coef(vf, sp, one, a0, a1, a2, b0, b1, b2, u):
    """theta_f v_f of one material on the face between cells a and b with face velocity u (harmonic
    v as eq. 28; theta_f the donor cell's, as the residual's div(theta u), Uintah's upwinded vol_frac)."""
    vL = sp[a0, a1, a2]
    vR = sp[b0, b1, b2]
    v = 2.0 * vL * vR / (vL + vR)
    if one:
        return v
    return (vf[a0, a1, a2] if u >= 0.0 else vf[b0, b1, b2]) * v


@njit(cache=True)
def add_material(A, vf, sp, cs, one, dims, lo, hi, s, keep, atb, ux, uy, uz, sh):
    """Adds one material to the stencil: kap += theta v / c^2, a_f += s_d theta_f v_f.

    s[d] = dt^2 / dx_d^2 (eq. P below); keep (CC, the domain's extra cells) = 0 drops this
    material's face term on the boundary face next to that extra cell (fixed face velocity, or
    zero-gradient pressure); atb[2d+side] says the patch touches that domain boundary.
    ux, uy, uz: the material's face velocities at P = 0, whose signs pick theta_f's donor cell
    (face f of the faces' array lies below cell f + sh[d]), so that the operator is the residual's
    Jacobian wherever no face velocity changes sign.
    Eq. P: kap dP - dt^2 div(sum_m theta_m v_m grad dP) = -(kap P + dt sum_m div(theta_m u_m)).
    """
    for i in range(lo[0], hi[0]):
        for j in range(lo[1], hi[1]):
            for k in range(lo[2], hi[2]):
                v = sp[i, j, k]
                A[i, j, k, 0] += vf[i, j, k] * v / (cs[i, j, k] * cs[i, j, k])
                for d in range(3):
                    if not dims[d]:
                        continue
                    di, dj, dk = _unit(d)
                    uf = ux if d == 0 else (uy if d == 1 else uz)
                    f0, f1, f2 = i - sh[d, 0], j - sh[d, 1], k - sh[d, 2]
                    cl = s[d] * _face_coef(vf, sp, one, i - di, j - dj, k - dk, i, j, k, uf[f0, f1, f2])
                    ch = s[d] * _face_coef(vf, sp, one, i, j, k, i + di, j + dj, k + dk,
                                           uf[f0 + di, f1 + dj, f2 + dk])
                    e = (i, j, k)[d]
                    if e == lo[d] and atb[2 * d] and not keep[i - di, j - dj, k - dk]:
                        cl = 0.0
                    if e == hi[d] - 1 and atb[2 * d + 1] and not keep[i + di, j + dj, k + dk]:
                        ch = 0.0
                    A[i, j, k, 1 + 2 * d] += cl
                    A[i, j, k, 2 + 2 * d] += ch


@njit(cache=True)
def _diag(A, i, j, k):
    return A[i, j, k, 0] + A[i, j, k, 1] + A[i, j, k, 2] + A[i, j, k, 3] + A[i, j, k, 4] + A[i, j, k, 5] \
        + A[i, j, k, 6]


@njit(cache=True)
def _apply_at(A, p, i, j, k, dims):
    v = p[i, j, k]
    s = A[i, j, k, 0] * v
    if dims[0]:
        s += A[i, j, k, 1] * (v - p[i - 1, j, k]) + A[i, j, k, 2] * (v - p[i + 1, j, k])
    if dims[1]:
        s += A[i, j, k, 3] * (v - p[i, j - 1, k]) + A[i, j, k, 4] * (v - p[i, j + 1, k])
    if dims[2]:
        s += A[i, j, k, 5] * (v - p[i, j, k - 1]) + A[i, j, k, 6] * (v - p[i, j, k + 1])
    return s


@njit(cache=True)
def apply(A, p, q, dims, lo, hi):
    """q = A p over [lo, hi); returns p . q."""
    dot = 0.0
    for i in range(lo[0], hi[0]):
        for j in range(lo[1], hi[1]):
            for k in range(lo[2], hi[2]):
                s = _apply_at(A, p, i, j, k, dims)
                q[i, j, k] = s
                dot += p[i, j, k] * s
    return dot


@njit(cache=True)
def cg_update(x, r, p, q, xn, rn, alpha, lo, hi):
    """x += alpha p, r -= alpha q; returns (r.r, max |r|)."""
    rr = 0.0
    rmax = 0.0
    for i in range(lo[0], hi[0]):
        for j in range(lo[1], hi[1]):
            for k in range(lo[2], hi[2]):
                xn[i, j, k] = x[i, j, k] + alpha * p[i, j, k]
                rv = r[i, j, k] - alpha * q[i, j, k]
                rn[i, j, k] = rv
                rr += rv * rv
                rmax = max(rmax, abs(rv))
    return rr, rmax


@njit(cache=True)
def cg_direction(z, p, pn, beta, lo, hi):
    """p_new = z + beta p."""
    for i in range(lo[0], hi[0]):
        for j in range(lo[1], hi[1]):
            for k in range(lo[2], hi[2]):
                pn[i, j, k] = z[i, j, k] + beta * p[i, j, k]


@njit(cache=True)
def jacobi(A, r, z, w, lo, hi):
    """z = w r / diag(A); returns r . z."""
    rz = 0.0
    for i in range(lo[0], hi[0]):
        for j in range(lo[1], hi[1]):
            for k in range(lo[2], hi[2]):
                z[i, j, k] = w * r[i, j, k] / _diag(A, i, j, k)
                rz += r[i, j, k] * z[i, j, k]
    return rz


@njit(cache=True)
def smooth(A, r, z, zn, w, dims, lo, hi):
    """One damped-Jacobi sweep: zn = z + w (r - A z) / diag(A); returns r . zn."""
    rz = 0.0
    for i in range(lo[0], hi[0]):
        for j in range(lo[1], hi[1]):
            for k in range(lo[2], hi[2]):
                zn[i, j, k] = z[i, j, k] + w * (r[i, j, k] - _apply_at(A, z, i, j, k, dims)) / _diag(A, i, j, k)
                rz += r[i, j, k] * zn[i, j, k]
    return rz


@njit(cache=True)
def restrict_residual(A, r, z, rc, g0, dims, lo, hi):
    """rc[coarse cell] += r - A z: the residual summed onto the 2x coarser global grid."""
    for i in range(lo[0], hi[0]):
        a = (i + g0[0]) // 2 if dims[0] else 0
        for j in range(lo[1], hi[1]):
            b = (j + g0[1]) // 2 if dims[1] else 0
            for k in range(lo[2], hi[2]):
                c = (k + g0[2]) // 2 if dims[2] else 0
                rc[a, b, c] += r[i, j, k] - _apply_at(A, z, i, j, k, dims)


@njit(cache=True)
def prolong_add(z, ec, zn, g0, dims, lo, hi):
    """zn = z + (coarse correction of the cell's parent): piecewise-constant prolongation."""
    for i in range(lo[0], hi[0]):
        a = (i + g0[0]) // 2 if dims[0] else 0
        for j in range(lo[1], hi[1]):
            b = (j + g0[1]) // 2 if dims[1] else 0
            for k in range(lo[2], hi[2]):
                c = (k + g0[2]) // 2 if dims[2] else 0
                zn[i, j, k] = z[i, j, k] + ec[a, b, c]


@njit(cache=True)
def coarse_operator(A, op, g0, dims, periodic, n, lo, hi):
    """op (4, nc+1...) += the patch's part of the 2x coarser operator.

    op[0] = sum of the children's kap; op[1+d][c] = coefficient of the low d-face of
    coarse cell c = 1/2 the sum of the fine faces on it (re-discretisation: the face
    area doubles per coarsened transverse direction, the spacing doubles). Index
    nc_d along d is the high domain boundary (unused when periodic).
    """
    for i in range(lo[0], hi[0]):
        for j in range(lo[1], hi[1]):
            for k in range(lo[2], hi[2]):
                g = (i + g0[0], j + g0[1], k + g0[2])
                a = g[0] // 2 if dims[0] else 0
                b = g[1] // 2 if dims[1] else 0
                c = g[2] // 2 if dims[2] else 0
                op[0, a, b, c] += A[i, j, k, 0]
                for d in range(3):
                    if not dims[d]:
                        continue
                    if g[d] % 2 == 0:
                        op[1 + d, a, b, c] += 0.5 * A[i, j, k, 1 + 2 * d]
                    if g[d] == n[d] - 1 and not periodic[d]:
                        if d == 0:
                            op[1, a + 1, b, c] += 0.5 * A[i, j, k, 2]
                        elif d == 1:
                            op[2, a, b + 1, c] += 0.5 * A[i, j, k, 4]
                        else:
                            op[3, a, b, c + 1] += 0.5 * A[i, j, k, 6]


@njit(cache=True)
def dot_sq_max(r, lo, hi):
    """(r . r, max |r|) over [lo, hi)."""
    rr = 0.0
    m = 0.0
    for i in range(lo[0], hi[0]):
        for j in range(lo[1], hi[1]):
            for k in range(lo[2], hi[2]):
                rr += r[i, j, k] * r[i, j, k]
                m = max(m, abs(r[i, j, k]))
    return rr, m
