"""Fused particle<->grid kernels of the explicit MPM step, written with scalar weights.

Each kernel evaluates a particle's shape weights once, as scalars per axis (base node,
three weights, three gradients: LLVM keeps them in registers; no scratch arrays that
could alias the node arrays), and does all the work that particle needs at its nodes:

  p2g        m_i, (mv)_i, V_i (where a task reads it), fext_i (000 eq. 22), fint_i = -sum V sigma.grad S (eq. 24),
             straight into the warehouse's node arrays (owned + halo nodes); shares of
             ghost particles that fall beyond the halo are dropped (no scratch array,
             no copy).
  g2p        v_p += dt sum S a_i, x_p += dt sum S v*_i (000 eqs. 26-27), USL: L_p; MUSL:
             the updated momentum m_p v_p S scattered back in the same pass (004 eq. 13);
             owned particles are written compacted, with the totals and the
             minimum_particle_mass / maximum_particle_velocity deletion in the same loop.
  grad       L_p = sum v_i (x) grad S_i(x_p) (004 eq. 14), MUSL's stress-update gradient, F, V
             and, for the models in FUSED (comp_neo_hook), the stress in the same loop.

CPDI particles visit the linear stencils of their domain's corners in turn (shape._corners; one
stencil for linear and GIMP, the loop folded away), each corner's weights and gradients
carried in the same per-axis values, so every kernel below serves all interpolators. The loop
over one stencil's nodes is shape._over_nodes, each kernel with its node function (_g2p_node, _g2p_usl_node,
_velocity_gradient_node, _gather_node, _scatter_node, ...), inlined; but p2g's (_p2g_one), whose
internal force came out of it with other fused multiply-adds in 2D (not bitwise).

p2g and g2p run the particles in chunks of shape.CHUNK: a first loop stores every particle's
base node and weights (shape._stencil_put; g2p also prefetches the node rows it will read), a
second does the work at the nodes (shape._stencil_get); the numbers are those of one loop,
bitwise. (grad, whose neo-Hooke stress is arithmetic-bound, measured no faster so.)

Node sums are added particle by particle in particle-ID order, so 1 patch and many
patches agree bitwise. p2g and g2p read the owned and the ghost particles from their own
arrays (TaskView.get_split), run by run in the merged ID order (particle_kernels.runs):
nobody forms a merged copy of every ghosted variable. Node arrays are C-ordered with
local index = global - node_low. `act` is the mask of the level's active axes (bit d:
axis d has more than one cell; the weights: shape._stencil); an inactive axis has one
node layer, weight 1 and gradient 0. Every entry point has the interpolator and act as
compile-time constants (made on first use by the factories below, one per layout a run has).
"""
import functools

import numpy as np
from numba import njit

from .constitutive import comp_neo_hook
from .shape import (AXI, CHUNK, CPDI, GIMP, LINEAR, _corners, _counts, _inv_dx, _over_nodes, _prefetch_nodes, _scratch,
                    _sel, _stencil, _stencil_get, _stencil_put, _visits)

FM = {'contract'}

# constitutive models whose stress the grad pass computes with F, in the same loop
# (`model` of the grad kernels; 0: F and V only, the model runs afterwards)
NEO_HOOKE = 1
FUSED = {"comp_neo_hook": NEO_HOOKE}


@njit(cache=True, fastmath=FM, inline="always")
def _deform(act, p, o, dt, L00, L01, L02, L10, L11, L12, L20, L21, L22, F_old, F_out, vol_out, m, rho0):
    """F^{n+1} = (I + L dt) F^n (004 eq. 14) and V = m/rho0 det F (eq. 17) of particle p,
    written at o (kernels.deform, fused) and returned as (F00, ..., F22, V), so that a stress
    computed in the same pass takes them from registers, not back from F_out (measured 8 % off
    MUSL's grad pass). Without a z axis (act = 1, 3) L02 = L12 = L22 = 0: the z column of
    (I + L dt) is (0, 0, 1) and its products are left out (they would add exact zeros); the
    z row (out-of-plane velocity) is kept."""
    G00, G01, G02 = F_old[p, 0, 0], F_old[p, 0, 1], F_old[p, 0, 2]
    G10, G11, G12 = F_old[p, 1, 0], F_old[p, 1, 1], F_old[p, 1, 2]
    G20, G21, G22 = F_old[p, 2, 0], F_old[p, 2, 1], F_old[p, 2, 2]
    A00 = 1.0 + dt * L00
    A10 = dt * L10
    A20 = dt * L20
    A01 = dt * L01
    A11 = 1.0 + dt * L11
    A21 = dt * L21
    if act & AXI or not act & 4:    # no z column: the (r, z) / (x, y) rows need the first two rows of F only
        F00 = A00 * G00 + A01 * G10
        F01 = A00 * G01 + A01 * G11
        F02 = A00 * G02 + A01 * G12
        F10 = A10 * G00 + A11 * G10
        F11 = A10 * G01 + A11 * G11
        F12 = A10 * G02 + A11 * G12
        if act & AXI:       # L has the 2x2 (r, z) block and L22 = u_r / r: (I + L dt) is block-diagonal
            A22 = 1.0 + dt * L22
            F20 = A22 * G20
            F21 = A22 * G21
            F22 = A22 * G22
        else:
            F20 = A20 * G00 + A21 * G10 + G20
            F21 = A20 * G01 + A21 * G11 + G21
            F22 = A20 * G02 + A21 * G12 + G22
    else:
        A02 = dt * L02
        A12 = dt * L12
        A22 = 1.0 + dt * L22
        F00 = A00 * G00 + A01 * G10 + A02 * G20
        F01 = A00 * G01 + A01 * G11 + A02 * G21
        F02 = A00 * G02 + A01 * G12 + A02 * G22
        F10 = A10 * G00 + A11 * G10 + A12 * G20
        F11 = A10 * G01 + A11 * G11 + A12 * G21
        F12 = A10 * G02 + A11 * G12 + A12 * G22
        F20 = A20 * G00 + A21 * G10 + A22 * G20
        F21 = A20 * G01 + A21 * G11 + A22 * G21
        F22 = A20 * G02 + A21 * G12 + A22 * G22
    F_out[o, 0, 0] = F00
    F_out[o, 0, 1] = F01
    F_out[o, 0, 2] = F02
    F_out[o, 1, 0] = F10
    F_out[o, 1, 1] = F11
    F_out[o, 1, 2] = F12
    F_out[o, 2, 0] = F20
    F_out[o, 2, 1] = F21
    F_out[o, 2, 2] = F22
    J = (F00 * (F11 * F22 - F12 * F21) - F01 * (F10 * F22 - F12 * F20)
         + F02 * (F10 * F21 - F11 * F20))
    V = m / rho0 * J
    vol_out[o] = V
    return F00, F01, F02, F10, F11, F12, F20, F21, F22, V


@njit(cache=True, fastmath=FM, inline="always")
def _store_L(L_out, o, L00, L01, L02, L10, L11, L12, L20, L21, L22):
    L_out[o, 0, 0] = L00
    L_out[o, 0, 1] = L01
    L_out[o, 0, 2] = L02
    L_out[o, 1, 0] = L10
    L_out[o, 1, 1] = L11
    L_out[o, 1, 2] = L12
    L_out[o, 2, 0] = L20
    L_out[o, 2, 1] = L21
    L_out[o, 2, 2] = L22


@njit(cache=True, fastmath=FM, inline="always")
def _add_L(act, wa, wb, wc, ga, gb, gc, ta, gv0, gv1, gv2, L00, L01, L02, L10, L11, L12, L20, L21, L22):
    """L += v_i (x) grad S_i (004 eq. 14) of one node with velocity (gv0, gv1, gv2) and per-axis weights
    wa, wb, wc / derivatives ga, gb, gc; the terms of inactive axes are left out (their gradient is 0).
    Axisymmetric (act & AXI): the (r, z) block and the hoop rate L22 += u_r <S/r> (ta: the node's r
    hoop value, shape.AXI), as Uintah's computeAxiSymVelocityGradient; no theta row.
    Returns the nine updated L terms (g2p's USL L and the grad pass share it)."""
    if act & AXI:
        G0 = ga * wb * wc
        G1 = wa * gb * wc
        L00 += gv0 * G0
        L10 += gv1 * G0
        L01 += gv0 * G1
        L11 += gv1 * G1
        L22 += gv0 * ta * wb
        return L00, L01, L02, L10, L11, L12, L20, L21, L22
    if act & 1:
        G0 = ga * wb * wc
        L00 += gv0 * G0
        L10 += gv1 * G0
        L20 += gv2 * G0
    if act & 2:
        G1 = wa * gb * wc
        L01 += gv0 * G1
        L11 += gv1 * G1
        L21 += gv2 * G1
    if act & 4:
        G2 = wa * wb * gc
        L02 += gv0 * G2
        L12 += gv1 * G2
        L22 += gv2 * G2
    return L00, L01, L02, L10, L11, L12, L20, L21, L22


@njit(cache=True, fastmath=FM, inline="always")
def _p2g(kind, act, own, ghost, runs, has_f, has_v, anchor, dx, node_low, gmass, gmom, gvol, gfext, gfint,
         proj, grad_own, grad_ghost):
    """Accumulate (+=) m, mv, V (if has_v), fext (if has_f), fint of the particles on the node
    arrays: the owned and ghost sources (x, m, v, V, sigma, fext, lp), run by run in their
    merged ID order (particle_kernels.runs), so every node adds its shares in particle-ID order.
    proj: Uintah's gradient-enhanced velocity projection, m (v_p + L_p (x_i - x_p)) at node i,
    with the particles' velocity gradients grad_own, grad_ghost of their last step."""
    sh0, sh1, sh2 = gmass.shape
    ih = _inv_dx(dx)
    fm = gmass.reshape(-1)
    fv = gvol.reshape(-1)
    fp = gmom.reshape(-1)
    fe = gfext.reshape(-1)
    fi = gfint.reshape(-1)
    sb, sw = _scratch(kind, act)
    nq = _corners(kind, act)
    for r in range(runs.shape[0]):
        px, pmass, pvel, pvol, pstress, pfext, lp = own if runs[r, 0] == 0 else ghost
        pgrad = grad_own if runs[r, 0] == 0 else grad_ghost
        for c0 in range(runs[r, 1], runs[r, 2], CHUNK):
            c1 = min(c0 + CHUNK, runs[r, 2])
            for p in range(c0, c1):
                for cq in range(nq):
                    q = (p - c0) * nq + cq
                    i, j, k = _stencil_put(kind, act, px, lp, p, anchor, ih, node_low, q, sw, cq)
                    sb[0, q] = i
                    sb[1, q] = j
                    sb[2, q] = k
            for p in range(c0, c1):
                for cq in range(nq):
                    q = (p - c0) * nq + cq
                    _p2g_one(kind, act, has_f, has_v, p, q, sb, _stencil_get(kind, act, q, ih, sw), sh0, sh1,
                             sh2, pmass, pvel, pvol, pstress, pfext, fm, fv, fp, fe, fi, proj, px, pgrad, anchor,
                             dx, node_low)


@njit(cache=True, fastmath=FM, inline="always")
def _p2g_one(kind, act, has_f, has_v, p, q, sb, st, sh0, sh1, sh2, pmass, pvel, pvol, pstress, pfext, fm, fv, fp, fe,
             fi, proj, px, pgrad, anchor, dx, node_low):
    """p2g's shares of particle p on the flat node arrays: weights st (_stencil_get), local base
    node (i, j, k) in column q of sb; shares on nodes beyond the arrays are dropped. proj: the
    momentum at node i is m (v + L (x_i - x_p)) (SerialMPM's interpolateParticlesToGrid with
    UseGradientEnhancedVelocityProjection), x_i = anchor + (local index + node_low) dx."""
    na, nb, nc = _counts(kind, act)
    wx0, wx1, wx2, gx0, gx1, gx2, wy0, wy1, wy2, gy0, gy1, gy2, wz0, wz1, wz2, gz0, gz1, gz2 = st
    i, j, k = sb[0, q], sb[1, q], sb[2, q]
    inside = i >= 0 and i + na <= sh0 and j >= 0 and j + nb <= sh1 and k >= 0 and k + nc <= sh2
    m = pmass[p]
    V = pvol[p]
    mv0 = m * pvel[p, 0]
    mv1 = m * pvel[p, 1]
    mv2 = m * pvel[p, 2]
    if act & AXI:           # no theta momentum, none along a collapsed axial direction either
        mv2 = 0.0
        if not act & 2:
            mv1 = 0.0
    s00 = V * pstress[p, 0, 0]
    s10 = V * pstress[p, 1, 0]
    s20 = V * pstress[p, 2, 0]
    s01 = V * pstress[p, 0, 1]
    s11 = V * pstress[p, 1, 1]
    s21 = V * pstress[p, 2, 1]
    s02 = V * pstress[p, 0, 2]
    s12 = V * pstress[p, 1, 2]
    s22 = V * pstress[p, 2, 2]
    for a in range(na):
        wa = _sel(a, wx0, wx1, wx2)
        ga = _sel(a, gx0, gx1, gx2)
        for b in range(nb):
            wb = _sel(b, wy0, wy1, wy2)
            gb = _sel(b, gy0, gy1, gy2)
            for c in range(nc):
                wc = _sel(c, wz0, wz1, wz2)
                gc = _sel(c, gz0, gz1, gz2)
                if not inside:
                    if not (0 <= i + a < sh0 and 0 <= j + b < sh1 and 0 <= k + c < sh2):
                        continue
                S = wa * wb * wc
                G0 = ga * wb * wc
                G1 = wa * gb * wc
                G2 = wa * wb * gc
                f = np.uint64(((i + a) * sh1 + j + b) * sh2 + k + c)
                f3 = np.uint64(3) * f
                fm[f] += m * S
                if has_v:
                    fv[f] += V * S
                if proj:
                    d0, d1, d2 = _node_offset(act, px, p, anchor, dx, node_low, i + a, j + b, k + c)
                    pv0 = m * (pvel[p, 0] - (pgrad[p, 0, 0] * d0 + pgrad[p, 0, 1] * d1 + pgrad[p, 0, 2] * d2))
                    pv1 = m * (pvel[p, 1] - (pgrad[p, 1, 0] * d0 + pgrad[p, 1, 1] * d1 + pgrad[p, 1, 2] * d2))
                    pv2 = m * (pvel[p, 2] - (pgrad[p, 2, 0] * d0 + pgrad[p, 2, 1] * d1 + pgrad[p, 2, 2] * d2))
                    if act & AXI:
                        pv2 = 0.0
                        if not act & 2:
                            pv1 = 0.0
                    fp[f3] += pv0 * S
                    fp[f3 + np.uint64(1)] += pv1 * S
                    fp[f3 + np.uint64(2)] += pv2 * S
                else:
                    fp[f3] += mv0 * S
                    fp[f3 + np.uint64(1)] += mv1 * S
                    fp[f3 + np.uint64(2)] += mv2 * S
                if has_f:
                    fe[f3] += pfext[p, 0] * S
                    if act & AXI:
                        if act & 2:
                            fe[f3 + np.uint64(1)] += pfext[p, 1] * S
                    else:
                        fe[f3 + np.uint64(1)] += pfext[p, 1] * S
                        fe[f3 + np.uint64(2)] += pfext[p, 2] * S
                if act & AXI:       # Uintah's axisymmetric internal force: hoop stress times <S/r>
                    H = _sel(a, gz0, gz1, gz2) * wb
                    fi[f3] -= s00 * G0 + s01 * G1 + s22 * H
                    fi[f3 + np.uint64(1)] -= s10 * G0 + s11 * G1
                elif act == 1:
                    fi[f3] -= s00 * G0
                    fi[f3 + np.uint64(1)] -= s10 * G0
                    fi[f3 + np.uint64(2)] -= s20 * G0
                elif act == 3:
                    fi[f3] -= s00 * G0 + s01 * G1
                    fi[f3 + np.uint64(1)] -= s10 * G0 + s11 * G1
                    fi[f3 + np.uint64(2)] -= s20 * G0 + s21 * G1
                else:
                    fi[f3] -= s00 * G0 + s01 * G1 + s02 * G2
                    fi[f3 + np.uint64(1)] -= s10 * G0 + s11 * G1 + s12 * G2
                    fi[f3 + np.uint64(2)] -= s20 * G0 + s21 * G1 + s22 * G2


@njit(cache=True, fastmath=FM, inline="always")
def _node_offset(act, px, p, anchor, dx, node_low, li, lj, lk):
    """x_p - x_i of particle p and the node of local index (li, lj, lk) (0 along an inactive axis,
    whose one node layer has no position of its own)."""
    d0 = px[p, 0] - (anchor[0] + (li + node_low[0]) * dx[0]) if act & 1 else 0.0
    d1 = px[p, 1] - (anchor[1] + (lj + node_low[1]) * dx[1]) if act & 2 else 0.0
    d2 = px[p, 2] - (anchor[2] + (lk + node_low[2]) * dx[2]) if act & 4 else 0.0
    return d0, d1, d2


@njit(cache=True, fastmath=FM, inline="always")
def _velocity_gradient_node(acc, args, act, x, y, z, n, wa, wb, wc, ga, gb, gc, ha):
    """L += v_i (x) grad S_i at one node (_add_L) of the node velocity array args (flat)."""
    L00, L01, L02, L10, L11, L12, L20, L21, L22 = acc
    f3 = np.uint64(3) * np.uint64(n)
    return _add_L(act, wa, wb, wc, ga, gb, gc, ha, args[f3], args[f3 + np.uint64(1)], args[f3 + np.uint64(2)],
                  L00, L01, L02, L10, L11, L12, L20, L21, L22)


@njit(cache=True, fastmath=FM, inline="always")
def _g2p_node(acc, args, act, x, y, z, n, wa, wb, wc, ga, gb, gc, ha):
    """g2p's sums at one node: += S a_i, S v*_i; args = (v*, a) (flat); acc the 6 running sums
    (MUSL's: its L is the grad pass's)."""
    a0, a1, a2, v0, v1, v2 = acc
    fv, fa = args
    S = wa * wb * wc
    f3 = np.uint64(3) * np.uint64(n)
    a0 += S * fa[f3]
    a1 += S * fa[f3 + np.uint64(1)]
    a2 += S * fa[f3 + np.uint64(2)]
    v0 += S * fv[f3]
    v1 += S * fv[f3 + np.uint64(1)]
    v2 += S * fv[f3 + np.uint64(2)]
    return a0, a1, a2, v0, v1, v2


@njit(cache=True, fastmath=FM, inline="always")
def _g2p_usl_node(acc, args, act, x, y, z, n, wa, wb, wc, ga, gb, gc, ha):
    """USL's sums at one node: _g2p_node's and v*_i (x) grad S_i; acc the 15 running sums (MUSL
    carries no L terms: 9 fewer values through every inlined level, less to type and lower)."""
    a0, a1, a2, v0, v1, v2, L00, L01, L02, L10, L11, L12, L20, L21, L22 = acc
    a0, a1, a2, v0, v1, v2 = _g2p_node((a0, a1, a2, v0, v1, v2), args, act, x, y, z, n, wa, wb, wc, ga, gb, gc, ha)
    L00, L01, L02, L10, L11, L12, L20, L21, L22 = _velocity_gradient_node(
        (L00, L01, L02, L10, L11, L12, L20, L21, L22), args[0], act, x, y, z, n, wa, wb, wc, ga, gb, gc, ha)
    return a0, a1, a2, v0, v1, v2, L00, L01, L02, L10, L11, L12, L20, L21, L22


@njit(cache=True, fastmath=FM, inline="always")
def _gather_node(acc, args, act, x, y, z, n, wa, wb, wc, ga, gb, gc, ha):
    """s += S g_i at one node of the node vector array args (flat): XPIC(2)'s S v_i and S (S+ S+ v)_i."""
    s0, s1, s2 = acc
    S = wa * wb * wc
    f3 = np.uint64(3) * np.uint64(n)
    return s0 + S * args[f3], s1 + S * args[f3 + np.uint64(1)], s2 + S * args[f3 + np.uint64(2)]


@njit(cache=True, fastmath=FM, inline="always")
def _scatter_node(acc, args, act, x, y, z, n, wa, wb, wc, ga, gb, gc, ha):
    """g_i += S (mv) at one node; args = (g flat, mv0, mv1, mv2): MUSL's and XPIC(2)'s scatters."""
    fo, mv0, mv1, mv2 = args
    S = wa * wb * wc
    f3 = np.uint64(3) * np.uint64(n)
    fo[f3] += mv0 * S
    fo[f3 + np.uint64(1)] += mv1 * S
    fo[f3 + np.uint64(2)] += mv2 * S
    return acc


@njit(cache=True, fastmath=FM, inline="always")
def _g2p_rows(kind, act, musl, xpic, part, first, end, owned, grid, outs, lim, acc):
    """Rows [first, end) of one source part = (x, v, m, lp): 000 eqs. 26-27 (see _g2p), or with
    xpic XPIC(2)'s update; grid = (anchor, ih, node_low, shape, fv, fa, fp, dt, scratch, fg, fs)
    (fg, fs: g.velocity and g.velSPSSP, read with xpic only), outs = (x_out, v_out, L_out,
    F_old, F_out, vol_out, rho0, write_L), lim = (check, min_mass, max_vel), acc = the
    running (o, n_del, totals); returns it updated."""
    px, pvel, pmass, lp = part
    anchor, ih, node_low, sh, fv, fa, fp, dt, sb, sw, fg, fs = grid
    sh0, sh1, sh2 = sh
    x_out, v_out, L_out, F_old, F_out, vol_out, rho0, write_L = outs
    check, min_mass, max_vel = lim
    o, n_del, t0, t1, t2, t3, t4, t5, t6, t7 = acc
    na, nb, nc = _counts(kind, act)
    nq = _corners(kind, act)
    for c0 in range(first, end, CHUNK):
        c1 = min(c0 + CHUNK, end)
        for p in range(c0, c1):
            for cq in range(nq):
                q = (p - c0) * nq + cq
                i, j, k = _stencil_put(kind, act, px, lp, p, anchor, ih, node_low, q, sw, cq)
                if not (i >= 0 and i + na <= sh0 and j >= 0 and j + nb <= sh1 and k >= 0 and k + nc <= sh2):
                    raise IndexError("particle's nodes lie outside the patch node arrays")
                sb[0, q] = i
                sb[1, q] = j
                sb[2, q] = k
                _prefetch_nodes(kind, act, i, j, k, sh1, sh2, fv)
                _prefetch_nodes(kind, act, i, j, k, sh1, sh2, fa)
        for p in range(c0, c1):
            u = np.uint64(p)          # unsigned particle indices: no negative-index wraparound
            a0 = a1 = a2 = 0.0
            v0 = v1 = v2 = 0.0
            L00 = L01 = L02 = L10 = L11 = L12 = L20 = L21 = L22 = 0.0
            for cq in range(nq):
                q = (p - c0) * nq + cq
                ijk = (sb[0, q], sb[1, q], sb[2, q])
                if musl:
                    a0, a1, a2, v0, v1, v2 = _over_nodes(_g2p_node, kind, act, ijk, sh,
                                                         _stencil_get(kind, act, q, ih, sw), False,
                                                         (a0, a1, a2, v0, v1, v2), (fv, fa))
                else:
                    a0, a1, a2, v0, v1, v2, L00, L01, L02, L10, L11, L12, L20, L21, L22 = _over_nodes(
                        _g2p_usl_node, kind, act, ijk, sh, _stencil_get(kind, act, q, ih, sw), False,
                        (a0, a1, a2, v0, v1, v2, L00, L01, L02, L10, L11, L12, L20, L21, L22), (fv, fa))
            if xpic:        # XPIC(2) (Hammerquist & Nairn 2017): v = 2 v+ - v++ + a dt
                s0 = s1 = s2 = ss0 = ss1 = ss2 = 0.0
                for cq in range(nq):
                    q = (p - c0) * nq + cq
                    st = _stencil_get(kind, act, q, ih, sw)
                    ijk = (sb[0, q], sb[1, q], sb[2, q])
                    s0, s1, s2 = _over_nodes(_gather_node, kind, act, ijk, sh, st, False, (s0, s1, s2), fg)
                    ss0, ss1, ss2 = _over_nodes(_gather_node, kind, act, ijk, sh, st, False, (ss0, ss1, ss2), fs)
                nv0 = 2.0 * s0 - ss0 + a0 * dt
                nv1 = 2.0 * s1 - ss1 + a1 * dt
                nv2 = 2.0 * s2 - ss2 + a2 * dt
            else:
                nv0 = pvel[u, 0] + dt * a0
                nv1 = pvel[u, 1] + dt * a1
                nv2 = pvel[u, 2] + dt * a2
            m = pmass[u]
            if musl:
                mv0 = m * nv0
                mv1 = m * nv1
                mv2 = m * nv2
                for cq in range(nq):
                    q = (p - c0) * nq + cq
                    _over_nodes(_scatter_node, kind, act, (sb[0, q], sb[1, q], sb[2, q]), sh,
                                _stencil_get(kind, act, q, ih, sw), False, 0.0, (fp, mv0, mv1, mv2))
            if not owned:
                continue
            if xpic:        # x += dt (v* - (a dt + v_p - 2 v+ + v++) / 2), as Uintah's SerialMPM
                x0 = px[u, 0] + v0 * dt - 0.5 * (a0 * dt + (pvel[u, 0] - 2.0 * s0) + ss0) * dt
                x1 = px[u, 1] + v1 * dt - 0.5 * (a1 * dt + (pvel[u, 1] - 2.0 * s1) + ss1) * dt
                x2 = px[u, 2] + v2 * dt - 0.5 * (a2 * dt + (pvel[u, 2] - 2.0 * s2) + ss2) * dt
            else:
                x0 = px[u, 0] + dt * v0
                x1 = px[u, 1] + dt * v1
                x2 = px[u, 2] + dt * v2
            w = np.uint64(o)
            if check:
                if m < min_mass or np.sqrt(nv0 * nv0 + nv1 * nv1 + nv2 * nv2) > max_vel:
                    x0 = np.nan
                    n_del += 1
            x_out[w, 0] = x0
            x_out[w, 1] = x1
            x_out[w, 2] = x2
            v_out[w, 0] = nv0
            v_out[w, 1] = nv1
            v_out[w, 2] = nv2
            if not musl:
                if write_L:
                    _store_L(L_out, w, L00, L01, L02, L10, L11, L12, L20, L21, L22)
                _deform(act, u, w, dt, L00, L01, L02, L10, L11, L12, L20, L21, L22, F_old, F_out, vol_out, m, rho0)
            t0 += m
            t1 += 0.5 * m * (nv0 ** 2 + nv1 ** 2 + nv2 ** 2)
            t2 += m * nv0
            t3 += m * nv1
            t4 += m * nv2
            t5 += m * x0
            t6 += m * x1
            t7 += m * x2
            o += 1
    return o, n_del, t0, t1, t2, t3, t4, t5, t6, t7


@njit(cache=True, fastmath=FM, inline="always")
def _g2p(kind, act, musl, xpic, own, ghost, runs, anchor, dx, node_low, gvs, gacc, dt, x_out, v_out, L_out, gmom,
         tot, min_mass, max_vel, write_L, F_old, F_out, vol_out, rho0, gvel, gspssp):
    """Update every particle given: the owned and ghost sources (x, v, m, lp), run by run
    in their merged ID order (as p2g); write the owned ones compacted to x_out / v_out; USL:
    F_out, vol_out (and L_out if write_L); MUSL: += m v_new S on gmom. xpic: XPIC(2)'s v and x
    from g.velocity (gvel) and g.velSPSSP (gspssp) too. Returns the number of particles
    deleted (x = NaN)."""
    sb, sw = _scratch(kind, act)
    grid = (anchor, _inv_dx(dx), node_low, gvs.shape[:3], gvs.reshape(-1), gacc.reshape(-1), gmom.reshape(-1), dt,
            sb, sw, gvel.reshape(-1), gspssp.reshape(-1))
    outs = (x_out, v_out, L_out, F_old, F_out, vol_out, rho0, write_L)
    lim = (min_mass > 0.0 or max_vel < np.inf, min_mass, max_vel)
    acc = (0, 0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0)
    for r in range(runs.shape[0]):
        if musl:                # one copy of the rows' code for the owned and the ghost runs
            owned = runs[r, 0] == 0
            acc = _g2p_rows(kind, act, musl, xpic, own if owned else ghost, runs[r, 1], runs[r, 2], owned, grid,
                            outs, lim, acc)
        elif runs[r, 0] == 0:   # USL: a ghost particle changes nothing (no remap), so no code for it
            acc = _g2p_rows(kind, act, musl, xpic, own, runs[r, 1], runs[r, 2], True, grid, outs, lim, acc)
    o, n_del, t0, t1, t2, t3, t4, t5, t6, t7 = acc
    tot[0] += t0
    tot[1] += t1
    tot[2] += t2
    tot[3] += t3
    tot[4] += t4
    tot[5] += t5
    tot[6] += t6
    tot[7] += t7
    return n_del


@njit(cache=True, fastmath=FM, inline="always")
def _grad(kind, act, model, px, lp, anchor, dx, node_low, gvel, L_out, write_L, dt, pmass, rho0, F_old,
          F_out, vol_out, K, mu, vel, s_out, e_out):
    """L_p = sum_i v_i (x) grad S_i(x_p) (stored if write_L), then F and V (_deform); with
    model = NEO_HOOKE also the stress (s_out), energy (e_out) and the wave speed, returned
    as (w0, w1, w2) (comp_neo_hook.point: the numbers of comp_neo_hook.kernel)."""
    sh0, sh1, sh2 = gvel.shape[:3]
    na, nb, nc = _counts(kind, act)
    ih = _inv_dx(dx)
    fv = gvel.reshape(-1)
    cK = K + 4.0 * mu / 3.0
    w0 = w1 = w2 = 0.0
    for p in range(px.shape[0]):
        L00 = L01 = L02 = L10 = L11 = L12 = L20 = L21 = L22 = 0.0
        for q in range(_corners(kind, act)):
            st = _stencil(kind, act, px, lp, p, anchor, ih, node_low, q)
            i, j, k = st[0], st[1], st[2]
            if not (i >= 0 and i + na <= sh0 and j >= 0 and j + nb <= sh1 and k >= 0 and k + nc <= sh2):
                raise IndexError("particle's nodes lie outside the patch node arrays")
            L00, L01, L02, L10, L11, L12, L20, L21, L22 = _over_nodes(
                _velocity_gradient_node, kind, act, (i, j, k), (sh0, sh1, sh2), st[3:], False,
                (L00, L01, L02, L10, L11, L12, L20, L21, L22), fv)
        if write_L:
            _store_L(L_out, p, L00, L01, L02, L10, L11, L12, L20, L21, L22)
        m = pmass[p]
        F00, F01, F02, F10, F11, F12, F20, F21, F22, V = _deform(act, p, p, dt, L00, L01, L02, L10, L11, L12, L20,
                                                                 L21, L22, F_old, F_out, vol_out, m, rho0)
        if model == NEO_HOOKE:
            e_out[p], cs = comp_neo_hook.point(K, mu, cK, F00, F01, F02, F10, F11, F12, F20, F21, F22, V, m, p, s_out)
            w0 = max(w0, cs + abs(vel[p, 0]))
            w1 = max(w1, cs + abs(vel[p, 1]))
            w2 = max(w2, cs + abs(vel[p, 2]))
    return w0, w1, w2


# ---- entry points, made by one factory per pass, keyed by (interpolator, active axes, update):
# the interpolator and the axis mask (and g2p's USL/MUSL) are closure constants, which numba
# compiles as literals, the same machine code as one hand-written function per combination; a
# new interpolator is a weight function in shape.py plus one line in INTERPOLATORS. Axisymmetry
# is the bit shape.AXI of the axis mask (x = r, y = z, z = theta): the same kernels, with the hoop
# terms of Uintah's axisymmetric MPM compiled in (the r-weighted GIMP weights, <S/r> in fint's r
# row and in L22, no theta momentum); without the bit not one instruction of them is compiled.
# p2g(owned, ghost, runs, has_fext, has_volume, anchor, dx, node_low, grid_mass, grid_momentum,
#     grid_volume, grid_fext, grid_fint)
#     owned/ghost: (px, pm, pv, pvol, ps, pf, lp) of the owned and ghost particles; has_fext
#     implies has_volume (V_i); each pair is its own compiled variant (_p2g_variant)
# g2p(musl, owned, ghost, runs, anchor, dx, node_low, grid_velocity_star, grid_acceleration, dt,
#     x_out, v_out, L_out, grid_momentum, totals, min_mass, max_vel, write_L, F_old, F_out,
#     vol_out, rho0, grid_velocity, grid_vel_spssp) -> number deleted
#     owned/ghost: (px, pv, pm, lp); kernels() gives it; the USL and MUSL entry points take the
#     arguments after musl
#     grid_velocity, grid_vel_spssp: XPIC(2)'s g.velocity and g.velSPSSP (never read by FLIP's entry)
# grad(px, lp, anchor, dx, node_low, grid_velocity, L_out, write_L, dt, particle_mass, rho0, F_old,
#      F_out, vol_out, model, bulk_modulus, shear_modulus, particle_velocity, stress_out,
#      energy_out) -> wave speed (3 floats; zeros unless model)

# fast_cpdi (Uintah's fastCpdiInterpolator) merges the nodes the corners share before the transfer:
# the same weights, one node list; here both visit the corners' linear stencils in turn
INTERPOLATORS = {"linear": LINEAR, "gimp": GIMP, "cpdi": CPDI, "fast_cpdi": CPDI}


@functools.lru_cache(maxsize=None)
def _p2g_variant(interpolator, axes, has_fext, has_volume, projection=False):
    """p2g without its two flags for one interpolator, mask and pair of flags, each compiled only
    where a run uses it (the three pairs in one entry cost three copies of the loop in every
    compile; the flags as run-time values made the pass 20-30 % slower). projection: Uintah's
    gradient-enhanced one, with the owned and ghost particles' velocity gradients after grid_fint."""
    kind = INTERPOLATORS[interpolator]

    if projection:
        @njit(cache=True, fastmath=FM)
        def p2g_projected(owned, ghost, runs, anchor, dx, node_low, grid_mass, grid_momentum, grid_volume, grid_fext,
                          grid_fint, grad_owned, grad_ghost):
            _p2g(kind, axes, owned, ghost, runs, has_fext, has_volume, anchor, dx, node_low, grid_mass, grid_momentum,
                 grid_volume, grid_fext, grid_fint, True, grad_owned, grad_ghost)
        return p2g_projected

    @njit(cache=True, fastmath=FM)
    def p2g(owned, ghost, runs, anchor, dx, node_low, grid_mass, grid_momentum, grid_volume, grid_fext, grid_fint):
        no_grad = np.empty((0, 3, 3))
        _p2g(kind, axes, owned, ghost, runs, has_fext, has_volume, anchor, dx, node_low, grid_mass, grid_momentum,
             grid_volume, grid_fext, grid_fint, False, no_grad, no_grad)
    return p2g


@functools.lru_cache(maxsize=None)
def _p2g_entry(interpolator, axes, projection=False):
    """p2g (signature above) for one interpolator and active-axis mask; with projection (Uintah's
    UseGradientEnhancedVelocityProjection) it takes the owned and ghost particles' velocity
    gradients after grid_fint (and always computes g.volume)."""
    def p2g(owned, ghost, runs, has_fext, has_volume, *grid):
        has_fext = bool(has_fext)
        has_volume = projection or has_fext or bool(has_volume)
        _p2g_variant(interpolator, axes, has_fext, has_volume, projection)(owned, ghost, runs, *grid)
    return p2g


@functools.lru_cache(maxsize=None)
def _g2p_entry(interpolator, axes, musl, xpic):
    """g2p after its musl flag (signature above) for one interpolator, mask, update (USL or MUSL)
    and particle velocity update (FLIP or XPIC(2)): each is compiled only where a run uses it
    (USL's has no remap and no code for ghost particles, MUSL's no L or F; with musl a run-time
    flag one entry held both: 40 CPU s of disks_50x50's cold compile). FLIP's never reads
    grid_velocity or grid_vel_spssp."""
    kind = INTERPOLATORS[interpolator]

    @njit(cache=True, fastmath=FM)
    def g2p(owned, ghost, runs, anchor, dx, node_low, grid_velocity_star, grid_acceleration, dt, x_out, v_out,
            L_out, grid_momentum, totals, min_mass, max_vel, write_L, F_old, F_out, vol_out, rho0, grid_velocity,
            grid_vel_spssp):
        return _g2p(kind, axes, musl, xpic, owned, ghost, runs, anchor, dx, node_low, grid_velocity_star,
                    grid_acceleration, dt, x_out, v_out, L_out, grid_momentum, totals, min_mass, max_vel, write_L,
                    F_old, F_out, vol_out, rho0, grid_velocity, grid_vel_spssp)
    return g2p


@njit(cache=True, fastmath=FM, inline="always")
def _spssp(kind, act, own, ghost, runs, anchor, dx, node_low, gvel, gout):
    """gout_i += sum_p S_ip m_p v+_p, v+_p = sum_j S_jp v_j (gvel): the owned and ghost
    sources (x, m, lp), run by run in their merged ID order (as p2g), so each node adds its
    shares in particle-ID order; shares beyond the node arrays are dropped."""
    sh0, sh1, sh2 = gvel.shape[:3]
    na, nb, nc = _counts(kind, act)
    ih = _inv_dx(dx)
    fg = gvel.reshape(-1)
    fo = gout.reshape(-1)
    nq = _corners(kind, act)
    for r in range(runs.shape[0]):
        px, pmass, lp = own if runs[r, 0] == 0 else ghost
        for p in range(runs[r, 1], runs[r, 2]):
            s0 = s1 = s2 = 0.0
            for q in range(nq):
                st = _stencil(kind, act, px, lp, p, anchor, ih, node_low, q)
                i, j, k = st[0], st[1], st[2]
                if not (i >= 0 and i + na <= sh0 and j >= 0 and j + nb <= sh1 and k >= 0 and k + nc <= sh2):
                    raise IndexError("particle's nodes lie outside the patch node arrays")
                s0, s1, s2 = _over_nodes(_gather_node, kind, act, (i, j, k), (sh0, sh1, sh2), st[3:], False,
                                         (s0, s1, s2), fg)
            m = pmass[p]
            mv0 = s0 * m
            mv1 = s1 * m
            mv2 = s2 * m
            for q in range(nq):
                st = _stencil(kind, act, px, lp, p, anchor, ih, node_low, q)
                _over_nodes(_scatter_node, kind, act, (st[0], st[1], st[2]), (sh0, sh1, sh2), st[3:], False, 0.0,
                            (fo, mv0, mv1, mv2))


@functools.lru_cache(maxsize=None)
def _spssp_entry(interpolator, axes):
    """XPIC(2)'s first extra pass, (S+ S+ m v)_i (signature above), for one interpolator and mask."""
    kind = INTERPOLATORS[interpolator]

    @njit(cache=True, fastmath=FM)
    def spssp(owned, ghost, runs, anchor, dx, node_low, grid_velocity, grid_out):
        _spssp(kind, axes, owned, ghost, runs, anchor, dx, node_low, grid_velocity, grid_out)
    return spssp


@functools.lru_cache(maxsize=None)
def _grad_entry(interpolator, axes):
    """grad (signature above) for one interpolator and active-axis mask; the fused model is a
    run-time value (its branch per particle measured no slower than two compiled copies of the
    loop, which doubled the compile)."""
    kind = INTERPOLATORS[interpolator]

    @njit(cache=True, fastmath=FM)
    def grad(px, lp, anchor, dx, node_low, grid_velocity, L_out, write_L, dt, particle_mass, rho0, F_old, F_out,
             vol_out, model, bulk_modulus, shear_modulus, particle_velocity, stress_out, energy_out):
        return _grad(kind, axes, model, px, lp, anchor, dx, node_low, grid_velocity, L_out, write_L, dt,
                     particle_mass, rho0, F_old, F_out, vol_out, bulk_modulus, shear_modulus, particle_velocity,
                     stress_out, energy_out)
    return grad


def one_run(n):
    """The runs of n owned particles and no ghosts."""
    return np.array([[0, 0, n]], np.int64)


def kernels(interpolator, axes, projection=False):
    """(p2g, g2p, grad) for `interpolator` on the active-axis mask `axes`, with shape.AXI for an
    axisymmetric run (signatures above). g2p(musl, *args, xpic=(grid_velocity, grid_vel_spssp))
    is XPIC(2)'s update (FLIP's without xpic). projection: p2g is the gradient-enhanced one
    (_p2g_entry)."""
    def g2p(musl_flag, *args, xpic=None):
        if xpic is None:            # FLIP: the stand-ins have g.velocity_star's type (no new specialisation)
            return _g2p_entry(interpolator, axes, musl_flag, False)(*args, args[6], args[6])
        return _g2p_entry(interpolator, axes, musl_flag, True)(*args, *xpic)
    return _p2g_entry(interpolator, axes, projection), g2p, _grad_entry(interpolator, axes)


def xpic_kernel(interpolator, axes):
    """spssp(owned, ghost, runs, anchor, dx, node_low, grid_velocity, grid_out) for XPIC(2):
    owned/ghost (px, pm, lp); grid_out += (S+ S+ m v)_i (then divided by g.mass: g.velSPSSP)."""
    return _spssp_entry(interpolator, axes)


def merged_p2g(p2g):
    """p2g on one array per particle variable (all particles in one source):
    f(px, pm, pv, pvol, ps, pf, has_f, lp, anchor, dx, node_low, gm, gmom, gvol, gfe, gfi)."""
    def f(px, pm, pv, pvol, ps, pf, has_f, lp, anchor, dx, node_low, gm, gmom, gvol, gfe, gfi):
        part = (px, pm, pv, pvol, ps, pf, lp)
        p2g(part, part, one_run(len(px)), has_f, True, anchor, dx, node_low, gm, gmom, gvol, gfe, gfi)
    return f


@njit(cache=True, fastmath=FM, inline="always")
def _mass_gradient_node(acc, args, act, x, y, z, n, wa, wb, wc, ga, gb, gc, ha):
    """mass_gradient at one node: += m grad S."""
    fo, m = args
    f3 = 3 * n
    fo[f3] += m * ga * wb * wc
    fo[f3 + 1] += m * wa * gb * wc
    fo[f3 + 2] += m * wa * wb * gc
    return acc


@njit(cache=True, fastmath=FM)
def mass_gradient(kind, act, px, pm, lp, anchor, dx, node_low, out):
    """out_i += sum_p m_p grad S_i(x_p) (contact normals; kind/act at run time), shares
    beyond the node array dropped."""
    ih = _inv_dx(dx)
    fo = out.reshape(-1)
    for p, q in _visits(kind, act, px.shape[0]):
        st = _stencil(kind, act, px, lp, p, anchor, ih, node_low, q)
        _over_nodes(_mass_gradient_node, kind, act, (st[0], st[1], st[2]), out.shape[:3], st[3:], True, 0.0,
                    (fo, pm[p]))
