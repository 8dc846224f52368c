"""Numba kernels of the ICE Eulerian phase (paper 000 sec. 3.3 step 12): advection.

Mass is fluxed through each face with the face velocity u*: the flux volume is the
slab u* dt A next to the face in the donor cell. First order takes the donor cell's
value; second order adds a limited slope evaluated at the slab's centroid (a distance
(1 - |u* dt/dx|) dx/2 from the donor's centre). Two limiters (<advection limiter>):
VAN_LEER (the default), van Leer's slope along the face normal; EXTREMA
("BarthJespersen"), Uintah's SecondOrderAdvector (VanderHeyden and Kashiwa, JCP 146,
1998): central gradients in every direction scaled by one factor per cell so that the
reconstruction at the cell's vertices stays within its face neighbours' extrema, the
slab centroid also offset across the normal by what the donor sends out of its other
faces, and with Uintah's compatible vertex weights m/m_vertex (equal to sus's output
to round-off: tests/ice/test_advection_limiters.py).
Momentum, internal energy and material volume are fluxed *compatibly*: the mass flux
times the reconstructed specific value (velocity, e, v), so a uniform velocity or
temperature stays exactly uniform and every flux leaves one cell and enters the
other (mass, momentum and energy are conserved to round-off). With dissipationHeating
(the default for ICE alone) E = m (e + |u|^2/2) is advected too and e = E/m - |u|^2/2:
the kinetic energy that the limited fluxes of mass and momentum destroy becomes heat.

One kernel call advects one material of one patch: the specific values q = Q/m are
computed once per cell into a scratch array (not three times per face), then each
direction's faces are swept in turn; the order of the sums per cell (x faces, then
y, then z, each in increasing index) is what makes the result independent of the
patch layout.
"""
from __future__ import annotations

import numpy as np
from numba import njit

from .eos import IDEAL_GAS, eos_cold_energy
from .specific_heat import cv_at

NQ = 7  # mass, velocity x/y/z, specific internal energy, specific volume, specific total energy
VAN_LEER, EXTREMA = 0, 1    # second-order limiters: slope along the face normal / Uintah's SecondOrderAdvector
SMALL_NUM = 1e-100          # Uintah's d_SMALL_NUM in the extrema limiter's ratios


@njit(cache=True, error_model="numpy")
def _van_leer(a, b):
    """Limited slope 2ab/(a+b) where a, b have the same sign, else 0 (branch-free: vectorizes)."""
    p = a * b
    return 2.0 * p / (a + b) if p > 0.0 else 0.0


@njit(cache=True, error_model="numpy")
def _extrema_limit(qc, qmax, qmin, vmax, vmin):
    """Uintah's gradient limiter: the largest factor in [0, 1] that keeps the vertex values
    [vmin, vmax] of the reconstruction within the neighbours' extrema [qmin, qmax]."""
    lim_max = max(0.0, (qmax - qc + SMALL_NUM) / (vmax - qc + SMALL_NUM))
    lim_min = max(0.0, (qmin - qc + SMALL_NUM) / (vmin - qc + SMALL_NUM))
    return min(1.0, lim_max, lim_min)


@njit(cache=True, error_model="numpy")
def limited_gradients(q, dims, dxs, compatible, grad):
    """grad[t, c] = the limited gradient of q[c] along view axis t (Uintah's SecondOrderBase:
    gradQ, Q_vertex, limitedGradient): central differences in every active direction, all
    scaled by one factor per cell and quantity so that the linear reconstruction at the cell's
    vertices stays within the extrema of its face neighbours. compatible (Uintah's
    useCompatibleFluxes): the vertex value of a specific quantity q = Q/m is the one the
    compatible flux carries, q + (grad q . r_v) m / m_v, m_v the mass at the vertex from the
    (already limited) mass gradient; mass (c = 0) comes first. Cells without both neighbours
    in an active direction get no gradient (first order there). Not compatible: the limited
    gradient is that of the cell's total Q = m q (Uintah's non-compatible advectQ)."""
    nq = q.shape[0]
    n0, n1, n2 = q.shape[1], q.shape[2], q.shape[3]
    h0, h1, h2 = 0.5 * dxs[0], 0.5 * dxs[1], 0.5 * dxs[2]
    for t in range(3):
        for c in range(nq):
            grad[t, c] = 0.0
    active = (1 if dims[0] else 0) + (2 if dims[1] else 0) + (4 if dims[2] else 0)
    i0, i1 = (1, n0 - 1) if dims[0] else (0, n0)
    j0, j1 = (1, n1 - 1) if dims[1] else (0, n1)
    k0, k1 = (1, n2 - 1) if dims[2] else (0, n2)
    for i in range(i0, i1):
        for j in range(j0, j1):
            for k in range(k0, k1):
                m = q[0, i, j, k]
                for c in range(nq):
                    total = c > 0 and not compatible          # reconstruct m q, not q
                    qc = q[c, i, j, k] * m if total else q[c, i, j, k]
                    qmax, qmin = qc, qc
                    g0 = g1 = g2 = 0.0
                    if dims[0]:
                        a, b = q[c, i - 1, j, k], q[c, i + 1, j, k]
                        if total:
                            a, b = a * q[0, i - 1, j, k], b * q[0, i + 1, j, k]
                        g0 = (b - a) / (2.0 * dxs[0])
                        qmax, qmin = max(qmax, a, b), min(qmin, a, b)
                    if dims[1]:
                        a, b = q[c, i, j - 1, k], q[c, i, j + 1, k]
                        if total:
                            a, b = a * q[0, i, j - 1, k], b * q[0, i, j + 1, k]
                        g1 = (b - a) / (2.0 * dxs[1])
                        qmax, qmin = max(qmax, a, b), min(qmin, a, b)
                    if dims[2]:
                        a, b = q[c, i, j, k - 1], q[c, i, j, k + 1]
                        if total:
                            a, b = a * q[0, i, j, k - 1], b * q[0, i, j, k + 1]
                        g2 = (b - a) / (2.0 * dxs[2])
                        qmax, qmin = max(qmax, a, b), min(qmin, a, b)
                    if c == 0 or not compatible:
                        reach = abs(g0) * h0 + abs(g1) * h1 + abs(g2) * h2
                        vmax, vmin = qc + reach, qc - reach
                    else:
                        m0, m1, m2 = grad[0, 0, i, j, k] * h0, grad[1, 0, i, j, k] * h1, grad[2, 0, i, j, k] * h2
                        vmax, vmin = -np.inf, np.inf
                        for v in range(8):          # the vertices (+-h0, +-h1, +-h2)
                            if v & ~active:         # a collapsed direction: the same vertex again
                                continue
                            s0 = 1.0 if v & 1 else -1.0
                            s1 = 1.0 if v & 2 else -1.0
                            s2 = 1.0 if v & 4 else -1.0
                            dq = s0 * g0 * h0 + s1 * g1 * h1 + s2 * g2 * h2
                            val = qc + dq * m / (m + s0 * m0 + s1 * m1 + s2 * m2)
                            vmax, vmin = max(vmax, val), min(vmin, val)
                    lim = _extrema_limit(qc, qmax, qmin, vmax, vmin)
                    grad[0, c, i, j, k] = g0 * lim
                    grad[1, c, i, j, k] = g1 * lim
                    grad[2, c, i, j, k] = g2 * lim


@njit(cache=True, error_model="numpy")
def _row_values_gradient(q, grad, d, u, l0, l1, lb, r0, r1, rb, dt, dx, compatible, buf):
    """Face values of a row of faces between the cells L = (l0, l1, lb + kk) and R = (r0, r1, rb + kk)
    from the donor's limited gradient at the outflow slab's centroid, (dx - |u| dt)/2 from its centre
    toward the face (Uintah's qAverageFlux). compatible: a specific quantity's value is
    q + (grad q . r) m / m_slab, so that the flux m_slab |u| dt/dx times it is Uintah's
    (m_slab q + m grad q . r) |u| dt/dx; not compatible, grad is that of Q = m q and the value
    is the slab's (Q + grad Q . r) / m_slab."""
    nq = q.shape[0]
    nk = u.shape[0]
    for c in range(nq):
        qL, qR = q[c, l0, l1, lb:lb + nk], q[c, r0, r1, rb:rb + nk]
        gL, gR = grad[d, c, l0, l1, lb:lb + nk], grad[d, c, r0, r1, rb:rb + nk]
        f = buf[c]
        if c == 0:
            for kk in range(nk):
                r = 0.5 * (dx - abs(u[kk]) * dt)
                f[kk] = qL[kk] + r * gL[kk] if u[kk] > 0.0 else qR[kk] - r * gR[kk]
        elif not compatible:
            mL, mR = q[0, l0, l1, lb:lb + nk], q[0, r0, r1, rb:rb + nk]
            ms = buf[0]
            for kk in range(nk):
                r = 0.5 * (dx - abs(u[kk]) * dt)
                slab = qL[kk] * mL[kk] + r * gL[kk] if u[kk] > 0.0 else qR[kk] * mR[kk] - r * gR[kk]
                f[kk] = slab / ms[kk] if ms[kk] != 0.0 else 0.0
        else:
            mL, mR = q[0, l0, l1, lb:lb + nk], q[0, r0, r1, rb:rb + nk]
            ms = buf[0]
            for kk in range(nk):
                r = 0.5 * (dx - abs(u[kk]) * dt)
                w = (mL[kk] if u[kk] > 0.0 else mR[kk]) / ms[kk] if ms[kk] != 0.0 else 0.0
                f[kk] = qL[kk] + w * r * gL[kk] if u[kk] > 0.0 else qR[kk] - w * r * gR[kk]


@njit(cache=True, error_model="numpy")
def _slab_offsets(ux, uy, uz, shs, dims, dt, rc):
    """rc[t] of every stored cell: the offset along view axis t of the centroid of the slabs it
    sends through its faces normal to the other axes, half of what it sends out of its low
    t-face minus what it sends out of its high one (Uintah's inFluxOutFluxVolume:
    r_y = (delY_bottom - delY_top) / 2); 0 where a face is not stored (never a donor there)."""
    n0, n1, n2 = rc.shape[1], rc.shape[2], rc.shape[3]
    for t in range(3):
        rc[t] = 0.0
        if not dims[t]:
            continue
        e0, e1, e2 = (1, 0, 0) if t == 0 else ((0, 1, 0) if t == 1 else (0, 0, 1))
        uf = ux if t == 0 else (uy if t == 1 else uz)
        f0, f1, f2 = uf.shape
        for i in range(n0):
            a = i - shs[t, 0]
            if a < 0 or a + e0 >= f0:
                continue
            for j in range(n1):
                b = j - shs[t, 1]
                if b < 0 or b + e1 >= f1:
                    continue
                c0 = max(0, shs[t, 2])
                c1 = min(n2, f2 - e2 + shs[t, 2])
                lo, hi, row = uf[a, b], uf[a + e0, b + e1], rc[t, i, j]
                for k in range(c0, c1):
                    c = k - shs[t, 2]
                    row[k] = 0.5 * (max(0.0, -lo[c] * dt) - max(0.0, hi[c + e2] * dt))


@njit(cache=True, error_model="numpy")
def _row_values_gradient_md(q, grad, rc, d, u, l0, l1, lb, r0, r1, rb, dt, dx, compatible, buf):
    """Multi-dimensional _row_values_gradient: the slab centroid is also offset across the face
    normal by the donor's rc (Uintah's qAverageFlux with d_r_out_x/y/z)."""
    nq = q.shape[0]
    nk = u.shape[0]
    mL, mR = q[0, l0, l1, lb:lb + nk], q[0, r0, r1, rb:rb + nk]
    ms = buf[0]
    for c in range(nq):
        qL, qR = q[c, l0, l1, lb:lb + nk], q[c, r0, r1, rb:rb + nk]
        f = buf[c]
        for kk in range(nk):                    # the normal offset: toward the face
            r = 0.5 * (dx - abs(u[kk]) * dt)
            f[kk] = r * grad[d, c, l0, l1, lb + kk] if u[kk] > 0.0 else -r * grad[d, c, r0, r1, rb + kk]
        for t in range(3):                      # the offsets across it
            if t == d:
                continue
            gL, gR = grad[t, c, l0, l1, lb:lb + nk], grad[t, c, r0, r1, rb:rb + nk]
            oL, oR = rc[t, l0, l1, lb:lb + nk], rc[t, r0, r1, rb:rb + nk]
            for kk in range(nk):
                f[kk] += gL[kk] * oL[kk] if u[kk] > 0.0 else gR[kk] * oR[kk]
        if c == 0:
            for kk in range(nk):
                f[kk] += qL[kk] if u[kk] > 0.0 else qR[kk]
        elif compatible:
            for kk in range(nk):
                m = mL[kk] if u[kk] > 0.0 else mR[kk]
                f[kk] = ((qL[kk] if u[kk] > 0.0 else qR[kk]) + f[kk] * m / ms[kk]) if ms[kk] != 0.0 else 0.0
        else:
            for kk in range(nk):
                qm = qL[kk] * mL[kk] if u[kk] > 0.0 else qR[kk] * mR[kk]
                f[kk] = (qm + f[kk]) / ms[kk] if ms[kk] != 0.0 else 0.0


@njit(cache=True, error_model="numpy")
def _start(mass, mom, eng, volm, tot, scal, with_e, heating, q, acc, lo, hi):
    """q = (m, (mu)/m, (me)/m, (mv)/m, E/m, then the transported scalars' (m f)/m) in every stored
    cell (halo corners outside the domain may hold garbage: never read); acc = the Lagrangian
    totals in the cells [lo, hi). heating: E = m e + |m u|^2 / (2 m) from the others (tot
    unused). scal: (ns, *mass.shape) Lagrangian totals m f of passive scalars (ns may be 0),
    stored after the others in q (from index nq - ns)."""
    nq = q.shape[0]
    base = nq - scal.shape[0]
    n0, n1, n2 = mass.shape
    for i in range(n0):
        for j in range(n1):
            for k in range(n2):
                m = mass[i, j, k]
                q[0, i, j, k] = m
                q[1, i, j, k] = mom[i, j, k, 0] / m
                q[2, i, j, k] = mom[i, j, k, 1] / m
                q[3, i, j, k] = mom[i, j, k, 2] / m
                q[4, i, j, k] = eng[i, j, k] / m
                q[5, i, j, k] = volm[i, j, k] / m
                if heating:
                    q[6, i, j, k] = q[4, i, j, k] + 0.5 * (q[1, i, j, k] ** 2 + q[2, i, j, k] ** 2 +
                                                           q[3, i, j, k] ** 2)
                elif with_e:
                    q[6, i, j, k] = tot[i, j, k] / m
                for s in range(base, nq):
                    q[s, i, j, k] = scal[s - base, i, j, k] / m
    n = hi[2] - lo[2]
    k0 = lo[2]
    for i in range(lo[0], hi[0]):
        for j in range(lo[1], hi[1]):
            for c in range(nq):
                a = acc[c, i, j, k0:k0 + n]
                if c >= base:
                    src = scal[c - base, i, j, k0:k0 + n]
                else:
                    src = q[c, i, j, k0:k0 + n] if c == 0 else (
                        eng[i, j, k0:k0 + n] if c == 4 else (volm[i, j, k0:k0 + n] if c == 5 else tot[i, j, k0:k0 + n]))
                if 1 <= c <= 3:
                    mc = mom[i, j, k0:k0 + n, c - 1]
                    for k in range(n):
                        a[k] = mc[k]
                elif c == 6 and heating:
                    qm, qe = q[0, i, j, k0:k0 + n], q[6, i, j, k0:k0 + n]
                    for k in range(n):
                        a[k] = qm[k] * qe[k]
                else:
                    for k in range(n):
                        a[k] = src[k]


@njit(cache=True, error_model="numpy")
def _sweep(q, uf, d, sh, flo, fhi, lo, hi, dt, dxs, dims, comp, second, transverse, acc, buf, sl):
    """Add the fluxes through the d-faces [flo, fhi) to the cells [lo, hi).

    Arrays are views whose last axis is the longest unit-stride one: each row of faces
    along it is done in a few simple loops (face values of all quantities, fluxes,
    sums into both cells) that the compiler vectorizes; both candidate donors' slopes
    are computed and the upwind one selected, which is cheaper than a branch per face.
    `transverse` (second order only): the face value is also moved half a step back
    along the donor cell's velocity in the other directions, q -= dt/2 v_t dq/dx_t
    (limited slopes), which supplies the cross terms u v dt d2q/dxdy that a purely
    normal reconstruction lacks; without them oblique flow is first order in time.
    `comp[t]`: the velocity component along view axis t.
    """
    n = q.shape[1 + d]
    e0, e1, e2 = (1, 0, 0) if d == 0 else ((0, 1, 0) if d == 1 else (0, 0, 1))
    dx = dxs[d]
    k0, k1 = flo[2], fhi[2]
    base = k0 + sh[2]                           # the R cell of the row's first face
    for i in range(flo[0], fhi[0]):
        for j in range(flo[1], fhi[1]):
            r0, r1 = i + sh[0], j + sh[1]
            u = uf[i, j, k0:k1]
            if d == 2:
                _row_values_inner(q, u, r0, r1, base, dt, dx, second, sl, buf)
            else:
                l0, l1 = r0 - e0, r1 - e1
                rd = r0 * e0 + r1 * e1              # R's index along d; L's is rd - 1
                a = max(rd - 2, 0)                  # L's lower neighbour (clamped: unused then)
                b = min(rd + 1, n - 1)              # R's upper neighbour
                _row_values_outer(q, u, l0, l1, r0, r1, l0 - e0 * (rd - 1 - a), l1 - e1 * (rd - 1 - a),
                                  r0 + e0 * (b - rd), r1 + e1 * (b - rd), rd >= 2, rd + 1 < n,
                                  base, dt, dx, second, buf)
            if second and transverse:
                _transverse(q, uf, d, sh, i, j, k0, k1, dt, dxs, dims, comp, buf)
            _add_fluxes(u, d, r0, r1, base, dt, dx, lo, hi, acc, buf)


@njit(cache=True, error_model="numpy")
def _sweep_extrema(q, grad, rc, uf, d, sh, flo, fhi, lo, hi, dt, dxs, dims, compatible, acc, buf):
    """_sweep with Uintah's limited gradients (limited_gradients) at the slab centroids: in 1D
    along the face normal, in 2D/3D with the slab centroid's offset across it (rc, _slab_offsets)."""
    e0, e1, e2 = (1, 0, 0) if d == 0 else ((0, 1, 0) if d == 1 else (0, 0, 1))
    dx = dxs[d]
    ndims = int(dims[0]) + int(dims[1]) + int(dims[2])
    k0, k1 = flo[2], fhi[2]
    base = k0 + sh[2]
    for i in range(flo[0], fhi[0]):
        for j in range(flo[1], fhi[1]):
            r0, r1 = i + sh[0], j + sh[1]
            u = uf[i, j, k0:k1]
            if ndims > 1:
                _row_values_gradient_md(q, grad, rc, d, u, r0 - e0, r1 - e1, base - e2, r0, r1, base, dt, dx,
                                        compatible, buf)
            else:
                _row_values_gradient(q, grad, d, u, r0 - e0, r1 - e1, base - e2, r0, r1, base, dt, dx, compatible, buf)
            _add_fluxes(u, d, r0, r1, base, dt, dx, lo, hi, acc, buf)


@njit(cache=True, error_model="numpy")
def _add_fluxes(u, d, r0, r1, base, dt, dx, lo, hi, acc, buf):
    """Turn a row's face values (buf) into fluxes, mass flux m_face |u| dt/dx times each face value,
    and add them to both cells of every face: each cell + its lower face - its upper face."""
    nq = buf.shape[0]
    nk = u.shape[0]
    e0, e1 = (1, 0) if d == 0 else ((0, 1) if d == 1 else (0, 0))
    fm = buf[0]
    for kk in range(nk):                # mass flux m_face |u| dt / dx, signed L -> R
        s = 1.0 if u[kk] > 0.0 else -1.0
        fm[kk] = abs(u[kk]) * dt / dx * s * fm[kk] if u[kk] != 0.0 else 0.0
    for c in range(1, nq):              # the other fluxes: mass flux times face value
        f = buf[c]
        for kk in range(nk):
            f[kk] = fm[kk] * f[kk] if u[kk] != 0.0 else 0.0
    if d == 2:
        c0, c1 = max(lo[2], base), min(hi[2], base + nk - 1)
        for c in range(nq):
            row = acc[c, r0, r1, c0:c1]
            f = buf[c, c0 - base:]
            for kk in range(c1 - c0):
                row[kk] = (row[kk] + f[kk]) - f[kk + 1]
    else:
        if r0 * e0 + r1 * e1 - 1 >= lo[d]:
            for c in range(nq):
                row = acc[c, r0 - e0, r1 - e1, base:base + nk]
                f = buf[c]
                for kk in range(nk):
                    row[kk] -= f[kk]
        if r0 * e0 + r1 * e1 < hi[d]:
            for c in range(nq):
                row = acc[c, r0, r1, base:base + nk]
                f = buf[c]
                for kk in range(nk):
                    row[kk] += f[kk]


@njit(cache=True, error_model="numpy")
def _row_values_inner(q, u, r0, r1, base, dt, dx, second, sl, buf):
    """Face values of a row of faces normal to the last axis (face kk between cells base+kk-1
    and base+kk): limited slopes once per cell, then the upwind pick."""
    nq = q.shape[0]
    n = q.shape[3]
    nk = u.shape[0]
    for c in range(nq):
        row = q[c, r0, r1]
        f = buf[c]
        if second:
            sl[0] = 0.0
            sl[n - 1] = 0.0
            for k in range(n - 2):
                qk = row[k + 1]
                sl[k + 1] = _van_leer(qk - row[k], row[k + 2] - qk)
            qb = row[base - 1:]
            sb = sl[base - 1:]
            for kk in range(nk):
                w = 0.5 * (1.0 - abs(u[kk]) * dt / dx)
                f[kk] = qb[kk] + w * sb[kk] if u[kk] > 0.0 else qb[kk + 1] + (-w) * sb[kk + 1]
        else:
            qb = row[base - 1:]
            for kk in range(nk):
                f[kk] = qb[kk] if u[kk] > 0.0 else qb[kk + 1]


@njit(cache=True, error_model="numpy")
def _row_values_outer(q, u, l0, l1, r0, r1, a0, a1, b0, b1, okL, okR, base, dt, dx, second, buf):
    """Face values of a row of faces normal to an outer axis: L = (l0, l1, .), R = (r0, r1, .), their
    outer neighbours A, B; okL/okR: whether L/R has both neighbours (else no slope)."""
    nq = q.shape[0]
    nk = u.shape[0]
    for c in range(nq):
        qL = q[c, l0, l1, base:base + nk]
        qR = q[c, r0, r1, base:base + nk]
        f = buf[c]
        if second:
            qA = q[c, a0, a1, base:base + nk]
            qB = q[c, b0, b1, base:base + nk]
            for kk in range(nk):
                w = 0.5 * (1.0 - abs(u[kk]) * dt / dx)
                sL = _van_leer(qL[kk] - qA[kk], qR[kk] - qL[kk]) if okL else 0.0
                sR = _van_leer(qR[kk] - qL[kk], qB[kk] - qR[kk]) if okR else 0.0
                f[kk] = qL[kk] + w * sL if u[kk] > 0.0 else qR[kk] + (-w) * sR
        else:
            for kk in range(nk):
                f[kk] = qL[kk] if u[kk] > 0.0 else qR[kk]


@njit(cache=True, error_model="numpy")
def _transverse(q, uf, d, sh, i, j, k0, k1, dt, dxs, dims, comp, buf):
    """Add the transverse correction -dt/2 v_t (limited dq/dx_t) of the donor cell to a row of face values."""
    nq = q.shape[0]
    e0, e1, e2 = (1, 0, 0) if d == 0 else ((0, 1, 0) if d == 1 else (0, 0, 1))
    for k in range(k0, k1):
        u = uf[i, j, k]
        if u == 0.0:
            continue
        r0, r1, r2 = i + sh[0], j + sh[1], k + sh[2]
        if u > 0.0:
            d0, d1, d2 = r0 - e0, r1 - e1, r2 - e2
        else:
            d0, d1, d2 = r0, r1, r2
        for t in range(3):
            if not dims[t] or t == d:
                continue
            f0, f1, f2 = (1, 0, 0) if t == 0 else ((0, 1, 0) if t == 1 else (0, 0, 1))
            tn = d0 * f0 + d1 * f1 + d2 * f2
            if tn >= 1 and tn + 1 < q.shape[1 + t]:
                wt = -0.5 * dt * q[1 + comp[t], d0, d1, d2] / dxs[t]
                for c in range(nq):
                    qd = q[c, d0, d1, d2]
                    buf[c, k - k0] += wt * _van_leer(qd - q[c, d0 - f0, d1 - f1, d2 - f2],
                                                q[c, d0 + f0, d1 + f1, d2 + f2] - qd)


@njit(cache=True, error_model="numpy")
def _open_transfers(q, ex, ey, ez, press, with_e, shs, flo, fhi, lo, hi, dims, acc):
    """MPMICE's open-face transfers (components/mpmice/kernels.open_face_transfers): across
    each face with e != 0 the fraction |e| of the donor's Lagrangian totals (q: m and the
    specific values) moves to the other cell, L -> R where e > 0: a first-order flux on
    top of the face velocity's, for the fluid a solid advancing through its cell displaces
    into a more open neighbour. The energy moved is the parcel's enthalpy, its internal
    (and total, with_e) energy plus the flow work p v (press: the donor's pressure): the
    pressure equation does not see this volume cross, so the next equilibration, which
    keeps each material's temperature, fits it into the receiver and the donor's remaining
    fluid into its cell; with the work the two are adiabatic to first order, without it the
    donor's fluid expands at constant temperature (an entropy gain). Nothing where e is a
    1-element dummy (ICE alone)."""
    if ex.size == 1 and ey.size == 1 and ez.size == 1:
        return
    nq = q.shape[0]
    for d in range(3):
        if not dims[d]:
            continue
        e = ex if d == 0 else (ey if d == 1 else ez)
        if e.size == 1:
            continue
        e0, e1, e2 = (1, 0, 0) if d == 0 else ((0, 1, 0) if d == 1 else (0, 0, 1))
        sh = shs[d]
        for i in range(flo[d][0], fhi[d][0]):
            for j in range(flo[d][1], fhi[d][1]):
                for k in range(flo[d][2], fhi[d][2]):
                    f = e[i, j, k]
                    if f == 0.0:
                        continue
                    r0, r1, r2 = i + sh[0], j + sh[1], k + sh[2]
                    l0, l1, l2 = r0 - e0, r1 - e1, r2 - e2
                    if f > 0.0:
                        a0, a1, a2, b0, b1, b2 = l0, l1, l2, r0, r1, r2
                    else:
                        a0, a1, a2, b0, b1, b2 = r0, r1, r2, l0, l1, l2
                    m = q[0, a0, a1, a2] * abs(f)
                    a_in = lo[0] <= a0 < hi[0] and lo[1] <= a1 < hi[1] and lo[2] <= a2 < hi[2]
                    b_in = lo[0] <= b0 < hi[0] and lo[1] <= b1 < hi[1] and lo[2] <= b2 < hi[2]
                    work = m * press[a0, a1, a2] * q[5, a0, a1, a2]
                    for c in range(nq):
                        x = m if c == 0 else m * q[c, a0, a1, a2]
                        if c == 4 or (c == 6 and with_e):
                            x += work
                        if a_in:
                            acc[c, a0, a1, a2] -= x
                        if b_in:
                            acc[c, b0, b1, b2] += x


@njit(cache=True, error_model="numpy")
def advect(mass, mom, eng, volm, tot, scal, with_e, heating, ux, uy, uz, ex, ey, ez, press, shs, flo, fhi, lo, hi, dt,
           dxs, dims, comp, second, transverse, q, acc, buf, sl, vol, cv, rho_o, vel_o, temp_o, spv_o, tot_o, scal_o):
    """Advect one material's Lagrangian totals (m, m u, m e, m v, E) over one step into the
    cells [lo, hi) and return the new primitives rho = m/V, u = (mu)/m, T = (me)/(m cv),
    v = (mv)/m (and the advected E in tot_o). heating (dissipationHeating, with with_e):
    E = m e + |m u|^2/(2 m) is made here and T = (E/m - |u|^2/2)/cv where that is positive.
    scal: (ns, ...) Lagrangian totals m f of transported scalars (Uintah's models' q_L_CC),
    fluxed as the specific values above; scal_o gets f = (m f)_adv / m_adv.

    All arrays are views with the collapsed axes first (a 2D run has a unit first axis),
    `comp` maps view axes to velocity components; shs, flo, fhi: (3, 3) per view axis.
    q, acc: scratch (nq, *mass.shape) with nq = 7 with E, else 6, plus ns; buf: (nq, row length).
    ex, ey, ez: MPMICE's open-face transfers (_open_transfers), or 1-element dummies; press: the
    cells' pressure for the transfers' flow work (a dummy with them).
    """
    _start(mass, mom, eng, volm, tot, scal, with_e, heating, q, acc, lo, hi)
    for d in range(3):                  # d a run-time value: one compiled _sweep, not one per axis
        if dims[d]:
            uf = ux if d == 0 else (uy if d == 1 else uz)
            _sweep(q, uf, d, shs[d], flo[d], fhi[d], lo, hi, dt, dxs, dims, comp, second, transverse, acc, buf, sl)
    _open_transfers(q, ex, ey, ez, press, with_e, shs, flo, fhi, lo, hi, dims, acc)
    _finish(acc, with_e, heating, lo, hi, vol, cv, rho_o, vel_o, temp_o, spv_o, tot_o, scal_o)


@njit(cache=True, error_model="numpy")
def _fluxes_extrema(q, ux, uy, uz, shs, flo, fhi, lo, hi, dt, dxs, dims, compatible, acc, buf, grad, rc):
    """acc += the second-order fluxes of q with Uintah's limiter: q's limited gradients, then one
    sweep per active direction (the slabs' centroids offset by the other directions' velocities)."""
    limited_gradients(q, dims, dxs, compatible, grad)
    if int(dims[0]) + int(dims[1]) + int(dims[2]) > 1:
        _slab_offsets(ux, uy, uz, shs, dims, dt, rc)
    for d in range(3):
        if dims[d]:
            uf = ux if d == 0 else (uy if d == 1 else uz)
            _sweep_extrema(q, grad, rc, uf, d, shs[d], flo[d], fhi[d], lo, hi, dt, dxs, dims, compatible, acc, buf)


@njit(cache=True, error_model="numpy")
def advect_extrema(mass, mom, eng, volm, tot, scal, with_e, heating, ux, uy, uz, ex, ey, ez, press, shs, flo, fhi, lo,
                   hi, dt, dxs, dims, compatible, q, acc, buf, grad, rc, vol, cv, rho_o, vel_o, temp_o, spv_o, tot_o,
                   scal_o):
    """advect (second order) with Uintah's limiter (<advection limiter="BarthJespersen">);
    grad, rc: scratch (3, nq, *mass.shape), (3, *mass.shape); compatible: Uintah's
    useCompatibleFluxes."""
    _start(mass, mom, eng, volm, tot, scal, with_e, heating, q, acc, lo, hi)
    _fluxes_extrema(q, ux, uy, uz, shs, flo, fhi, lo, hi, dt, dxs, dims, compatible, acc, buf, grad, rc)
    _open_transfers(q, ex, ey, ez, press, with_e, shs, flo, fhi, lo, hi, dims, acc)
    _finish(acc, with_e, heating, lo, hi, vol, cv, rho_o, vel_o, temp_o, spv_o, tot_o, scal_o)


@njit(cache=True, error_model="numpy")
def outflow_fraction(vf, ux, uy, uz, shs, flo, fhi, lo, hi, dt, dxs, dims, compatible, q, acc, buf, grad, rc, out):
    """out += the volume fraction that second-order advection with Uintah's limiter carries out of
    each cell of [lo, hi) over the step, net of what it carries in: the fraction itself is
    reconstructed (its limited gradient at the outflow slab's centroid), as Uintah's advectQ of
    vol_frac in computeDelPressAndUpdatePressCC (term2, the dilatation of eq. 29).
    compatible: False (Uintah's), an argument so that _fluxes_extrema gets advect_extrema's types
    (a literal False compiled it and its helpers a second time, ~8 CPU s);
    q, acc: scratch (1, *vf.shape); buf (1, row length + 1); grad (3, 1, *vf.shape), rc (3, *vf.shape)."""
    q[0] = vf
    n = hi[2] - lo[2]
    k0 = lo[2]
    for i in range(lo[0], hi[0]):
        for j in range(lo[1], hi[1]):
            a, f = acc[0, i, j, k0:k0 + n], vf[i, j, k0:k0 + n]
            for k in range(n):
                a[k] = f[k]
    _fluxes_extrema(q, ux, uy, uz, shs, flo, fhi, lo, hi, dt, dxs, dims, compatible, acc, buf, grad, rc)
    for i in range(lo[0], hi[0]):
        for j in range(lo[1], hi[1]):
            a, f, o = acc[0, i, j, k0:k0 + n], vf[i, j, k0:k0 + n], out[i, j, k0:k0 + n]
            for k in range(n):
                o[k] += f[k] - a[k]


@njit(cache=True, error_model="numpy")
def _finish(acc, with_e, heating, lo, hi, vol, cv, rho_o, vel_o, temp_o, spv_o, tot_o, scal_o):
    """The new primitives of the cells [lo, hi) from the advected totals (see advect)."""
    n = hi[2] - lo[2]
    k0 = lo[2]
    ns = scal_o.shape[0]
    base = acc.shape[0] - ns
    for i in range(lo[0], hi[0]):
        for j in range(lo[1], hi[1]):
            am, ae, av = acc[0, i, j, k0:k0 + n], acc[4, i, j, k0:k0 + n], acc[5, i, j, k0:k0 + n]
            ro, to, so, vo = rho_o[i, j, k0:k0 + n], temp_o[i, j, k0:k0 + n], spv_o[i, j, k0:k0 + n], \
                vel_o[i, j, k0:k0 + n]
            for k in range(n):
                m = max(am[k], 1e-300)
                ro[k] = m / vol
                to[k] = ae[k] / (m * cv_at(cv, i, j, k0 + k))
                so[k] = av[k] / m
            for c in range(3):
                ac = acc[1 + c, i, j, k0:k0 + n]
                for k in range(n):
                    vo[k, c] = ac[k] / max(am[k], 1e-300)
            if heating:                         # e = E/m - |u|^2/2 where positive
                ae = acc[6, i, j, k0:k0 + n]
                for k in range(n):
                    m = max(am[k], 1e-300)
                    e = ae[k] / m - 0.5 * (vo[k, 0] ** 2 + vo[k, 1] ** 2 + vo[k, 2] ** 2)
                    if e > 0.0:
                        to[k] = e / cv_at(cv, i, j, k0 + k)
            elif with_e:
                ae, eo = acc[6, i, j, k0:k0 + n], tot_o[i, j, k0:k0 + n]
                for k in range(n):
                    eo[k] = ae[k]
            for s in range(ns):
                af, fo = acc[base + s, i, j, k0:k0 + n], scal_o[s, i, j, k0:k0 + n]
                for k in range(n):
                    fo[k] = af[k] / max(am[k], 1e-300)


@njit(cache=True)
def energy_finish(rho_o, vel_o, temp_o, tot_o, lo, hi, vol, cv, code, params):
    """Conservative total energy -> temperature: cv T = E/m - |u|^2/2 - e_c(rho) where that
    is positive (elsewhere the advected internal energy stays). e_c (eos_cold_energy) is
    evaluated at rho = m/V, the material density of a single material; with several
    materials the option allows ideal gases only (e_c = 0). Returns the number of cells
    where the advected internal energy was kept."""
    bad = 0
    for i in range(lo[0], hi[0]):
        for j in range(lo[1], hi[1]):
            for k in range(lo[2], hi[2]):
                m = rho_o[i, j, k] * vol
                u0, u1, u2 = vel_o[i, j, k, 0], vel_o[i, j, k, 1], vel_o[i, j, k, 2]
                e = tot_o[i, j, k] / m - 0.5 * (u0 * u0 + u1 * u1 + u2 * u2)
                if code != IDEAL_GAS:
                    e -= eos_cold_energy(code, params, rho_o[i, j, k])
                if e > 0.0:
                    temp_o[i, j, k] = e / cv_at(cv, i, j, k)
                else:
                    bad += 1
    return bad
