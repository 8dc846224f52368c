"""Geometric multigrid on the gathered coarse levels (every rank holds the same copy).

The fine level is smoothed patch by patch with ghost exchange (pcg.py); its residual,
summed onto the 2x coarser grid, reaches every rank through one sum reduction, and
this module runs the rest of the V-cycle there: symmetric Gauss-Seidel (forward
before, backward after the coarse correction), sum restriction, piecewise-constant
prolongation, coarse operators by re-discretisation (1/2 the summed face
coefficients per coarsened direction) and a dense solve on the coarsest grid.
Memory and work on each rank are those of the whole coarse grid (1/2^d of the fine
cells): simple and exact in parallel, not meant for thousands of ranks.

Level arrays: kap (nx, ny, nz); F (3, nx+1, ny+1, nz+1), F[d, i, j, k] the coefficient
of the low d-face of cell (i, j, k), index n_d the high boundary face (a wall when 0,
Dirichlet otherwise; for a periodic direction face n_d is face 0).
"""
from __future__ import annotations

import numpy as np
from numba import njit

COARSEST = 64           # stop coarsening at this many cells
DENSE_MAX = 1024        # dense inverse on the coarsest level up to this many cells


@njit(cache=True)
def _nb(u, F, d, i, j, k, n, per):
    """(a_lo, u_lo, a_hi, u_hi): coefficients and values of the two d-neighbours."""
    e = i if d == 0 else (j if d == 1 else k)
    a_lo = F[d, i, j, k]
    if e > 0:
        u_lo = u[i - 1, j, k] if d == 0 else (u[i, j - 1, k] if d == 1 else u[i, j, k - 1])
    elif per:
        u_lo = u[n - 1, j, k] if d == 0 else (u[i, n - 1, k] if d == 1 else u[i, j, n - 1])
    else:
        u_lo = 0.0
    if e + 1 < n:
        a_hi = F[d, i + 1, j, k] if d == 0 else (F[d, i, j + 1, k] if d == 1 else F[d, i, j, k + 1])
        u_hi = u[i + 1, j, k] if d == 0 else (u[i, j + 1, k] if d == 1 else u[i, j, k + 1])
    elif per:
        a_hi = F[d, 0, j, k] if d == 0 else (F[d, i, 0, k] if d == 1 else F[d, i, j, 0])
        u_hi = u[0, j, k] if d == 0 else (u[i, 0, k] if d == 1 else u[i, j, 0])
    else:
        a_hi = F[d, n, j, k] if d == 0 else (F[d, i, n, k] if d == 1 else F[d, i, j, n])
        u_hi = 0.0
    return a_lo, u_lo, a_hi, u_hi


@njit(cache=True)
def _row(kap, F, u, i, j, k, dims, per, shape):
    """(diagonal, sum of off-diagonal a_f u_nb) of row (i, j, k)."""
    dg = kap[i, j, k]
    off = 0.0
    for d in range(3):
        if dims[d]:
            a_lo, u_lo, a_hi, u_hi = _nb(u, F, d, i, j, k, shape[d], per[d])
            dg += a_lo + a_hi
            off += a_lo * u_lo + a_hi * u_hi
    return dg, off


@njit(cache=True)
def residual(kap, F, u, b, r, dims, per):
    """r = b - A u."""
    sh = kap.shape
    for i in range(sh[0]):
        for j in range(sh[1]):
            for k in range(sh[2]):
                dg, off = _row(kap, F, u, i, j, k, dims, per, sh)
                r[i, j, k] = b[i, j, k] - (dg * u[i, j, k] - off)


@njit(cache=True)
def gauss_seidel(kap, F, u, b, dims, per, forward):
    """One lexicographic Gauss-Seidel sweep (backward when not forward: symmetric pair)."""
    sh = kap.shape
    for ii in range(sh[0]):
        i = ii if forward else sh[0] - 1 - ii
        for jj in range(sh[1]):
            j = jj if forward else sh[1] - 1 - jj
            for kk in range(sh[2]):
                k = kk if forward else sh[2] - 1 - kk
                dg, off = _row(kap, F, u, i, j, k, dims, per, sh)
                u[i, j, k] = (b[i, j, k] + off) / dg


@njit(cache=True)
def coarsen(kap, F, cf, kc, Fc):
    """Coarse operator: kap summed over children; faces summed, halved along coarsened d. An
    odd extent leaves its last coarse cell one fine cell wide: its high boundary face (fine
    face n, odd) is the coarse boundary face; the face arrays' padding beyond a direction's
    cells is skipped."""
    sh = kap.shape
    for i in range(sh[0]):
        a = i // 2 if cf[0] else i
        for j in range(sh[1]):
            b = j // 2 if cf[1] else j
            for k in range(sh[2]):
                c = k // 2 if cf[2] else k
                kc[a, b, c] += kap[i, j, k]
    for d in range(3):
        w = 0.5 if cf[d] else 1.0
        for i in range(F.shape[1]):
            for j in range(F.shape[2]):
                for k in range(F.shape[3]):
                    e = i if d == 0 else (j if d == 1 else k)
                    if (d != 0 and i >= sh[0]) or (d != 1 and j >= sh[1]) or (d != 2 and k >= sh[2]):
                        continue                        # padding: no cell there
                    if cf[d] and e % 2 == 1 and e != sh[d]:
                        continue                        # interior fine face of a coarse cell
                    # cells i -> i // 2; along d the faces 2m -> m and the boundary face n -> its
                    # coarse one, (n + 1) // 2, for n odd as well as even
                    a = ((i + 1) // 2 if d == 0 else i // 2) if cf[0] else i
                    b = ((j + 1) // 2 if d == 1 else j // 2) if cf[1] else j
                    c = ((k + 1) // 2 if d == 2 else k // 2) if cf[2] else k
                    Fc[d, a, b, c] += w * F[d, i, j, k]


@njit(cache=True)
def restrict(r, rc, cf):
    sh = r.shape
    for i in range(sh[0]):
        for j in range(sh[1]):
            for k in range(sh[2]):
                rc[i // 2 if cf[0] else i, j // 2 if cf[1] else j, k // 2 if cf[2] else k] += r[i, j, k]


@njit(cache=True)
def prolong_add(u, ec, cf):
    sh = u.shape
    for i in range(sh[0]):
        for j in range(sh[1]):
            for k in range(sh[2]):
                u[i, j, k] += ec[i // 2 if cf[0] else i, j // 2 if cf[1] else j, k // 2 if cf[2] else k]


@njit(cache=True)
def _dense_entry(kap, F, u, i, j, k, dims, per, sh, col, M):
    dg, off = _row(kap, F, u, i, j, k, dims, per, sh)
    M[(i * sh[1] + j) * sh[2] + k, col] = dg * u[i, j, k] - off


@njit(cache=True)
def dense(kap, F, dims, per, M):
    """The level's operator as a dense matrix (coarsest level; M zeroed by the caller). Column c
    is the operator on the unit vector of cell c, evaluated on the rows that c's stencil reaches
    (the cell and its face neighbours): the others are zero."""
    sh = kap.shape
    u = np.zeros(sh)
    for i in range(sh[0]):
        for j in range(sh[1]):
            for k in range(sh[2]):
                col = (i * sh[1] + j) * sh[2] + k
                u[i, j, k] = 1.0
                _dense_entry(kap, F, u, i, j, k, dims, per, sh, col, M)
                for d in range(3):
                    if not dims[d]:
                        continue
                    n = sh[d]
                    e = i if d == 0 else (j if d == 1 else k)
                    for s in (-1, 1):
                        f = e + s
                        if f < 0 or f >= n:
                            if not per[d]:
                                continue
                            f = (f + n) % n
                        if f == e:
                            continue
                        a = f if d == 0 else i
                        b = f if d == 1 else j
                        c = f if d == 2 else k
                        _dense_entry(kap, F, u, a, b, c, dims, per, sh, col, M)
                u[i, j, k] = 0.0


class Hierarchy:
    """The coarse levels below the fine grid and one symmetric V-cycle over them."""

    def __init__(self, kap, F, dims, periodic, nsweeps=1):
        self.dims = np.asarray(dims, dtype=np.int64)
        self.per = np.asarray(periodic, dtype=np.int64)
        self.nsweeps = max(1, int(nsweeps))
        self.levels = [(kap, F)]
        self.cfs = []
        while kap.size > COARSEST:
            sh = kap.shape
            cf = np.array([self.dims[d] and sh[d] >= 4 for d in range(3)], dtype=np.int64)
            if not cf.any():
                break
            csh = tuple((sh[d] + 1) // 2 if cf[d] else sh[d] for d in range(3))
            kc = np.zeros(csh)
            Fc = np.zeros((3,) + tuple(c + 1 for c in csh))
            coarsen(kap, F, cf, kc, Fc)
            self.cfs.append(cf)
            self.levels.append((kc, Fc))
            kap, F = kc, Fc
        self.inverse = None
        if kap.size <= DENSE_MAX:
            M = np.zeros((kap.size, kap.size))
            dense(kap, F, self.dims, self.per, M)
            self.inverse = np.linalg.inv(M)
        self.shapes = [lv[0].shape for lv in self.levels]

    def vcycle(self, b, lev=0):
        """u ~ A^-1 b on level `lev` by one V-cycle (a fixed symmetric linear operator)."""
        kap, F = self.levels[lev]
        if lev == len(self.levels) - 1:
            if self.inverse is not None:
                return (self.inverse @ b.ravel()).reshape(b.shape)
            u = np.zeros_like(b)
            for _ in range(30):
                gauss_seidel(kap, F, u, b, self.dims, self.per, True)
                gauss_seidel(kap, F, u, b, self.dims, self.per, False)
            return u
        u = np.zeros_like(b)
        for _ in range(self.nsweeps):
            gauss_seidel(kap, F, u, b, self.dims, self.per, True)
        r = np.empty_like(b)
        residual(kap, F, u, b, r, self.dims, self.per)
        rc = np.zeros(self.shapes[lev + 1])
        restrict(r, rc, self.cfs[lev])
        prolong_add(u, self.vcycle(rc, lev + 1), self.cfs[lev])
        for _ in range(self.nsweeps):
            gauss_seidel(kap, F, u, b, self.dims, self.per, False)
        return u
