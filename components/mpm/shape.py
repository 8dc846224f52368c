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
        if nc == 1:
            f = np.uint64(3 * (((i + a) * sh1 + j) * sh2 + k))
            _prefetch(flat, f)
            _prefetch(flat, f + np.uint64(3 * (nb - 1) * sh2 + 2))
        else:
            for b in range(nb):
                f = np.uint64(3 * (((i + a) * sh1 + j + b) * sh2 + k))
                _prefetch(flat, f)
                _prefetch(flat, f + np.uint64(3 * nc - 1))


@njit(cache=True, inline="always")
def _scratch():
    """Stencil scratch of one chunk: the base nodes (i, j, k), (3, CHUNK), and per axis
    (w1, w0, w2, g0, g1, g2), (3, 6, CHUNK); linear stores only the fraction f = w1. The
    particle index runs last, so a chunk's values of one kind are contiguous."""
    return np.empty((3, CHUNK), np.int64), np.empty((3, 6, CHUNK))


@njit(cache=True, fastmath=FM, inline="always")
def _ax_put(kind, d, x, a0, ih, l, q, sw):
    i, w0, w1, w2, g0, g1, g2 = _ax(kind, True, x, a0, ih, l)
    sw[d, 0, q] = w1
    if kind != LINEAR:
        sw[d, 1, q] = w0
        sw[d, 2, q] = w2
        sw[d, 3, q] = g0
        sw[d, 4, q] = g1
        sw[d, 5, q] = g2
    return i


@njit(cache=True, fastmath=FM, inline="always")
def _stencil_put(kind, act, px, lp, p, anchor, ih, node_low, q, sw):
    """Store the weights of _stencil of particle p as row q of sw; returns its local base node
    (i, j, k) (0 on an inactive axis)."""
    i = j = k = 0
    if act & 1:
        i = _ax_put(kind, 0, px[p, 0], anchor[0], ih[0], lp[p, 0], q, sw) - node_low[0]
    if act & 2:
        j = _ax_put(kind, 1, px[p, 1], anchor[1], ih[1], lp[p, 1], q, sw) - node_low[1]
    if act & 4:
        k = _ax_put(kind, 2, px[p, 2], anchor[2], ih[2], lp[p, 2], q, sw) - node_low[2]
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
    wz0, wz1, wz2, gz0, gz1, gz2 = _ax_get(kind, act & 4 != 0, q, 2, ih[2], sw)
    return wx0, wx1, wx2, gx0, gx1, gx2, wy0, wy1, wy2, gy0, gy1, gy2, wz0, wz1, wz2, gz0, gz1, gz2


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
