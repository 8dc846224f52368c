"""MPM shape functions: linear, uGIMP and CPDI weights of a particle, as scalars per axis.

Conventions
-----------
* Particles: ``px`` (n,3); ``lp`` (n,3) particle half-widths in physical units (uGIMP
  only, ``dx/(2*ppc)``: Uintah's p.size).
* Grid: node (I,J,K) sits at ``anchor + (I,J,K)*dx``; node arrays use LOCAL indices,
  ``global = local + node_low``, scalar arrays (nx,ny,nz), vector ones (nx,ny,nz,3).
* Active axes ``act``: bit d set when axis d has more than one cell. An inactive axis has
  ONE node layer (local index 0, weight 1, gradient 0), so a 2D particle touches 4
  (linear) / 9 (GIMP) nodes and a 1D one 2 / 3.

CPDI (Sadeghirad, Brannon & Burghardt 2011; Uintah's cpdi and fast_cpdi) averages the linear
weights over the corners x_p + sum_k s_k r_k (s_k = +-1) of the particle's deformed domain,
r_k = F e_k l_k (column k of F times the half-width: Uintah's 0.5 F p.size), and takes the
gradient of that average over the parallelogram (parallelepiped): grad S_i = sum_c N_i(x_c)
J^-T s_c / n_c with J = [r_1 r_2 r_3] (the paper's alpha vectors). Each corner is a linear stencil
whose per-axis values carry it: weights w (times 1/n_c on the first active axis) and "derivatives"
g = w A_d, A = J^-T s_c, so the products w w w and g w w of the kernels give S and grad S.
``lp`` is then the (n, 18) domain array of ``cpdi_domains``: r_1, r_2, r_3, then the rows of J^-1.
A kernel visits ``_corners(kind, act)`` stencils per particle (1 for linear and GIMP).

``_stencil`` gives a particle's base node and, per axis, its weights and their
derivatives (three each; the third is 0 for linear): LLVM keeps them in registers and,
with ``kind``/``act`` compile-time constants, folds the inactive axes away. The fused
kernels that use it are in transfer.py (the step) and kernels.py (output-only stress).

``_stencil_put`` / ``_stencil_get`` split it in two for the hot kernels, which run in chunks of
CHUNK particles: first every particle's base node and weights (a short loop: the processor
overlaps the floor/convert/index chains of many particles), then the work at the nodes, whose
loads no longer wait on that chain. The stored values are exactly _stencil's. The first loop
also asks the cache for the node values the second will read (``_prefetch_nodes``): node
arrays written by an earlier task come from memory, and a particle's four node rows are
otherwise demand misses the processor cannot hide.
"""
import numpy as np
from llvmlite import ir
from numba import njit, types
from numba.core import cgutils
from numba.extending import intrinsic

LINEAR = 0
GIMP = 1
CPDI = 2
FM = {'contract'}

# bit of the axis mask `act`: axisymmetric (Uintah's <axisymmetric>): x is r, y is the axial z,
# the collapsed z is the angle theta; the stencil's z slots (gz0, gz1, gz2) then carry the
# hoop values t_a of the r nodes (the node's <S/r> is t_a w_b, Uintah's d_S.z)
AXI = 8


@njit(cache=True, fastmath=FM, inline="always")
def _gimp3(xi, lc):
    """uGIMP weights and d/dxi (cell units) of the three nodes around a particle at xi (cell units)
    with half-width lc: the hat function averaged over [xi - lc, xi + lc] (Bardenhagen & Kober
    2004), in Uintah's GIMPInterpolator form: three pieces by where the particle sits in its cell,
    so a node beyond the particle's reach gets exactly 0 (not a round-off square). Returns the base
    node (nodes ix - 1 .. ix + 1 when xi - ix <= 1/2, else ix .. ix + 2) and the values ascending."""
    ix = np.floor(xi)
    p0 = xi - ix
    p1 = xi - (ix + 1.0)
    lo = p0 <= 0.5
    p2 = xi - (ix - 1.0) if lo else xi - (ix + 2.0)
    q = 0.25 / lc
    near0 = p0 <= lc                # the particle reaches the node below ix
    near1 = p0 > 1.0 - lc           # ... the node above ix + 1
    a0 = 1.0 + lc - p0
    a1 = 1.0 + lc + p1
    a2 = 1.0 + lc - p2 if near0 else 1.0 + lc + p2
    c0 = 1.0 - (p0 * p0 + lc * lc) * (2.0 * q)
    c1 = 1.0 - (p1 * p1 + lc * lc) * (2.0 * q)
    f0 = c0 if near0 else (a0 * a0 * q if near1 else 1.0 - p0)
    f1 = a1 * a1 * q if near0 else (c1 if near1 else 1.0 + p1)
    f2 = a2 * a2 * q if near0 or near1 else 0.0
    d0 = -p0 * (4.0 * q) if near0 else (-a0 * (2.0 * q) if near1 else -1.0)
    d1 = a1 * (2.0 * q) if near0 else (-p1 * (4.0 * q) if near1 else 1.0)
    d2 = -a2 * (2.0 * q) if near0 else (a2 * (2.0 * q) if near1 else 0.0)
    if lo:
        return int(ix) - 1, f2, f0, f1, d2, d0, d1
    return int(ix), f0, f1, f2, d0, d1, d2


@njit(cache=True, fastmath=FM, inline="always")
def _ax(kind, active, x, a0, ih, l, h):
    """Base node (global index) and weights / d/dx of one axis: (i, w0, w1, w2, g0, g1, g2).
    h is the spacing, 1 / ih: GIMP places the particle at (x - a0) / h cells as Uintah's
    Level::positionToIndex does, so its pieces and zeros fall where Uintah's do."""
    if not active:
        return 0, 1.0, 0.0, 0.0, 0.0, 0.0, 0.0
    if kind == LINEAR:
        xi = (x - a0) * ih
        i = int(np.floor(xi))
        f = xi - i
        return i, 1.0 - f, f, 0.0, -ih, ih, 0.0
    i, s0, s1, s2, d0, d1, d2 = _gimp3((x - a0) / h, l / h)
    return i, s0, s1, s2, d0 * ih, d1 * ih, d2 * ih


@njit(cache=True, fastmath=FM, inline="always")
def _hat_moments(u):
    """Integrals from 0 to u (clamped to [-1, 1]) of the hat N(v) = 1 - |v|: of N, v N, sign(v)
    (= -N') and v sign(v)."""
    u = min(max(u, -1.0), 1.0)
    au = abs(u)
    return u - 0.5 * u * au, u * u * (0.5 - au / 3.0), au, 0.5 * u * au


@njit(cache=True, fastmath=FM, inline="always")
def _axi_node(xn, h, c0, c1, inv_D):
    """Axisymmetric GIMP values of the r node at xn (spacing h) for a particle spanning [c0, c1]
    in r, inv_D = 1 / int r dr: the r-weighted averages S = <N>, G = <dN/dr> and the hoop
    value t = <N/r> (all with the weight r dr: the particle's volume per radian)."""
    a0, a1, b0, b1 = _hat_moments((c0 - xn) / h)
    A0, A1, B0, B1 = _hat_moments((c1 - xn) / h)
    t = h * (A0 - a0) * inv_D
    return xn * t + h * h * (A1 - a1) * inv_D, -(xn * (B0 - b0) + h * (B1 - b1)) * inv_D, t


@njit(cache=True, fastmath=FM, inline="always")
def _ax_axi(kind, x, a0, ih, l):
    """The r axis of an axisymmetric run: (i, w0, w1, w2, g0, g1, g2, t0, t1, t2), t the hoop
    values. Linear: the usual weights and t = S/r at the particle (Uintah's AxiLinear).
    GIMP: the averages of the hat over the particle's r extent [r - l, r + l] (cut at the
    axis) weighted by r (Uintah's AxiGIMP, Nairn's axisymmetric GIMP), base node as GIMP."""
    if kind == LINEAR:
        i, w0, w1, w2, g0, g1, g2 = _ax(kind, True, x, a0, ih, l, 1.0)
        rinv = 1.0 / x
        return i, w0, w1, w2, g0, g1, g2, w0 * rinv, w1 * rinv, 0.0
    h = 1.0 / ih
    i = int(np.floor((x - a0) * ih + 0.5)) - 1
    c0 = max(x - l, 0.0)
    c1 = x + l
    inv_D = 2.0 / (c1 * c1 - c0 * c0)
    xn = a0 + i * h
    w0, g0, t0 = _axi_node(xn, h, c0, c1, inv_D)
    w1, g1, t1 = _axi_node(xn + h, h, c0, c1, inv_D)
    w2, g2, t2 = _axi_node(xn + 2.0 * h, h, c0, c1, inv_D)
    return i, w0, w1, w2, g0, g1, g2, t0, t1, t2


@njit(cache=True, fastmath=FM, inline="always")
def _sel(a, x0, x1, x2):
    return x0 if a == 0 else (x1 if a == 1 else x2)


@njit(cache=True, inline="always")
def _corners(kind, act):
    """Linear stencils a particle visits: 1, or CPDI's 2^(active axes) domain corners."""
    if kind != CPDI:
        return 1
    return (2 if act & 1 else 1) * (2 if act & 2 else 1) * (2 if act & 4 else 1)


@njit(cache=True)
def _visits(kind, act, n):
    """(particle, corner) of every stencil of n particles, for the output-only kernels whose kind
    is a run-time value."""
    nq = _corners(kind, act)
    out = np.empty((n * nq, 2), np.int64)
    for p in range(n):
        for q in range(nq):
            out[p * nq + q, 0] = p
            out[p * nq + q, 1] = q
    return out


@njit(cache=True, fastmath=FM, inline="always")
def _cpdi_ax(act, d, x, lp, p, q, a0, ih):
    """CPDI: base node and per-axis values of axis d for corner q (bit b of q: the sign of the
    b-th active domain vector), weights scaled by 1/n_corners on the first active axis."""
    if not act & (1 << d):
        return 0, 1.0, 0.0, 0.0, 0.0, 0.0, 0.0
    off = 0.0
    A = 0.0
    b = 0
    for k in range(3):
        if act & (1 << k):
            s = 1.0 if (q >> b) & 1 else -1.0
            off += s * lp[p, 3 * k + d]
            A += s * lp[p, 9 + 3 * k + d]
            b += 1
    xi = (x + off - a0) * ih
    i = int(np.floor(xi))
    f = xi - i
    scale = 1.0 / _corners(CPDI, act) if d == (0 if act & 1 else (1 if act & 2 else 2)) else 1.0
    w0 = (1.0 - f) * scale
    w1 = f * scale
    return i, w0, w1, 0.0, w0 * A, w1 * A, 0.0


@njit(cache=True, fastmath=FM, inline="always")
def _axis_r(kind, act, px, lp, p, q, anchor, ih):
    """The r axis of an axisymmetric run with its hoop values (see _ax_axi); CPDI (Uintah's
    axiCpdiInterpolator): corner q's linear weights on the in-plane domain, t = w / r of the
    particle's own radius."""
    if kind == CPDI:
        i, w0, w1, w2, g0, g1, g2 = _cpdi_ax(act, 0, px[p, 0], lp, p, q, anchor[0], ih[0])
        rinv = 1.0 / px[p, 0]
        return i, w0, w1, w2, g0, g1, g2, w0 * rinv, w1 * rinv, 0.0
    return _ax_axi(kind, px[p, 0], anchor[0], ih[0], lp[p, 0])


@njit(cache=True, fastmath=FM, inline="always")
def _axis(kind, act, d, px, lp, p, q, anchor, ih):
    if kind == CPDI:
        return _cpdi_ax(act, d, px[p, d], lp, p, q, anchor[d], ih[d])
    return _ax(kind, act & (1 << d) != 0, px[p, d], anchor[d], ih[d], lp[p, d], ih[3 + d])


@njit(cache=True, fastmath=FM, inline="always")
def _stencil(kind, act, px, lp, p, anchor, ih, node_low, q=0):
    """The weights of particle p (CPDI: of its corner q) on its three axes, base indices made local."""
    if act & AXI:
        i, wx0, wx1, wx2, gx0, gx1, gx2, gz0, gz1, gz2 = _axis_r(kind, act, px, lp, p, q, anchor, ih)
        k, wz0, wz1, wz2 = 0, 1.0, 0.0, 0.0
    else:
        i, wx0, wx1, wx2, gx0, gx1, gx2 = _axis(kind, act, 0, px, lp, p, q, anchor, ih)
        k, wz0, wz1, wz2, gz0, gz1, gz2 = _axis(kind, act, 2, px, lp, p, q, anchor, ih)
    j, wy0, wy1, wy2, gy0, gy1, gy2 = _axis(kind, act, 1, px, lp, p, q, anchor, ih)
    if act & 1:
        i -= node_low[0]
    if act & 2:
        j -= node_low[1]
    if act & 4:
        k -= node_low[2]
    return (i, j, k, wx0, wx1, wx2, gx0, gx1, gx2, wy0, wy1, wy2, gy0, gy1, gy2,
            wz0, wz1, wz2, gz0, gz1, gz2)


CHUNK = 64


@intrinsic
def _prefetch(typingctx, arr, idx):
    """Hint (llvm.prefetch: read, keep in all levels) that arr[idx] of a 1D array will be read
    soon; no effect on any result, and an address outside the array does not fault."""
    if not (isinstance(arr, types.Array) and arr.ndim == 1 and isinstance(idx, types.Integer)):
        return None

    def codegen(context, builder, sig, args):
        ary = context.make_array(sig.args[0])(context, builder, args[0])
        i8p = ir.IntType(8).as_pointer()
        i32 = ir.IntType(32)
        fn = cgutils.get_or_insert_function(builder.module, ir.FunctionType(ir.VoidType(), [i8p, i32, i32, i32]),
                                            "llvm.prefetch.p0")
        builder.call(fn, [builder.bitcast(builder.gep(ary.data, [args[1]]), i8p), i32(0), i32(3), i32(1)])
        return context.get_dummy_value()
    return types.void(arr, idx), codegen


@njit(cache=True, inline="always")
def _prefetch_nodes(kind, act, i, j, k, sh1, sh2, flat):
    """Prefetch the vector values (3 per node, flat C order) of the nodes of a stencil with local
    base node (i, j, k): the first and last value of each run of nodes contiguous in memory."""
    na, nb, nc = _counts(kind, act)
    for a in range(na):
        if not act & 4:         # nc == 1, as a test numba_fold takes before typing
            f = np.uint64(3 * (((i + a) * sh1 + j) * sh2 + k))
            _prefetch(flat, f)
            _prefetch(flat, f + np.uint64(3 * (nb - 1) * sh2 + 2))
        else:
            for b in range(nb):
                f = np.uint64(3 * (((i + a) * sh1 + j + b) * sh2 + k))
                _prefetch(flat, f)
                _prefetch(flat, f + np.uint64(3 * nc - 1))


@njit(cache=True, inline="always")
def _scratch(kind, act):
    """Stencil scratch of one chunk: the base nodes (i, j, k), (3, CHUNK n_corners), and per axis
    (w1, w0, w2, g0, g1, g2), (3, 6, CHUNK n_corners); linear stores only the fraction f = w1.
    The stencil index (particle, then corner) runs last, so a chunk's values of one kind are
    contiguous."""
    n = CHUNK * _corners(kind, act)
    return np.empty((3, n), np.int64), np.empty((3, 6, n))


@njit(cache=True, fastmath=FM, inline="always")
def _ax_put(kind, act, d, px, lp, p, c, anchor, ih, q, sw):
    if kind == CPDI:
        i, w0, w1, w2, g0, g1, g2 = _cpdi_ax(act, d, px[p, d], lp, p, c, anchor[d], ih[d])
    else:
        i, w0, w1, w2, g0, g1, g2 = _ax(kind, True, px[p, d], anchor[d], ih[d], lp[p, d], ih[3 + d])
    sw[d, 0, q] = w1
    if kind != LINEAR:
        sw[d, 1, q] = w0
        sw[d, 2, q] = w2
        sw[d, 3, q] = g0
        sw[d, 4, q] = g1
        sw[d, 5, q] = g2
    return i


@njit(cache=True, fastmath=FM, inline="always")
def _stencil_put(kind, act, px, lp, p, anchor, ih, node_low, q, sw, c=0):
    """Store the weights of _stencil of particle p (CPDI: corner c) as row q of sw; returns its
    local base node (i, j, k) (0 on an inactive axis)."""
    i = j = k = 0
    if act & AXI:
        i, w0, w1, w2, g0, g1, g2, t0, t1, t2 = _axis_r(kind, act, px, lp, p, c, anchor, ih)
        i -= node_low[0]
        sw[0, 0, q] = w1
        if kind != LINEAR:
            sw[0, 1, q] = w0
            sw[0, 2, q] = w2
            sw[0, 3, q] = g0
            sw[0, 4, q] = g1
            sw[0, 5, q] = g2
        sw[2, 3, q] = t0
        sw[2, 4, q] = t1
        sw[2, 5, q] = t2
    elif act & 1:
        i = _ax_put(kind, act, 0, px, lp, p, c, anchor, ih, q, sw) - node_low[0]
    if act & 2:
        j = _ax_put(kind, act, 1, px, lp, p, c, anchor, ih, q, sw) - node_low[1]
    if act & 4:
        k = _ax_put(kind, act, 2, px, lp, p, c, anchor, ih, q, sw) - node_low[2]
    return i, j, k


@njit(cache=True, fastmath=FM, inline="always")
def _ax_get(kind, active, q, d, ih, sw):
    if not active:
        return 1.0, 0.0, 0.0, 0.0, 0.0, 0.0
    if kind == LINEAR:
        f = sw[d, 0, q]
        return 1.0 - f, f, 0.0, -ih, ih, 0.0
    return sw[d, 1, q], sw[d, 0, q], sw[d, 2, q], sw[d, 3, q], sw[d, 4, q], sw[d, 5, q]


@njit(cache=True, fastmath=FM, inline="always")
def _stencil_get(kind, act, q, ih, sw):
    """The weights and gradients of _stencil stored in row q of sw."""
    wx0, wx1, wx2, gx0, gx1, gx2 = _ax_get(kind, act & 1 != 0, q, 0, ih[0], sw)
    wy0, wy1, wy2, gy0, gy1, gy2 = _ax_get(kind, act & 2 != 0, q, 1, ih[1], sw)
    if act & AXI:               # the hoop values in the z slots (see AXI)
        wz0, wz1, wz2, gz0, gz1, gz2 = 1.0, 0.0, 0.0, sw[2, 3, q], sw[2, 4, q], sw[2, 5, q]
    else:
        wz0, wz1, wz2, gz0, gz1, gz2 = _ax_get(kind, act & 4 != 0, q, 2, ih[2], sw)
    return wx0, wx1, wx2, gx0, gx1, gx2, wy0, wy1, wy2, gy0, gy1, gy2, wz0, wz1, wz2, gz0, gz1, gz2


@njit(cache=True, fastmath=FM, inline="always")
def _over_nodes(visit, kind, act, ijk, sh, st, clip, acc, args):
    """The loop over the nodes of one stencil, for every kernel: base node ijk (local), the
    weights and gradients st (as _stencil_get gives them) on arrays of shape sh; at each node
    acc = visit(acc, args, act, x, y, z, n, wa, wb, wc, ga, gb, gc, ha): local index (x, y, z), flat
    index n, S = wa wb wc, grad S = (ga wb wc, wa gb wc, wa wb gc), ha the z slot of axis a
    (AXI's <S/r>). clip: nodes beyond sh are passed over. visit is an inlined njit function,
    so each kernel compiles to its own loop."""
    na, nb, nc = _counts(kind, act)
    i, j, k = ijk
    sh0, sh1, sh2 = sh
    wx0, wx1, wx2, gx0, gx1, gx2, wy0, wy1, wy2, gy0, gy1, gy2, wz0, wz1, wz2, gz0, gz1, gz2 = st
    for a in range(na):
        wa = _sel(a, wx0, wx1, wx2)
        ga = _sel(a, gx0, gx1, gx2)
        for b in range(nb):
            wb = _sel(b, wy0, wy1, wy2)
            gb = _sel(b, gy0, gy1, gy2)
            for c in range(nc):
                if clip and not (0 <= i + a < sh0 and 0 <= j + b < sh1 and 0 <= k + c < sh2):
                    continue
                acc = visit(acc, args, act, i + a, j + b, k + c, ((i + a) * sh1 + j + b) * sh2 + k + c, wa, wb,
                            _sel(c, wz0, wz1, wz2), ga, gb, _sel(c, gz0, gz1, gz2), _sel(a, gz0, gz1, gz2))
    return acc


@njit(cache=True, inline="always")
def _counts(kind, act):
    n = 3 if kind == GIMP else 2
    return (n if act & 1 else 1), (n if act & 2 else 1), (n if act & 4 else 1)


@njit(cache=True, inline="always")
def _inv_dx(dx):
    """The inverse spacings, then the spacings (GIMP places particles by dividing by them)."""
    ih = np.empty(3)
    for d in range(3):
        ih[d] = 1.0 / dx[d] if dx[d] != 0.0 else 0.0
    return ih[0], ih[1], ih[2], float(dx[0]), float(dx[1]), float(dx[2])


@njit(cache=True, fastmath=FM)
def cpdi_domains(act, F, lp, dx, lcrit, out):
    """CPDI's domain array of each particle, out (n, 18): r_1, r_2, r_3 (physical units), then the
    rows of J^-1, J = [r_k] on the active axes (identity on the others). As Uintah, the domain
    in cells is half of (F p.size)(:, k) with p.size in cells: F acts on the cell-scaled size, so
    r_k = h_d sum_m F_dm l_mk / h_m on axis d (h the cell spacing; where the cells are not cubes a
    shear F_dm, d != m, weighs l_mk by h_d/h_m, unlike F l of the physical domain); l_k e_k the
    undeformed half-vectors, or with a size matrix lp (n, 3, 3) its columns H e_k (a
    <smoothcyl>'s turned sectors). Where a corner
    r_3 +- r_1 +- r_2 reaches beyond lcrit cells it is scaled back to lcrit and the r_k are
    rebuilt from those corners (Uintah's cpdi_lcrit)."""
    ih0, ih1, ih2 = _inv_dx(dx)[:3]
    ih = (ih0, ih1, ih2)
    for p in range(F.shape[0]):
        r = np.empty((3, 3))        # r[k, d]: component d of r_k, in cells
        for k in range(3):
            for d in range(3):
                if dx[d] == 0.0:
                    r[k, d] = 0.0
                elif lp.ndim == 2:
                    r[k, d] = F[p, d, k] * lp[p, k] * ih[k]
                else:
                    FH = (F[p, d, 0] * lp[p, 0, k] * (ih[0] / ih[d]) + F[p, d, 1] * lp[p, 1, k] * (ih[1] / ih[d])
                          + F[p, d, 2] * lp[p, 2, k] * (ih[2] / ih[d]))
                    r[k, d] = FH * ih[d]
        # the corners r_3 + a r_1 + b r_2 (Uintah's la, lb, lc, ld: a, b = ++, +-, -+, --)
        c = np.empty((4, 3))
        scaled = False
        for n in range(4):
            a = 1.0 if n < 2 else -1.0
            b = 1.0 if n % 2 == 0 else -1.0
            l2 = 0.0
            for d in range(3):
                c[n, d] = a * r[0, d] + b * r[1, d] + r[2, d]
                l2 += c[n, d] * c[n, d]
            if l2 > lcrit * lcrit:
                s = lcrit / np.sqrt(l2)
                for d in range(3):
                    c[n, d] *= s
                scaled = True
        if scaled:
            for d in range(3):
                r[0, d] = 0.25 * (c[0, d] + c[1, d] - c[2, d] - c[3, d])
                r[1, d] = 0.25 * (c[0, d] - c[1, d] + c[2, d] - c[3, d])
                r[2, d] = 0.25 * (c[0, d] + c[1, d] + c[2, d] + c[3, d])
        J = np.zeros((3, 3))        # J[d, k] = r_k[d] (physical) on the active block
        for k in range(3):
            for d in range(3):
                on = act & (1 << k) != 0 and act & (1 << d) != 0
                v = r[k, d] * dx[d] if on else 0.0
                out[p, 3 * k + d] = v
                J[d, k] = v if on else (1.0 if d == k else 0.0)
        det = (J[0, 0] * (J[1, 1] * J[2, 2] - J[1, 2] * J[2, 1]) - J[0, 1] * (J[1, 0] * J[2, 2] - J[1, 2] * J[2, 0])
               + J[0, 2] * (J[1, 0] * J[2, 1] - J[1, 1] * J[2, 0]))
        inv = 1.0 / det
        for k in range(3):
            for d in range(3):
                k1, k2, d1, d2 = (d + 1) % 3, (d + 2) % 3, (k + 1) % 3, (k + 2) % 3
                cof = J[k1, d1] * J[k2, d2] - J[k1, d2] * J[k2, d1]      # (J^-1)[k, d] = cof(J)[d, k] / det
                out[p, 9 + 3 * k + d] = cof * inv if act & (1 << k) and act & (1 << d) else 0.0
