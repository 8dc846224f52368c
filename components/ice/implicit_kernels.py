"""Numba kernels of semi-implicit ICE (implicit.py): face-velocity correction, RHS."""
from __future__ import annotations

import numpy as np
from numba import njit

from .kernels import _exchange_matrix, solve_small


@njit(cache=True)
def face_correct(u0, sp_vol, P, uf, sh, dd, flo, fhi, dt, dx):
    """Eq. 28 with p = p_eq + P: uf = u*(p_eq) - dt v_f (P_R - P_L) / dx (harmonic v_f as eq. 28)."""
    for i in range(flo[0], fhi[0]):
        for j in range(flo[1], fhi[1]):
            for k in range(flo[2], fhi[2]):
                a, b, c = i + sh[0], j + sh[1], k + sh[2]
                l0, l1, l2 = a - dd[0], b - dd[1], c - dd[2]
                vL = sp_vol[l0, l1, l2]
                vR = sp_vol[a, b, c]
                uf[i, j, k] = u0[i, j, k] - dt * (2.0 * vL * vR / (vL + vR)) * (P[a, b, c] - P[l0, l1, l2]) / dx


@njit(cache=True)
def add_exchange_faces(A, vfs, sps, ufs, sh, dims, lo, hi, s, keep, atb, dt, K, kcell=None):
    """Face terms of eq. P with the momentum exchange: a_f += s_d sum_m theta_m,f (E v_f)_m.

    The exchanged face velocities are u_m = E (u* - dt v_f grad dP) (eq. 28, then eq. 38 on
    faces with its implicit matrix E, exchange_faces), so their response to grad dP is E v_f,
    not v_f (Uintah's exchange-corrected sp_vol_FC). With K = 1e15 a gas face next to a
    solid moves with the solid; without E the outer iteration would stall there.
    keep[m] (CC, the domain's extra cells) = 0 drops material m on the domain-boundary face
    next to that extra cell (fixed face velocity).
    kcell: the slip model's coefficient per cell, as in exchange_faces.
    ufs[d][m]: the exchanged face velocities at P = 0 (face f below cell f + sh[d]); their signs
    pick the donor cell of theta_m,f in the sum, as the residual's div(theta u) (Uintah's upwinded
    vol_frac); the exchange matrix keeps the centred theta, as exchange_faces.
    """
    n = len(vfs)
    a = np.empty((n, n))
    b = np.empty(n)
    th = np.empty(n)
    thk = np.empty(n)
    sv = np.empty(n)
    for d in range(3):
        if not dims[d]:
            continue
        di, dj, dk = (1, 0, 0) if d == 0 else ((0, 1, 0) if d == 1 else (0, 0, 1))
        for i in range(lo[0], hi[0] + di):
            for j in range(lo[1], hi[1] + dj):
                for k in range(lo[2], hi[2] + dk):
                    e = (i, j, k)[d]
                    bnd = e == lo[d] and atb[2 * d] or e == hi[d] and atb[2 * d + 1]
                    x0, x1, x2 = (i - di, j - dj, k - dk) if e == lo[d] else (i, j, k)   # its extra cell
                    for m in range(n):
                        vL = sps[m][i - di, j - dj, k - dk]
                        vR = sps[m][i, j, k]
                        th[m] = 0.5 * (vfs[m][i - di, j - dj, k - dk] + vfs[m][i, j, k])
                        sv[m] = 2.0 * (vL * vR) / (vL + vR)     # as exchange_faces
                        b[m] = sv[m]
                        if kcell is not None:
                            thk[m] = 0.5 * (vfs[m][i - di, j - dj, k - dk] * kcell[i - di, j - dj, k - dk]
                                            + vfs[m][i, j, k] * kcell[i, j, k])
                    _exchange_matrix(a, th if kcell is None else thk, sv, K, dt, n, None)
                    solve_small(a, b, n)
                    c = 0.0
                    f0, f1, f2 = i - sh[d, 0], j - sh[d, 1], k - sh[d, 2]
                    for m in range(n):
                        if not bnd or keep[m][x0, x1, x2]:
                            below = ufs[d][m][f0, f1, f2] >= 0.0
                            c += (vfs[m][i - di, j - dj, k - dk] if below else vfs[m][i, j, k]) * b[m]
                    c *= s[d]
                    if e > lo[d]:
                        A[i - di, j - dj, k - dk, 2 + 2 * d] += c
                    if e < hi[d]:
                        A[i, j, k, 1 + 2 * d] += c


@njit(cache=True)
def pressure_rhs(A, P, div, rhs, lo, hi):
    """Eq. 29 as a residual: rhs = -(kap P + dt sum_m div(theta_m u_m)); returns (rhs.rhs, max |rhs|).

    rhs is dimensionless: the mismatch of sum theta after the step (a relative volume).
    """
    rr = 0.0
    m = 0.0
    for i in range(lo[0], hi[0]):
        for j in range(lo[1], hi[1]):
            for k in range(lo[2], hi[2]):
                v = -(A[i, j, k, 0] * P[i, j, k] + div[i, j, k])
                rhs[i, j, k] = v
                rr += v * v
                m = max(m, abs(v))
    return rr, m


@njit(cache=True)
def add_increment(P, dP, out, lo, hi):
    """out = P + dP over the interior (eq. 30 accumulated over outer iterations)."""
    for i in range(lo[0], hi[0]):
        for j in range(lo[1], hi[1]):
            for k in range(lo[2], hi[2]):
                out[i, j, k] = P[i, j, k] + dP[i, j, k]
