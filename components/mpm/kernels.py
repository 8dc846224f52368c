"""Numba kernels of the explicit MPM step (paper 000 sec. 3.2, paper 004 eqs. 5-17).

Node arrays use local indices (global = local + node_low) as in shape.py. The particle<->grid
transfers of the step are in transfer.py; here the grid update, contact,
totals and the output-only nodal stress.
"""
import numpy as np
from numba import njit

from .shape import _counts, _inv_dx, _sel, _stencil, _visits

FM = {'contract'}


# ---- grid ---------------------------------------------------------------------------
@njit(cache=True)
def divide_by_mass(gmass, gsum, out):
    """out_i = gsum_i / m_i for any number of components per node, zero where there is no
    mass: v_i = (m v)_i / m_i (000 eq. 22), the mass-weighted nodal stress. out may be gsum."""
    m = gmass.reshape(-1)
    s = gsum.reshape(-1)
    o = out.reshape(-1)
    k = s.shape[0] // m.shape[0]
    for i in range(m.shape[0]):
        inv = 1.0 / m[i] if m[i] > 0.0 else 0.0
        for c in range(k):
            o[k * i + c] = s[k * i + c] * inv


@njit(cache=True)
def integrate_acceleration(gmass, gvel, gfint, gfext, gravity, dt, min_mass, damp, gvs, gacc):
    """a_i = (fint_i + fext_i)/m_i + g - damp v_i (000 eq. 21), v*_i = v_i + a_i dt (eq. 25).

    Nodes with m_i <= min_mass get no force-driven acceleration (Uintah's
    minimum_mass_for_acc); empty nodes get a = 0."""
    m = gmass.reshape(-1)
    v = gvel.reshape(-1)
    fi = gfint.reshape(-1)
    fe = gfext.reshape(-1)
    vs = gvs.reshape(-1)
    ac = gacc.reshape(-1)
    for i in range(m.shape[0]):
        mi = m[i]
        for d in range(3):
            k = 3 * i + d
            if mi > 0.0:
                a = gravity[d] - damp * v[k]
                if mi > min_mass:
                    a += (fi[k] + fe[k]) / mi
            else:
                a = 0.0
            ac[k] = a
            vs[k] = v[k] + a * dt


@njit(cache=True)
def velocity_bc(gvs, gacc, gvel, dt, lo, hi, comps, value):
    """Set v* components `comps` (mask) to `value` on the node box [lo, hi) and
    recompute a = (v* - v)/dt there, as Uintah's setGridBoundaryConditions."""
    for i in range(lo[0], hi[0]):
        for j in range(lo[1], hi[1]):
            for k in range(lo[2], hi[2]):
                for d in range(3):
                    if comps[d]:
                        gvs[i, j, k, d] = value[d]
                        gacc[i, j, k, d] = (value[d] - gvel[i, j, k, d]) / dt


@njit(cache=True)
def single_velocity(gmass, gvel, gacc, gvel_old, dt):
    """Single-velocity contact: every material takes the centre-of-mass velocity of the
    node (004: one velocity field); with gacc, a_m = (v_cm - v_old_m)/dt.

    gmass (nm, N), gvel/gacc/gvel_old (nm, N, 3) flattened per material."""
    nm = gmass.shape[0]
    for i in range(gmass.shape[1]):
        M = 0.0
        n_with = 0
        for m in range(nm):
            if gmass[m, i] > 0.0:
                M += gmass[m, i]
                n_with += 1
        if n_with < 2:
            continue
        for d in range(3):
            P = 0.0
            for m in range(nm):
                P += gmass[m, i] * gvel[m, i, d]
            vcm = P / M
            for m in range(nm):
                gvel[m, i, d] = vcm
                if dt > 0.0:
                    gacc[m, i, d] = (vcm - gvel_old[m, i, d]) / dt


# ---- particles ----------------------------------------------------------------------
@njit(cache=True)
def sums(pm, pv, px, out):
    """out += [sum m, sum m v^2/2, sum m v (3), sum m x (3)] over particles."""
    for p in range(pm.shape[0]):
        m = pm[p]
        out[0] += m
        out[1] += 0.5 * m * (pv[p, 0] ** 2 + pv[p, 1] ** 2 + pv[p, 2] ** 2)
        for d in range(3):
            out[2 + d] += m * pv[p, d]
            out[5 + d] += m * px[p, d]


@njit(cache=True)
def p2g_stress(kind, act, px, pmass, pstress, lp, anchor, dx, node_low, gmass, gsm):
    """gsm_i += sum S m_p sigma_p and gmass_i += sum S m_p (Uintah's g.stressFS before
    the division by mass; kind/act at run time: this is an output-only task)."""
    sh0, sh1, sh2 = gmass.shape
    na, nb, nc = _counts(kind, act)
    ih = _inv_dx(dx)
    fm = gmass.reshape(-1)
    fs = gsm.reshape(-1)
    for p, q in _visits(kind, act, px.shape[0]):
        (i, j, k, wx0, wx1, wx2, gx0, gx1, gx2, wy0, wy1, wy2, gy0, gy1, gy2,
         wz0, wz1, wz2, gz0, gz1, gz2) = _stencil(kind, act, px, lp, p, anchor, ih, node_low, q)
        if not (i >= 0 and i + na <= sh0 and j >= 0 and j + nb <= sh1 and k >= 0 and k + nc <= sh2):
            raise IndexError("particle's nodes lie outside the patch node arrays")
        for a in range(na):
            for b in range(nb):
                for c in range(nc):
                    S = _sel(a, wx0, wx1, wx2) * _sel(b, wy0, wy1, wy2) * _sel(c, wz0, wz1, wz2) * pmass[p]
                    f = ((i + a) * sh1 + j + b) * sh2 + k + c
                    fm[f] += S
                    for r in range(3):
                        for t in range(3):
                            fs[9 * f + 3 * r + t] += S * pstress[p, r, t]


@njit(cache=True)
def owned_mask(px, anchor, dx, lo, hi, dims, out):
    """out[p] = particle p lies in the patch's cells [lo, hi) (as relocation decides)."""
    for p in range(px.shape[0]):
        ok = True
        for d in range(3):
            if dims[d]:
                c = np.floor((px[p, d] - anchor[d]) / dx[d])
                ok &= (c >= lo[d]) and (c < hi[d])
        out[p] = ok


@njit(cache=True)
def friction(gmass, gvel, gnorm, mu, dx, delt, gacc, gvel_old, dt):
    """Coulomb friction contact (Uintah's FrictionContactBard without the separation and
    volume constraints); see contact.py. gnorm: outward unit normals per material;
    dt > 0: also a_m = (v_m - v_old_m)/dt at the nodes changed."""
    nm = gmass.shape[0]
    vcm = np.empty(3)
    for i in range(gmass.shape[1]):
        M = 0.0
        n_with = 0
        for m in range(nm):
            if gmass[m, i] > 0.0:
                M += gmass[m, i]
                n_with += 1
        if n_with < 2:
            continue
        for d in range(3):
            P = 0.0
            for m in range(nm):
                P += gmass[m, i] * gvel[m, i, d]
            vcm[d] = P / M
        for m in range(nm):
            mass = gmass[m, i]
            if not (mass > 1e-15 * M and M - mass > 1e-15 * M):
                continue
            d0 = gvel[m, i, 0] - vcm[0]
            d1 = gvel[m, i, 1] - vcm[1]
            d2 = gvel[m, i, 2] - vcm[2]
            n0, n1, n2 = gnorm[m, i, 0], gnorm[m, i, 1], gnorm[m, i, 2]
            dn = d0 * n0 + d1 * n1 + d2 * n2
            if not dn > 0.0:                        # separating or sliding: free surface
                continue
            t0 = d0 - dn * n0
            t1 = d1 - dn * n1
            t2 = d2 - dn * n2
            tl = np.sqrt(t0 * t0 + t1 * t1 + t2 * t2)
            D0 = -dn * n0
            D1 = -dn * n1
            D2 = -dn * n2
            if tl > 1e-14 * abs(dn):
                fc = min(mu, tl / dn)               # tl = dv . tangent
                D0 -= t0 / tl * fc * dn
                D1 -= t1 / tl * fc * dn
                D2 -= t2 / tl * fc * dn
            # Uintah's limiter on the strain the contact imposes in one step
            emax = 0.0
            for d, Dd in ((0, D0), (1, D1), (2, D2)):
                if dx[d] > 0.0:
                    emax = max(emax, abs(Dd / dx[d] * delt))
            if emax > 0.0:
                emax *= max(1.0, mass / (M - mass))
                ff = min(emax, 0.5) / emax
                D0 *= ff
                D1 *= ff
                D2 *= ff
            gvel[m, i, 0] += D0
            gvel[m, i, 1] += D1
            gvel[m, i, 2] += D2
            if dt > 0.0:
                for d in range(3):
                    gacc[m, i, d] = (gvel[m, i, d] - gvel_old[m, i, d]) / dt


@njit(cache=True)
def rigid(gmass, gvel, gacc, gvel_old, dt, master, direction, vel, use_own):
    """Uintah's SpecifiedBodyContact after integration: where the master material has
    mass it takes the rigid velocity, the others its components along `direction`."""
    nm = gmass.shape[0]
    rv = np.empty(3)
    for i in range(gmass.shape[1]):
        if not gmass[master, i] > 0.0:
            continue
        for d in range(3):
            rv[d] = gvel[master, i, d] if use_own else vel[d]
        for m in range(nm):
            for d in range(3):
                if m == master or direction[d]:
                    gvel[m, i, d] = rv[d]
                    if dt > 0.0:
                        gacc[m, i, d] = (rv[d] - gvel_old[m, i, d]) / dt

