"""MPM shape functions (linear and uGIMP) and fused particle<->grid kernels.

Conventions
-----------
* Particles: ``px`` (n,3), ``pvel`` (n,3), ``pstress`` (n,3,3), ``lp`` (n,3)
  particle half-widths (physical units, used by GIMP only; ``dx/(2*ppc)``).
* Grid: node (I,J,K) sits at ``anchor + (I,J,K)*dx``.  Node arrays are indexed
  with LOCAL indices, ``global = local + node_low``.  Scalar node arrays are
  (nx,ny,nz), vector ones (nx,ny,nz,3).
* Dimension ``dim``: axes ``>= dim`` have ONE node layer (local index 0,
  weight 1, gradient 0), so a 2D particle touches 4 (linear) / 9 (GIMP)
  nodes and a 1D one 2 / 3.

The generic kernels take ``kind`` and ``dim`` as plain ints; the public
specialised kernels (chosen once in Python via :func:`get_interpolator`) pass
them as constants and inline the generic body, so LLVM folds the branches
and unrolls the node loops.

Node arrays passed to the fused kernels must be C-contiguous (they are
flattened internally).  For speed ``p2g`` sums consecutive particles that
share a stencil in a local buffer, so keep particles sorted by cell (linear)
or by nearest node (GIMP); any order gives the same result.
"""
from collections import namedtuple

import numpy as np
from numba import njit

LINEAR = 0
GIMP = 1
KINDS = {"linear": LINEAR, "gimp": GIMP}


def nodes_per_axis(kind):
    """Nodes a particle touches along one active axis."""
    return 2 if KINDS.get(kind, kind) == LINEAR else 3


def num_nodes(kind, dim):
    """Nodes a particle touches: linear 2/4/8, GIMP 3/9/27 for dim 1/2/3."""
    return nodes_per_axis(kind) ** dim


def lp_from_ppc(n, dx, ppc):
    """uGIMP half-widths ``dx/(2*ppc)`` per direction for n particles."""
    lp = np.asarray(dx, np.float64) / (2.0 * np.asarray(ppc, np.float64))
    return np.ascontiguousarray(np.broadcast_to(lp, (n, 3)), dtype=np.float64)


@njit(cache=True, fastmath={'contract'}, inline="always")
def _gimp1(r, l, inv):
    """uGIMP weight and d/dr (cell units) for node-particle offset r and
    half-width l (inv = 0.5/l): the hat function averaged over [r-l, r+l] (Bardenhagen &
    Kober 2004), written branch-free via the hat's antiderivative."""
    c1 = min(max(r + l, -1.0), 1.0)
    c0 = min(max(r - l, -1.0), 1.0)
    S = (c1 - c0 - 0.5 * (c1 * abs(c1) - c0 * abs(c0))) * inv
    dS = (max(0.0, 1.0 - abs(r + l)) - max(0.0, 1.0 - abs(r - l))) * inv
    return S, dS


@njit(cache=True, fastmath={'contract'}, inline="always")
def _axis(kind, d, dim, x, lpd, a0, ih, lo, nlocal, base, w, g):
    """Fill base local index, weights and gradients of one axis (ih = 1/dx)."""
    if d >= dim:
        base[d] = 0
        w[d, 0] = 1.0
        g[d, 0] = 0.0
        return True
    xi = (x - a0) * ih
    if kind == LINEAR:
        i = int(np.floor(xi))
        f = xi - i
        w[d, 0] = 1.0 - f
        w[d, 1] = f
        g[d, 0] = -ih
        g[d, 1] = ih
        nn = 2
    else:
        i = int(np.floor(xi + 0.5)) - 1  # nearest node minus one
        l = lpd * ih
        inv = 0.5 / l
        for a in range(3):
            s, ds = _gimp1(xi - (i + a), l, inv)
            w[d, a] = s
            g[d, a] = ds * ih
        nn = 3
    b = i - lo
    base[d] = b
    return b >= 0 and b + nn <= nlocal


@njit(cache=True, fastmath={'contract'}, inline="always")
def _setup(kind, dim, dx, shape):
    """Scratch arrays and flat node offsets of the particle stencil."""
    na = 2 if kind == LINEAR else 3
    nb = na if dim >= 2 else 1
    nc = na if dim >= 3 else 1
    nn = na * nb * nc
    off = np.empty(nn, np.int64)
    q = 0
    for a in range(na):
        for b in range(nb):
            for c in range(nc):
                off[q] = (a * shape[1] + b) * shape[2] + c
                q += 1
    ih = np.empty(3)
    for d in range(3):
        ih[d] = 1.0 / dx[d] if dx[d] != 0.0 else 0.0
    return (na, nb, nc, nn, off, ih, np.zeros(3, np.int64), np.zeros((3, 3)),
            np.zeros((3, 3)), np.zeros(nn), np.zeros((nn, 3)))


@njit(cache=True, fastmath={'contract'}, inline="always")
def _particle(kind, dim, px, lp, p, anchor, ih, node_low, shape, base, w, g,
              na, nb, nc, S, G):
    """Weights S[q], gradients G[q,:] of particle p; returns flat base index."""
    ok = True
    for d in range(3):
        ok &= _axis(kind, d, dim, px[p, d], lp[p, d], anchor[d], ih[d],
                    node_low[d], shape[d], base, w, g)
    if not ok:
        raise IndexError("particle's nodes lie outside the patch node arrays")
    q = 0
    for a in range(na):
        wa = w[0, a]
        ga = g[0, a]
        for b in range(nb):
            wb = w[1, b] if dim >= 2 else 1.0
            gb = g[1, b] if dim >= 2 else 0.0
            for c in range(nc):
                wc = w[2, c] if dim >= 3 else 1.0
                gc = g[2, c] if dim >= 3 else 0.0
                S[q] = wa * wb * wc
                G[q, 0] = ga * wb * wc
                G[q, 1] = wa * gb * wc
                G[q, 2] = wa * wb * gc
                q += 1
    return (base[0] * shape[1] + base[1]) * shape[2] + base[2]


@njit(cache=True, fastmath={'contract'}, inline="always")
def _fill_weights(kind, dim, px, lp, anchor, dx, node_low, shape, ni, S, dS):
    na, nb, nc, nn, off, ih, base, w, g, Sq, Gq = _setup(kind, dim, dx, shape)
    for p in range(px.shape[0]):
        _particle(kind, dim, px, lp, p, anchor, ih, node_low, shape, base, w,
                  g, na, nb, nc, Sq, Gq)
        q = 0
        for a in range(na):
            for b in range(nb):
                for c in range(nc):
                    ni[p, q, 0] = base[0] + a
                    ni[p, q, 1] = base[1] + b
                    ni[p, q, 2] = base[2] + c
                    S[p, q] = Sq[q]
                    dS[p, q, 0] = Gq[q, 0]
                    dS[p, q, 1] = Gq[q, 1]
                    dS[p, q, 2] = Gq[q, 2]
                    q += 1


@njit(cache=True, fastmath={'contract'}, inline="always")
def _p2g(kind, dim, px, pmass, pvel, pvol, pstress, pfext, lp, anchor, dx,
         node_low, gmass, gmom, gvol, gfext, gfint):
    """Scatter m, m*v (eq. 11), V, f_ext and f_int = -sum V sigma.grad S (eq. 15).

    Contributions of consecutive particles with the same stencil are summed
    in a small local buffer first (fast for cell-sorted particles)."""
    shape = np.array(gmass.shape, np.int64)
    na, nb, nc, nn, off, ih, base, w, g, Sq, Gq = _setup(kind, dim, dx, shape)
    fm = gmass.reshape(-1)
    fv = gvol.reshape(-1)
    fp = gmom.reshape(-1)
    fe = gfext.reshape(-1)
    fi = gfint.reshape(-1)
    acc = np.zeros((nn, 11))
    cur = -1
    n = px.shape[0]
    for p in range(n + 1):
        if p < n:
            f0 = _particle(kind, dim, px, lp, p, anchor, ih, node_low, shape,
                           base, w, g, na, nb, nc, Sq, Gq)
        else:
            f0 = -2
        if f0 != cur:
            if cur >= 0:
                for q in range(nn):
                    f = np.uint64(cur + off[q])
                    f3 = np.uint64(3 * (cur + off[q]))
                    fm[f] += acc[q, 0]
                    fv[f] += acc[q, 1]
                    for d in range(3):
                        fp[f3 + np.uint64(d)] += acc[q, 2 + d]
                        fe[f3 + np.uint64(d)] += acc[q, 5 + d]
                        fi[f3 + np.uint64(d)] += acc[q, 8 + d]
            if p == n:
                break
            acc[:, :] = 0.0
            cur = f0
        m = pmass[p]
        V = pvol[p]
        mv0 = m * pvel[p, 0]
        mv1 = m * pvel[p, 1]
        mv2 = m * pvel[p, 2]
        fe0 = pfext[p, 0]
        fe1 = pfext[p, 1]
        fe2 = pfext[p, 2]
        s00 = V * pstress[p, 0, 0]
        s01 = V * pstress[p, 0, 1]
        s02 = V * pstress[p, 0, 2]
        s10 = V * pstress[p, 1, 0]
        s11 = V * pstress[p, 1, 1]
        s12 = V * pstress[p, 1, 2]
        s20 = V * pstress[p, 2, 0]
        s21 = V * pstress[p, 2, 1]
        s22 = V * pstress[p, 2, 2]
        for q in range(nn):
            S = Sq[q]
            G0 = Gq[q, 0]
            G1 = Gq[q, 1]
            G1 = Gq[q, 1] if dim >= 2 else 0.0
            G2 = Gq[q, 2] if dim >= 3 else 0.0
            acc[q, 0] += m * S
            acc[q, 1] += V * S
            acc[q, 2] += mv0 * S
            acc[q, 3] += mv1 * S
            acc[q, 4] += mv2 * S
            acc[q, 5] += fe0 * S
            acc[q, 6] += fe1 * S
            acc[q, 7] += fe2 * S
            if dim == 1:
                acc[q, 8] -= s00 * G0
                acc[q, 9] -= s10 * G0
                acc[q, 10] -= s20 * G0
            elif dim == 2:
                acc[q, 8] -= s00 * G0 + s01 * G1
                acc[q, 9] -= s10 * G0 + s11 * G1
                acc[q, 10] -= s20 * G0 + s21 * G1
            else:
                acc[q, 8] -= s00 * G0 + s01 * G1 + s02 * G2
                acc[q, 9] -= s10 * G0 + s11 * G1 + s12 * G2
                acc[q, 10] -= s20 * G0 + s21 * G1 + s22 * G2


@njit(cache=True, fastmath={'contract'}, inline="always")
def _g2p(kind, dim, px, pvel, lp, anchor, dx, node_low, gvel, gacc, dt,
         px_new, pvel_new, pL):
    """v_p += dt sum S a_i, x_p += dt sum S v_i (eq. 12), L_p = sum v_i (x) grad S (eq. 14).

    ``px_new``/``pvel_new`` may alias ``px``/``pvel``."""
    shape = np.array(gvel.shape[:3], np.int64)
    na, nb, nc, nn, off, ih, base, w, g, Sq, Gq = _setup(kind, dim, dx, shape)
    fv = gvel.reshape(-1)
    fa = gacc.reshape(-1)
    for p in range(px.shape[0]):
        f0 = _particle(kind, dim, px, lp, p, anchor, ih, node_low, shape,
                       base, w, g, na, nb, nc, Sq, Gq)
        a0 = a1 = a2 = 0.0
        v0 = v1 = v2 = 0.0
        L00 = L01 = L02 = L10 = L11 = L12 = L20 = L21 = L22 = 0.0
        for q in range(nn):
            f3 = np.uint64(3 * (f0 + off[q]))
            S = Sq[q]
            G0 = Gq[q, 0]
            G1 = Gq[q, 1]
            G2 = Gq[q, 2] if dim >= 3 else 0.0
            gv0 = fv[f3]
            gv1 = fv[f3 + np.uint64(1)]
            gv2 = fv[f3 + np.uint64(2)]
            a0 += S * fa[f3]
            a1 += S * fa[f3 + np.uint64(1)]
            a2 += S * fa[f3 + np.uint64(2)]
            v0 += S * gv0
            v1 += S * gv1
            v2 += S * gv2
            L00 += gv0 * G0
            L10 += gv1 * G0
            L20 += gv2 * G0
            if dim >= 2:
                L01 += gv0 * G1
                L11 += gv1 * G1
                L21 += gv2 * G1
            if dim >= 3:
                L02 += gv0 * G2
                L12 += gv1 * G2
                L22 += gv2 * G2
        pvel_new[p, 0] = pvel[p, 0] + dt * a0
        pvel_new[p, 1] = pvel[p, 1] + dt * a1
        pvel_new[p, 2] = pvel[p, 2] + dt * a2
        px_new[p, 0] = px[p, 0] + dt * v0
        px_new[p, 1] = px[p, 1] + dt * v1
        px_new[p, 2] = px[p, 2] + dt * v2
        pL[p, 0, 0] = L00
        pL[p, 0, 1] = L01
        pL[p, 0, 2] = L02
        pL[p, 1, 0] = L10
        pL[p, 1, 1] = L11
        pL[p, 1, 2] = L12
        pL[p, 2, 0] = L20
        pL[p, 2, 1] = L21
        pL[p, 2, 2] = L22


# ---- specialised kernels: (kind, dim) are compile-time constants -------------
# fill(px, lp, anchor, dx, node_low, shape, ni, S, dS)
# p2g(px, pmass, pvel, pvol, pstress, pfext, lp, anchor, dx, node_low,
#     gmass, gmom, gvol, gfext, gfint)                      (accumulates, +=)
# g2p(px, pvel, lp, anchor, dx, node_low, gvel, gacc, dt, px_new, pvel_new, pL)

@njit(cache=True, fastmath={'contract'})
def fill_linear_1d(px, lp, anchor, dx, node_low, shape, ni, S, dS):
    _fill_weights(LINEAR, 1, px, lp, anchor, dx, node_low, shape, ni, S, dS)


@njit(cache=True, fastmath={'contract'})
def fill_linear_2d(px, lp, anchor, dx, node_low, shape, ni, S, dS):
    _fill_weights(LINEAR, 2, px, lp, anchor, dx, node_low, shape, ni, S, dS)


@njit(cache=True, fastmath={'contract'})
def fill_linear_3d(px, lp, anchor, dx, node_low, shape, ni, S, dS):
    _fill_weights(LINEAR, 3, px, lp, anchor, dx, node_low, shape, ni, S, dS)


@njit(cache=True, fastmath={'contract'})
def fill_gimp_1d(px, lp, anchor, dx, node_low, shape, ni, S, dS):
    _fill_weights(GIMP, 1, px, lp, anchor, dx, node_low, shape, ni, S, dS)


@njit(cache=True, fastmath={'contract'})
def fill_gimp_2d(px, lp, anchor, dx, node_low, shape, ni, S, dS):
    _fill_weights(GIMP, 2, px, lp, anchor, dx, node_low, shape, ni, S, dS)


@njit(cache=True, fastmath={'contract'})
def fill_gimp_3d(px, lp, anchor, dx, node_low, shape, ni, S, dS):
    _fill_weights(GIMP, 3, px, lp, anchor, dx, node_low, shape, ni, S, dS)


@njit(cache=True, fastmath={'contract'})
def p2g_linear_1d(px, pm, pv, pvol, ps, pf, lp, an, dx, lo, gm, gp, gv, ge, gi):
    _p2g(LINEAR, 1, px, pm, pv, pvol, ps, pf, lp, an, dx, lo, gm, gp, gv, ge, gi)


@njit(cache=True, fastmath={'contract'})
def p2g_linear_2d(px, pm, pv, pvol, ps, pf, lp, an, dx, lo, gm, gp, gv, ge, gi):
    _p2g(LINEAR, 2, px, pm, pv, pvol, ps, pf, lp, an, dx, lo, gm, gp, gv, ge, gi)


@njit(cache=True, fastmath={'contract'})
def p2g_linear_3d(px, pm, pv, pvol, ps, pf, lp, an, dx, lo, gm, gp, gv, ge, gi):
    _p2g(LINEAR, 3, px, pm, pv, pvol, ps, pf, lp, an, dx, lo, gm, gp, gv, ge, gi)


@njit(cache=True, fastmath={'contract'})
def p2g_gimp_1d(px, pm, pv, pvol, ps, pf, lp, an, dx, lo, gm, gp, gv, ge, gi):
    _p2g(GIMP, 1, px, pm, pv, pvol, ps, pf, lp, an, dx, lo, gm, gp, gv, ge, gi)


@njit(cache=True, fastmath={'contract'})
def p2g_gimp_2d(px, pm, pv, pvol, ps, pf, lp, an, dx, lo, gm, gp, gv, ge, gi):
    _p2g(GIMP, 2, px, pm, pv, pvol, ps, pf, lp, an, dx, lo, gm, gp, gv, ge, gi)


@njit(cache=True, fastmath={'contract'})
def p2g_gimp_3d(px, pm, pv, pvol, ps, pf, lp, an, dx, lo, gm, gp, gv, ge, gi):
    _p2g(GIMP, 3, px, pm, pv, pvol, ps, pf, lp, an, dx, lo, gm, gp, gv, ge, gi)


@njit(cache=True, fastmath={'contract'})
def g2p_linear_1d(px, pv, lp, an, dx, lo, gvel, gacc, dt, px_new, pv_new, pL):
    _g2p(LINEAR, 1, px, pv, lp, an, dx, lo, gvel, gacc, dt, px_new, pv_new, pL)


@njit(cache=True, fastmath={'contract'})
def g2p_linear_2d(px, pv, lp, an, dx, lo, gvel, gacc, dt, px_new, pv_new, pL):
    _g2p(LINEAR, 2, px, pv, lp, an, dx, lo, gvel, gacc, dt, px_new, pv_new, pL)


@njit(cache=True, fastmath={'contract'})
def g2p_linear_3d(px, pv, lp, an, dx, lo, gvel, gacc, dt, px_new, pv_new, pL):
    _g2p(LINEAR, 3, px, pv, lp, an, dx, lo, gvel, gacc, dt, px_new, pv_new, pL)


@njit(cache=True, fastmath={'contract'})
def g2p_gimp_1d(px, pv, lp, an, dx, lo, gvel, gacc, dt, px_new, pv_new, pL):
    _g2p(GIMP, 1, px, pv, lp, an, dx, lo, gvel, gacc, dt, px_new, pv_new, pL)


@njit(cache=True, fastmath={'contract'})
def g2p_gimp_2d(px, pv, lp, an, dx, lo, gvel, gacc, dt, px_new, pv_new, pL):
    _g2p(GIMP, 2, px, pv, lp, an, dx, lo, gvel, gacc, dt, px_new, pv_new, pL)


@njit(cache=True, fastmath={'contract'})
def g2p_gimp_3d(px, pv, lp, an, dx, lo, gvel, gacc, dt, px_new, pv_new, pL):
    _g2p(GIMP, 3, px, pv, lp, an, dx, lo, gvel, gacc, dt, px_new, pv_new, pL)


_TABLE = {
    ("linear", 1): (fill_linear_1d, p2g_linear_1d, g2p_linear_1d),
    ("linear", 2): (fill_linear_2d, p2g_linear_2d, g2p_linear_2d),
    ("linear", 3): (fill_linear_3d, p2g_linear_3d, g2p_linear_3d),
    ("gimp", 1): (fill_gimp_1d, p2g_gimp_1d, g2p_gimp_1d),
    ("gimp", 2): (fill_gimp_2d, p2g_gimp_2d, g2p_gimp_2d),
    ("gimp", 3): (fill_gimp_3d, p2g_gimp_3d, g2p_gimp_3d),
}

Interpolator = namedtuple("Interpolator", "kind dim nn fill p2g g2p weights")


def get_interpolator(kind, dim):
    """Pick the specialised kernels once.  kind: 'linear' | 'gimp'
    (Uintah <interpolator>), dim: 1, 2 or 3."""
    kind = kind.lower()
    if kind not in KINDS or dim not in (1, 2, 3):
        raise ValueError(f"unsupported interpolator {kind!r} dim={dim}")
    fill, p2g, g2p = _TABLE[(kind, dim)]
    nn = num_nodes(kind, dim)

    def weights(px, lp, anchor, dx, node_low, shape):
        """Return (ni (n,nn,3) int64 local indices, S (n,nn), dS (n,nn,3)).
        shape: local node-array shape (nx,ny,nz), used for bounds checks."""
        n = px.shape[0]
        ni = np.empty((n, nn, 3), np.int64)
        S = np.empty((n, nn))
        dS = np.empty((n, nn, 3))
        fill(px, lp, np.asarray(anchor, np.float64), np.asarray(dx, np.float64),
             np.asarray(node_low, np.int64), np.asarray(shape[:3], np.int64),
             ni, S, dS)
        return ni, S, dS

    return Interpolator(kind, dim, nn, fill, p2g, g2p, weights)
