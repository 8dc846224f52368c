"""MPM shape functions: linear and uGIMP weights of a particle, as scalars per axis.

Conventions
-----------
* Particles: ``px`` (n,3); ``lp`` (n,3) particle half-widths in physical units (uGIMP
  only, ``dx/(2*ppc)``: Uintah's p.size).
* Grid: node (I,J,K) sits at ``anchor + (I,J,K)*dx``; node arrays use LOCAL indices,
  ``global = local + node_low``, scalar arrays (nx,ny,nz), vector ones (nx,ny,nz,3).
* Active axes ``act``: bit d set when axis d has more than one cell. An inactive axis has
  ONE node layer (local index 0, weight 1, gradient 0), so a 2D particle touches 4
  (linear) / 9 (GIMP) nodes and a 1D one 2 / 3.

``_stencil`` gives a particle's base node and, per axis, its weights and their
derivatives (three each; the third is 0 for linear): LLVM keeps them in registers and,
with ``kind``/``act`` compile-time constants, folds the inactive axes away. The fused
kernels that use it are in transfer.py (the step) and kernels.py (output-only stress).
"""
import numpy as np
from numba import njit

LINEAR = 0
GIMP = 1
FM = {'contract'}


@njit(cache=True, fastmath=FM, inline="always")
def _gimp1(r, l, inv):
    """uGIMP weight and d/dr (cell units) for node-particle offset r and
    half-width l (inv = 0.5/l): the hat function averaged over [r-l, r+l] (Bardenhagen &
    Kober 2004), written branch-free via the hat's antiderivative."""
    c1 = min(max(r + l, -1.0), 1.0)
    c0 = min(max(r - l, -1.0), 1.0)
    S = (c1 - c0 - 0.5 * (c1 * abs(c1) - c0 * abs(c0))) * inv
    dS = (max(0.0, 1.0 - abs(r + l)) - max(0.0, 1.0 - abs(r - l))) * inv
    return S, dS


@njit(cache=True, fastmath=FM, inline="always")
def _ax(kind, active, x, a0, ih, l):
    """Base node (global index) and weights / d/dx of one axis: (i, w0, w1, w2, g0, g1, g2)."""
    if not active:
        return 0, 1.0, 0.0, 0.0, 0.0, 0.0, 0.0
    xi = (x - a0) * ih
    if kind == LINEAR:
        i = int(np.floor(xi))
        f = xi - i
        return i, 1.0 - f, f, 0.0, -ih, ih, 0.0
    i = int(np.floor(xi + 0.5)) - 1
    lc = l * ih
    inv = 0.5 / lc
    s0, d0 = _gimp1(xi - i, lc, inv)
    s1, d1 = _gimp1(xi - (i + 1), lc, inv)
    s2, d2 = _gimp1(xi - (i + 2), lc, inv)
    return i, s0, s1, s2, d0 * ih, d1 * ih, d2 * ih


@njit(cache=True, fastmath=FM, inline="always")
def _sel(a, x0, x1, x2):
    return x0 if a == 0 else (x1 if a == 1 else x2)


@njit(cache=True, fastmath=FM, inline="always")
def _stencil(kind, act, px, lp, p, anchor, ih, node_low):
    """The weights of particle p on its three axes, base indices made local."""
    i, wx0, wx1, wx2, gx0, gx1, gx2 = _ax(kind, act & 1 != 0, px[p, 0], anchor[0], ih[0], lp[p, 0])
    j, wy0, wy1, wy2, gy0, gy1, gy2 = _ax(kind, act & 2 != 0, px[p, 1], anchor[1], ih[1], lp[p, 1])
    k, wz0, wz1, wz2, gz0, gz1, gz2 = _ax(kind, act & 4 != 0, px[p, 2], anchor[2], ih[2], lp[p, 2])
    if act & 1:
        i -= node_low[0]
    if act & 2:
        j -= node_low[1]
    if act & 4:
        k -= node_low[2]
    return (i, j, k, wx0, wx1, wx2, gx0, gx1, gx2, wy0, wy1, wy2, gy0, gy1, gy2,
            wz0, wz1, wz2, gz0, gz1, gz2)


@njit(cache=True, inline="always")
def _counts(kind, act):
    n = 2 if kind == LINEAR else 3
    return (n if act & 1 else 1), (n if act & 2 else 1), (n if act & 4 else 1)


@njit(cache=True, inline="always")
def _inv_dx(dx):
    ih = np.empty(3)
    for d in range(3):
        ih[d] = 1.0 / dx[d] if dx[d] != 0.0 else 0.0
    return ih[0], ih[1], ih[2]
