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


CONTACT_EPSILON = 1e-14       # Uintah's Contact::compare


@njit(cache=True)
def friction(gmass, gvel, gnorm, tn, mu, dx, delt, gacc, gvel_old, dt):
    """Coulomb friction contact (Uintah's FrictionContactBard without the separation and
    volume constraints); see contact.py. gnorm: outward unit normals per material; tn: the
    normal traction per material (friction_bard: a node in compression, tn < -1e-12, is in
    contact even when its material separates) or an empty array (approach: only approaching
    materials are); dt > 0: also a_m = (v_m - v_old_m)/dt at the nodes changed."""
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
            # Uintah's !compare(mass / M, 0) && !compare(mass - M, 0): its EPSILON 1e-14, the second
            # in kg, passes over round-off masses at the edge of a GIMP particle's reach
            if not (mass / M > CONTACT_EPSILON and M - mass > CONTACT_EPSILON):
                continue
            d0 = gvel[m, i, 0] - vcm[0]
            d1 = gvel[m, i, 1] - vcm[1]
            d2 = gvel[m, i, 2] - vcm[2]
            n0, n1, n2 = gnorm[m, i, 0], gnorm[m, i, 1], gnorm[m, i, 2]
            dn = d0 * n0 + d1 * n1 + d2 * n2
            if not (dn > 0.0 or (tn.shape[0] > 0 and tn[m, i] < -1e-12)):
                continue                            # separating or sliding, not pressed: free surface
            t0 = d0 - dn * n0
            t1 = d1 - dn * n1
            t2 = d2 - dn * n2
            tl = np.sqrt(t0 * t0 + t1 * t1 + t2 * t2)
            D0 = -dn * n0
            D1 = -dn * n1
            D2 = -dn * n2
            if tl > 1e-14 * abs(dn):
                adn = abs(dn)
                fc = min(mu, tl / adn)              # tl = dv . tangent
                D0 -= t0 / tl * fc * adn
                D1 -= t1 / tl * fc * adn
                D2 -= t2 / tl * fc * adn
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


# the rigid contact acts where the master material's nodal mass exceeds this (kg): Uintah's
# Contact::compare(m, 0) with its EPSILON 1e-14, which passes over the round-off masses at the
# edge of a GIMP particle's reach (their velocity, momentum / mass, is noise)
RIGID_MIN_MASS = 1e-14


@njit(cache=True)
def rigid(gmass, gvel, gacc, gvel_old, h, dt, master, direction, vel, use_own, origin, omega, axis,
          shape, anchor, spacing, low):
    """Uintah's SpecifiedBodyContact after integration (h = dt; 0 before it): where the
    master material has mass (above RIGID_MIN_MASS) it takes the rigid velocity, the others its components
    along `direction`. The rigid velocity is vel plus the rotation part at the node x:
    (R(omega dt) (x - o) - (x - o))/dt about coordinate `axis`, else omega x (x - o)."""
    nm = gmass.shape[0]
    rv = np.empty(3)
    rot = np.zeros(3)
    turning = omega[0] != 0.0 or omega[1] != 0.0 or omega[2] != 0.0
    nyz = shape[1] * shape[2]
    for i in range(gmass.shape[1]):
        if not gmass[master, i] > RIGID_MIN_MASS:
            continue
        if turning:
            r = np.empty(3)
            ijk = (i // nyz, (i // shape[2]) % shape[1], i % shape[2])
            for d in range(3):
                r[d] = anchor[d] + (low[d] + ijk[d]) * spacing[d] - origin[d]
            if axis < 0:
                rot[0] = omega[1] * r[2] - omega[2] * r[1]
                rot[1] = omega[2] * r[0] - omega[0] * r[2]
                rot[2] = omega[0] * r[1] - omega[1] * r[0]
            else:
                a, b = (axis + 1) % 3, (axis + 2) % 3      # rotation in the (a, b) plane
                turn = np.arctan2(r[b], r[a]) + omega[axis] * dt
                radius = np.sqrt(r[a] * r[a] + r[b] * r[b])
                rot[axis] = 0.0
                rot[a] = (radius * np.cos(turn) - r[a]) / dt
                rot[b] = (radius * np.sin(turn) - r[b]) / dt
        for d in range(3):
            rv[d] = gvel[master, i, d] if use_own else vel[d] + rot[d]
        for m in range(nm):
            for d in range(3):
                if m == master or direction[d]:
                    gvel[m, i, d] = rv[d]
                    if h > 0.0:
                        gacc[m, i, d] = (rv[d] - gvel_old[m, i, d]) / h



# -- friction_LR: Nairn & Hammerquist's logistic-regression normals (Uintah's
#    SerialMPM::computeLogisticRegression and FrictionContactLR) --------------------------------

@njit(cache=True)
def lr_alpha(gmass, possible, rigid, alpha, n_matls):
    """Per node: the alpha material (most mass among the possible ones; a rigid one wins)
    and how many materials have mass there (above 1e-8 of the total); alpha = -99 where
    fewer than two."""
    nm, nn = gmass.shape
    for i in range(nn):
        total = 0.0
        for m in range(nm):
            total += gmass[m, i]
        alpha[i] = -99
        count = 0
        most = -9.0e99
        for m in range(nm):
            if possible[m] and gmass[m, i] > 1e-8 * total and gmass[m, i] > 1e-16:
                count += 1
                if gmass[m, i] > most:
                    alpha[i] = m
                    most = gmass[m, i]
        most_rigid = 1e-90
        for m in range(nm):
            if rigid[m] and possible[m] and gmass[m, i] > most_rigid:
                most_rigid = gmass[m, i]
                alpha[i] = m
        n_matls[i] = count
        if count < 2:
            alpha[i] = -99


@njit(cache=True)
def _in_box(i, j, k, lo, hi):
    return lo[0] <= i < hi[0] and lo[1] <= j < hi[1] and lo[2] <= k < hi[2]


@njit(cache=True)
def lr_near(kind, act, px, lp, anchor, dx, node_low, shape, own_lo, own_hi, n_matls, smin, count, fill,
            start, xs):
    """Particles of one material near multi-material nodes (weight > smin, node owned):
    count[i] += 1 per particle; with fill, also xs[start[i] + k] = x_p in particle order."""
    sh0, sh1, sh2 = shape[0], shape[1], shape[2]
    na, nb, nc = _counts(kind, act)
    ih = _inv_dx(dx)
    for p in range(px.shape[0]):
        (i, j, k, wx0, wx1, wx2, gx0, gx1, gx2, wy0, wy1, wy2, gy0, gy1, gy2,
         wz0, wz1, wz2, gz0, gz1, gz2) = _stencil(kind, act, px, lp, p, anchor, ih, node_low)
        for a in range(na):
            for b in range(nb):
                for c in range(nc):
                    S = _sel(a, wx0, wx1, wx2) * _sel(b, wy0, wy1, wy2) * _sel(c, wz0, wz1, wz2)
                    if not (S > smin and _in_box(i + a, j + b, k + c, own_lo, own_hi)):
                        continue
                    node = ((i + a) * sh1 + j + b) * sh2 + k + c
                    if n_matls[node] < 2:
                        continue
                    if fill:
                        for d in range(3):
                            xs[start[node] + count[node], d] = px[p, d]
                    count[node] += 1


@njit(cache=True)
def _solve4(A, r):
    """r <- A^-1 r by Gauss-Jordan with partial pivoting (Uintah's FastMatrix solve); A is destroyed."""
    for i in range(4):
        big = abs(A[i, i])
        row = i
        for j in range(i + 1, 4):
            if abs(A[j, i]) > big:
                big = abs(A[j, i])
                row = j
        if row != i:
            for j in range(i, 4):
                A[i, j], A[row, j] = A[row, j], A[i, j]
            r[i], r[row] = r[row], r[i]
        s = 1.0 / A[i, i]
        r[i] *= s
        for j in range(i, 4):
            A[i, j] *= s
        for j in range(i + 1, 4):
            f = A[j, i]
            r[j] -= f * r[i]
            for k in range(i, 4):
                A[j, k] -= f * A[i, k]
    for i in range(3, -1, -1):
        for j in range(i + 1, 4):
            r[i] -= A[i, j] * r[j]


@njit(cache=True)
def lr_normals(alpha, start, count, xs, lam, normal):
    """The unit normal from the alpha material to the others at each multi-material node:
    phi minimises sum_p (c_p - (2/(1+exp(-x_p.phi)) - 1))^2 + lam |phi_xyz|^2 (c_p = -1 for
    alpha's particles, +1 for the others; Nairn & Hammerquist 2019 eqs. 20, 54-55) by
    Gauss-Newton from phi = 0, to 1 - n_k.n_k+1 < 1e-7 (at most 51 iterations, then
    the best one). start/count: (node, material) runs of xs, the particle positions."""
    nn, nm = count.shape
    A = np.empty((4, 4))
    rhs = np.empty(4)
    phi = np.empty(4)
    x4 = np.empty(4)
    for i in range(nn):
        normal[i, 0] = normal[i, 1] = normal[i, 2] = 0.0
        if alpha[i] < 0:
            continue
        with_particles = 0
        for m in range(nm):
            if count[i, m] > 0:
                with_particles += 1
        if with_particles < 2:
            alpha[i] = -99
            continue
        phi[:] = 0.0
        nk0 = nk1 = nk2 = 0.0
        best = 1.0
        b0 = b1 = b2 = 0.0
        iters = 0
        while True:
            iters += 1
            A[:, :] = 0.0
            for d in range(3):
                A[d, d] = lam
                rhs[d] = -lam * phi[d]
            rhs[3] = 0.0
            for m in range(nm):
                cp = -1.0 if m == alpha[i] else 1.0
                for q in range(start[i, m], start[i, m] + count[i, m]):
                    x4[0], x4[1], x4[2], x4[3] = xs[q, 0], xs[q, 1], xs[q, 2], 1.0
                    e = np.exp(-(x4[0] * phi[0] + x4[1] * phi[1] + x4[2] * phi[2] + phi[3]))
                    f20 = 2.0 / (1.0 + e) - 1.0
                    psi = 2.0 * e / ((1.0 + e) * (1.0 + e))
                    psi2 = psi * psi
                    for a in range(4):
                        for b in range(4):
                            A[a, b] += psi2 * x4[a] * x4[b]
                        rhs[a] += psi * (cp - f20) * x4[a]
            _solve4(A, rhs)
            for a in range(4):
                phi[a] += rhs[a]
            length = np.sqrt(phi[0] * phi[0] + phi[1] * phi[1] + phi[2] * phi[2]) + 1e-100
            n0, n1, n2 = phi[0] / length, phi[1] / length, phi[2] / length
            err = 1.0 - (n0 * nk0 + n1 * nk1 + n2 * nk2)
            if err < best:
                best = err
                b0, b1, b2 = n0, n1, n2
            if err < 1e-7 or iters > 50:
                if iters > 50:
                    n0, n1, n2 = b0, b1, b2
                normal[i, 0], normal[i, 1], normal[i, 2] = n0, n1, n2
                break
            nk0, nk1, nk2 = n0, n1, n2


@njit(cache=True)
def lr_prominence(kind, act, px, lp, half, surface, anchor, dx, node_low, shape, own_lo, own_hi,
                  near, alpha, normal, m, pmax, pmin):
    """Material m's extreme face projections at nodes near two or more particles: over the
    face centres x_p +- half of its surface particles (weight > 0), pmax = the largest x.n
    where m is the alpha material, pmin = the smallest elsewhere (start at -/+9e99)."""
    sh1, sh2 = shape[1], shape[2]
    na, nb, nc = _counts(kind, act)
    ih = _inv_dx(dx)
    for p in range(px.shape[0]):
        if not surface[p] > 0.9:
            continue
        (i, j, k, wx0, wx1, wx2, gx0, gx1, gx2, wy0, wy1, wy2, gy0, gy1, gy2,
         wz0, wz1, wz2, gz0, gz1, gz2) = _stencil(kind, act, px, lp, p, anchor, ih, node_low)
        for a in range(na):
            for b in range(nb):
                for c in range(nc):
                    S = _sel(a, wx0, wx1, wx2) * _sel(b, wy0, wy1, wy2) * _sel(c, wz0, wz1, wz2)
                    if not (S > 0.0 and _in_box(i + a, j + b, k + c, own_lo, own_hi)):
                        continue
                    node = ((i + a) * sh1 + j + b) * sh2 + k + c
                    if near[node] < 2:
                        continue
                    for f in range(6):
                        d = f // 2
                        sgn = 1.0 if f % 2 else -1.0
                        proj = 0.0
                        for e in range(3):
                            proj += px[p, e] * normal[node, e]
                        proj += sgn * half[p, d] * normal[node, d]
                        if m == alpha[node]:
                            pmax[node] = max(pmax[node], proj)
                        else:
                            pmin[node] = min(pmin[node], proj)


@njit(cache=True)
def friction_lr(gmass, gvel, requested, alpha, normal, prom, mu, gacc, gvel_old, dt):
    """Uintah's FrictionContactLR at each node with an alpha material: a beta material b
    whose prominence does not exceed alpha's (they touch) and that moves toward it
    (dv.n > 0, dv = v_b - v_cm, n = -normAlphaToBeta) loses that normal part and, of its
    tangential part, up to mu |dv.n| (Coulomb); alpha takes -m_b/m_alpha of that change
    (momentum kept); only the `requested` materials take part. mu: per node.
    dt > 0: also a = (v - v_old)/dt at the nodes changed."""
    nm, nn = gmass.shape
    for i in range(nn):
        al = alpha[i]
        if al < 0:
            continue
        M = 0.0
        v0 = v1 = v2 = 0.0
        for m in range(nm):
            if not requested[m]:
                continue
            M += gmass[m, i]
            v0 += gvel[m, i, 0] * gmass[m, i]
            v1 += gvel[m, i, 1] * gmass[m, i]
            v2 += gvel[m, i, 2] * gmass[m, i]
        v0 /= M
        v1 /= M
        v2 /= M
        n0, n1, n2 = -normal[i, 0], -normal[i, 1], -normal[i, 2]
        changed = False
        for m in range(nm):
            if not requested[m] or m == al or not gmass[m, i] > 1e-16 or prom[m, i] - prom[al, i] > 0.0:
                continue
            d0, d1, d2 = gvel[m, i, 0] - v0, gvel[m, i, 1] - v1, gvel[m, i, 2] - v2
            dn = d0 * n0 + d1 * n1 + d2 * n2
            if not dn > 0.0:
                continue
            t0, t1, t2 = d0 - dn * n0, d1 - dn * n1, d2 - dn * n2
            tl = np.sqrt(t0 * t0 + t1 * t1 + t2 * t2) + 1e-100
            t0, t1, t2 = t0 / tl, t1 / tl, t2 / tl
            fc = min(mu[i], (d0 * t0 + d1 * t1 + d2 * t2) / abs(dn))
            D0 = -dn * n0 - t0 * fc * abs(dn)
            D1 = -dn * n1 - t1 * fc * abs(dn)
            D2 = -dn * n2 - t2 * fc * abs(dn)
            r = gmass[m, i] / gmass[al, i]
            gvel[m, i, 0] += D0
            gvel[m, i, 1] += D1
            gvel[m, i, 2] += D2
            gvel[al, i, 0] -= D0 * r
            gvel[al, i, 1] -= D1 * r
            gvel[al, i, 2] -= D2 * r
            changed = True
        if changed and dt > 0.0:
            for m in range(nm):
                for d in range(3):
                    gacc[m, i, d] = (gvel[m, i, d] - gvel_old[m, i, d]) / dt


@njit(cache=True)
def specified_friction(gmass, gvel, requested, alpha, normal, prom, master, vel, use_own, exclude, mu,
                       gacc, gvel_old, dt):
    """Uintah's SpecifiedBodyFrictionContact: at a node with an alpha material the master
    takes the rigid velocity (`vel`, or its own with use_own) and another requested material
    with mass there, not standing out past alpha (prominence) and moving toward the master
    (dv.n > 0, dv = v_b - v_rigid, n = -normAlphaToBeta) loses that normal part and, of its
    tangential part, up to mu |dv.n| (the master takes nothing back); elsewhere the master
    takes the rigid velocity where it has mass. A node where material `exclude` (>= 0) has
    mass is left alone. dt > 0: a = (v - v_old)/dt at the nodes changed."""
    nm, nn = gmass.shape
    rv = np.empty(3)
    for i in range(nn):
        for d in range(3):
            rv[d] = gvel[master, i, d] if use_own else vel[d]
        al = alpha[i]
        if al < 0:
            if gmass[master, i] > 1e-99:
                for d in range(3):
                    gvel[master, i, d] = rv[d]
                    if dt > 0.0:
                        gacc[master, i, d] = (rv[d] - gvel_old[master, i, d]) / dt
            continue
        if exclude >= 0 and gmass[exclude, i] >= 1e-99:
            continue
        n0, n1, n2 = -normal[i, 0], -normal[i, 1], -normal[i, 2]
        for m in range(nm):
            if not requested[m]:
                continue
            if m == master:
                for d in range(3):
                    gvel[m, i, d] = rv[d]
                    if dt > 0.0:
                        gacc[m, i, d] = (rv[d] - gvel_old[m, i, d]) / dt
                continue
            if abs(gmass[master, i]) <= 1e-14 or abs(gmass[m, i]) <= 1e-14 or prom[m, i] - prom[al, i] > 0.0:
                continue
            d0, d1, d2 = gvel[m, i, 0] - rv[0], gvel[m, i, 1] - rv[1], gvel[m, i, 2] - rv[2]
            dn = d0 * n0 + d1 * n1 + d2 * n2
            if not dn > 0.0:
                continue
            t0, t1, t2 = d0 - dn * n0, d1 - dn * n1, d2 - dn * n2
            tl = np.sqrt(t0 * t0 + t1 * t1 + t2 * t2) + 1e-100
            t0, t1, t2 = t0 / tl, t1 / tl, t2 / tl
            fc = min(mu, (d0 * t0 + d1 * t1 + d2 * t2) / (abs(dn) + 1e-100))
            gvel[m, i, 0] += -dn * n0 - t0 * fc * abs(dn)
            gvel[m, i, 1] += -dn * n1 - t1 * fc * abs(dn)
            gvel[m, i, 2] += -dn * n2 - t2 * fc * abs(dn)
            if dt > 0.0:
                for d in range(3):
                    gacc[m, i, d] = (gvel[m, i, d] - gvel_old[m, i, d]) / dt


@njit(cache=True)
def rigid_reaction(master_mass, fint, others, own_lo, own_hi, shape, anchor, spacing, low, origin,
                   with_arm, force, torque):
    """Uintah's RigidReactionForce/Torque: at the owned nodes where the rigid (master)
    material has mass, force += -fint of the other contact materials and torque +=
    (x_i - origin) x -fint (with include_rotation; Uintah's arm is 0 without it)."""
    nyz = shape[1] * shape[2]
    for i in range(master_mass.shape[0]):
        if not master_mass[i] > RIGID_MIN_MASS:
            continue
        a, b, c = i // nyz, (i // shape[2]) % shape[1], i % shape[2]
        if not (own_lo[0] <= a < own_hi[0] and own_lo[1] <= b < own_hi[1] and own_lo[2] <= c < own_hi[2]):
            continue
        r0 = r1 = r2 = 0.0
        if with_arm:
            r0 = anchor[0] + (low[0] + a) * spacing[0] - origin[0]
            r1 = anchor[1] + (low[1] + b) * spacing[1] - origin[1]
            r2 = anchor[2] + (low[2] + c) * spacing[2] - origin[2]
        for m in range(fint.shape[0]):
            if not others[m]:
                continue
            f0, f1, f2 = -fint[m, i, 0], -fint[m, i, 1], -fint[m, i, 2]
            force[0] += f0
            force[1] += f1
            force[2] += f2
            torque[0] += r1 * f2 - r2 * f1
            torque[1] += r2 * f0 - r0 * f2
            torque[2] += r0 * f1 - r1 * f0


@njit(cache=True)
def pressure_stabilization(px, anchor, dx, lo, hi, dims, dt, F_old, vol_old, F, vol, L):
    """Uintah's DoPressureStabilization (SerialMPM::computeParticleGradients): V = V_old J/J_old
    (J_old of the stabilized F_old: the volume follows the unstabilized increments, as Uintah's);
    in each cell of the patch (lo, hi; p.x at the step's start), J_c = sum V_p / sum (V_p / J_p);
    each particle's F is scaled by (J_c/J_p)^(1/3) and L (if given, len(L) = len(F)) gets
    ln(J_c/J_p)/(3 dt) I."""
    n0, n1, n2 = hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]
    vsum = np.zeros((n0, n1, n2))
    v0sum = np.zeros((n0, n1, n2))
    cells = np.empty((px.shape[0], 3), np.int64)
    for p in range(px.shape[0]):
        for d in range(3):
            c = lo[d]
            if dims[d]:
                c = int(np.floor((px[p, d] - anchor[d]) / dx[d]))
            cells[p, d] = min(max(c, lo[d]), hi[d] - 1) - lo[d]
        J = _det3(F, p)
        vol[p] = vol_old[p] * (J / _det3(F_old, p))
        vsum[cells[p, 0], cells[p, 1], cells[p, 2]] += vol[p]
        v0sum[cells[p, 0], cells[p, 1], cells[p, 2]] += vol[p] / J
    has_L = L.shape[0] == F.shape[0]
    for p in range(px.shape[0]):
        Jc = vsum[cells[p, 0], cells[p, 1], cells[p, 2]] / v0sum[cells[p, 0], cells[p, 1], cells[p, 2]]
        r = Jc / _det3(F, p)
        F[p] *= np.cbrt(r)
        if has_L:
            g = np.log(r) / (3.0 * dt)
            for d in range(3):
                L[p, d, d] += g


@njit(cache=True, inline="always")
def _det3(F, p):
    return (F[p, 0, 0] * (F[p, 1, 1] * F[p, 2, 2] - F[p, 1, 2] * F[p, 2, 1])
            - F[p, 0, 1] * (F[p, 1, 0] * F[p, 2, 2] - F[p, 1, 2] * F[p, 2, 0])
            + F[p, 0, 2] * (F[p, 1, 0] * F[p, 2, 1] - F[p, 1, 1] * F[p, 2, 0]))
