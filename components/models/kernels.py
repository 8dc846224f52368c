"""Numba kernels of the models: reactions (paper 001 sec. 3, eqs. 5-9) and the passive scalar.

Index conventions as in components/mpmice/kernels.py: `cc_low` / `node_low` are the
global indices of entry [0, 0, 0] of a patch's CC / NC arrays; a collapsed direction
(dims[d] == False) has one node layer (index 0).
"""
from __future__ import annotations

import numpy as np
from numba import njit


@njit(cache=True, inline="always")
def _node_masses(gmass, node_low, gi, gj, gk, dims, n_lo, n_hi):
    """Max, min and the gradient sums (plus - minus) of the reactant's node masses around a
    cell, a node on a symmetry face of the domain counted twice per face (Uintah's NC_CCweight;
    n_lo / n_hi: those faces' node indices, out of reach where a face is not a symmetry plane)."""
    mx = 1e-100
    mn = 1e100
    g0 = 0.0
    g1 = 0.0
    g2 = 0.0
    for a in range(2 if dims[0] else 1):
        for b in range(2 if dims[1] else 1):
            for c in range(2 if dims[2] else 1):
                x = gi + a - node_low[0] if dims[0] else 0
                y = gj + b - node_low[1] if dims[1] else 0
                z = gk + c - node_low[2] if dims[2] else 0
                m = gmass[x, y, z]
                if dims[0] and (gi + a == n_lo[0] or gi + a == n_hi[0]):
                    m *= 2.0
                if dims[1] and (gj + b == n_lo[1] or gj + b == n_hi[1]):
                    m *= 2.0
                if dims[2] and (gk + c == n_lo[2] or gk + c == n_hi[2]):
                    m *= 2.0
                mx = max(mx, m)
                mn = min(mn, m)
                g0 += m * (2 * a - 1) if dims[0] else 0.0
                g1 += m * (2 * b - 1) if dims[1] else 0.0
                g2 += m * (2 * c - 1) if dims[2] else 0.0
    return mx, mn, g0, g1, g2


@njit(cache=True)
def burn_cells(gmass, node_low, cc_low, lo, hi, dims, dx, n_lo, n_hi, temps, vfs, press, mass_c,
               T_thresh, p_thresh, coeff, p_ref, dt, burned, area):
    """Simple_Burn (001 eqs. 5-6): in a surface cell of the reactant whose hottest material
    (volume fraction > 0.2) is above T_thresh, and where p > p_thresh,
    m_burn = dt A K (p / p_ref)^0.778, at most the reactant's particle mass in the cell.

    Surface cell: (max - min) / max of the reactant's node masses around the cell in
    (0.4, 1); a node on the domain boundary (first / last node n_lo / n_hi) counts
    twice per boundary it lies on (as Uintah's NC_CCweight), so a reactant touching a
    symmetry plane or wall is not burning there. A = V / ((sum_d |n_d| dx_d) max_d |n_d|^(-1/3)) with n
    the unit gradient of the node masses (Uintah's computeSurfaceArea; dx_d for a face-aligned surface)."""
    s1, s2 = burned.shape[1], burned.shape[2]
    vol = dx[0] * dx[1] * dx[2]
    nm = len(temps)
    for i in range(lo[0], hi[0]):
        for j in range(lo[1], hi[1]):
            for k in range(lo[2], hi[2]):
                mx, mn, g0, g1, g2 = _node_masses(gmass, node_low, i + cc_low[0], j + cc_low[1], k + cc_low[2],
                                                  dims, n_lo, n_hi)
                r = (mx - mn) / mx
                if not (r > 0.4 and r < 1.0 and mx > 1e-12):
                    continue
                n0, n1, n2 = abs(g0) / dx[0], abs(g1) / dx[1], abs(g2) / dx[2]
                nn = np.sqrt(n0 * n0 + n1 * n1 + n2 * n2)
                if nn <= 0.0:
                    continue
                n0, n1, n2 = n0 / nn, n1 / nn, n2 / nn
                shape_factor = (1.0 / max(n0, max(n1, n2))) ** (1.0 / 3.0)
                A = vol / ((n0 * dx[0] + n1 * dx[1] + n2 * dx[2]) * shape_factor)
                area[i, j, k] = A
                T = 0.0
                for m in range(nm):
                    if vfs[m][i, j, k] > 0.2 and temps[m][i, j, k] > T:
                        T = temps[m][i, j, k]
                p = press[i, j, k]
                if T > T_thresh and p > p_thresh:
                    mb = dt * A * coeff * (p / p_ref) ** 0.778
                    burned[i, j, k] = min(mb, mass_c[(i * s1 + j) * s2 + k])


@njit(cache=True)
def mass_burn_fraction(mass_src, cmass, cc_low, node_low, dims, lo_cell, n_lo, n_hi, sym_lo, sym_hi, out):
    """Uintah's massBurnFraction (MPMICE::interpolateCCToNC): at every node of the domain the mean
    over the cells around it of |m_src| / cMass, the fraction of its mass the solid there burns
    this step. A cell beyond a symmetry plane is its mirror image, beyond another face it burns
    nothing; nodes outside the domain 0. lo_cell: the local cell of a collapsed direction."""
    nx, ny, nz = out.shape
    w = 1.0 / (1 << (dims[0] + dims[1] + dims[2]))
    for x in range(nx):
        for y in range(ny):
            for z in range(nz):
                g = (x + node_low[0], y + node_low[1], z + node_low[2])
                out[x, y, z] = 0.0
                inside = True
                for d in range(3):
                    if dims[d] and not (n_lo[d] <= g[d] <= n_hi[d]):
                        inside = False
                if not inside:
                    continue
                s = 0.0
                for a in range(2 if dims[0] else 1):
                    for b in range(2 if dims[1] else 1):
                        for c in range(2 if dims[2] else 1):
                            cell = np.empty(3, np.int64)
                            ok = True
                            for d, o in ((0, a), (1, b), (2, c)):
                                if not dims[d]:
                                    cell[d] = lo_cell[d]
                                    continue
                                gc = g[d] - 1 + o
                                if gc < n_lo[d]:
                                    if not sym_lo[d]:
                                        ok = False
                                    gc = n_lo[d]
                                elif gc > n_hi[d] - 1:
                                    if not sym_hi[d]:
                                        ok = False
                                    gc = n_hi[d] - 1
                                cell[d] = gc - cc_low[d]
                            for d in range(3):
                                if not 0 <= cell[d] < cmass.shape[d]:
                                    ok = False
                            if ok:
                                cm = cmass[cell[0], cell[1], cell[2]]
                                if cm > 0.0:        # 0: a cell beyond the ghost cells the task reads
                                    s += abs(mass_src[cell[0], cell[1], cell[2]]) / cm
                out[x, y, z] = s * w


@njit(cache=True)
def burn_particles(frac, min_mass, pmass, pvol, psize, px):
    """Uintah's interpolateToParticlesAndUpdate share of a burn: p.mass+ = max(m (1 - f), 0) with
    f the particle's interpolated massBurnFraction, its volume and size scaled alike; a particle
    left with min_mass or less is deleted (position NaN, which relocation removes)."""
    for p in range(frac.shape[0]):
        f = frac[p]
        if f <= 0.0:
            continue
        m = pmass[p]
        new = max(m * (1.0 - f), 0.0)
        ratio = new / m if m > 0.0 else 0.0
        pmass[p] = new
        pvol[p] *= ratio
        if psize.shape[0] > 0:          # p.size carried (GIMP, CPDI)
            for d in range(3):
                psize[p, d] *= ratio
        if new <= min_mass:
            for d in range(3):
                px[p, d] = np.nan


@njit(cache=True)
def pressure_source(mass_src, vol_src, v_react, vfs, sps, css, lo, hi, vol, press):
    """001 eq. 9's reaction term: p += (V_created - m_burned v_reactant) / V / sum_m theta_m kappa_m,
    kappa = v / c^2 (Uintah: sum_m m_src,m v_m, with the product's volume V_created)."""
    for i in range(lo[0], hi[0]):
        for j in range(lo[1], hi[1]):
            for k in range(lo[2], hi[2]):
                ms = mass_src[i, j, k]
                if ms == 0.0:
                    continue
                ks = 0.0
                for m in range(len(vfs)):
                    c = css[m][i, j, k]
                    ks += vfs[m][i, j, k] * sps[m][i, j, k] / (c * c)
                press[i, j, k] += (vol_src[i, j, k] - ms * v_react[i, j, k]) / vol / ks


@njit(cache=True)
def volume_source(mass_src, vol_src, sp_vol, lo, hi, sp_vol_L):
    """The product's Lagrangian volume holds its new mass at the specific volume it was
    made with (vol_src), not at the cell's current one (ICE's eq. 40 used m^L v)."""
    for i in range(lo[0], hi[0]):
        for j in range(lo[1], hi[1]):
            for k in range(lo[2], hi[2]):
                ms = mass_src[i, j, k]
                if ms != 0.0:
                    sp_vol_L[i, j, k] = max(sp_vol_L[i, j, k] + vol_src[i, j, k] - ms * sp_vol[i, j, k], 1e-100)


@njit(cache=True)
def particles_per_cell(px, anchor, dx, cc_low, lo, hi, count):
    """Steady_Burn's numPPC: the reactant's particles in each interior cell of the patch."""
    for p in range(px.shape[0]):
        i = int(np.floor((px[p, 0] - anchor[0]) / dx[0])) - cc_low[0]
        j = int(np.floor((px[p, 1] - anchor[1]) / dx[1])) - cc_low[1]
        k = int(np.floor((px[p, 2] - anchor[2]) / dx[2])) - cc_low[2]
        if lo[0] <= i < hi[0] and lo[1] <= j < hi[1] and lo[2] <= k < hi[2]:
            count[i, j, k] += 1.0


@njit(cache=True, inline="always")
def _ts_constants(T0, P, v_solid, CC1, CC2, CC3, CC4, CC5):
    """C1..C5 of the Ward-Son-Brewster steady burn at solid temperature T0, pressure P."""
    C3 = CC3 * P * P
    return CC1 / v_solid, T0 + CC2, C3, T0 + CC4, CC5 * C3


@njit(cache=True, inline="always")
def wsb_mass_flux(Ts, C1, C2, Ec, R):
    """m(Ts) = sqrt(C1 Ts^2 / (Ts - C2) exp(-Ec / (R Ts))): condensed-phase decomposition."""
    return np.sqrt(C1 * Ts * Ts / (Ts - C2) * np.exp(-Ec / R / Ts))


@njit(cache=True, inline="always")
def _ts_of_m(m, C3, C4, C5):
    """Ts(m) = C4 + C5 / (sqrt(m^2 + C3) + m)^2: the gas flame's heat feedback."""
    d = np.sqrt(m * m + C3) + m
    return C4 + C5 / (d * d)


@njit(cache=True)
def wsb_surface_temperature(Ts, C1, C2, C3, C4, C5, Ec, R, eps):
    """Ts = Ts(m(Ts)) by Uintah's bisection-Newton: Newton steps while they stay in the bracket
    and shrink by 0.7, else a bisection; |Ts - F(Ts)| < eps ends it (at most 100 steps)."""
    Tmin = C4
    Tsmax = 0.5 * (2.0 * R * C2 - Ec + np.sqrt(4.0 * R * R * C2 * C2 + Ec * Ec)) / R   # max of F
    Tmax = _ts_of_m(wsb_mass_flux(Tsmax if Tmin < Tsmax else Tmin, C1, C2, Ec, R), C3, C4, C5)
    IL, IR = Tmin, Tmax
    if Ts > Tmax or Ts < Tmin:
        Ts = 0.5 * (Tmin + Tmax)
    it = 0
    while it <= 100:
        it += 1
        y = Ts - _ts_of_m(wsb_mass_flux(Ts, C1, C2, Ec, R), C3, C4, C5)
        if y < 0.0:
            IL = Ts
        elif y > 0.0:
            IR = Ts
        else:
            IL = IR = Ts
        if abs(y) < eps:
            return Ts
        delta_new = 1e100
        while it <= 100:
            m = wsb_mass_flux(Ts, C1, C2, Ec, R)
            K1 = Ts - C2
            K2 = np.sqrt(m * m + C3)
            dF = 1.0 + (R * Ts * (K1 - C2) + Ec * K1) * m * C5 / ((K2 + m) * (K2 + m) * K1 * K2 * R * Ts * Ts)
            if dF == 0.0:
                break
            delta_old = delta_new
            delta_new = -y / dF                                  # Newton step
            Ts += delta_new
            y = Ts - _ts_of_m(wsb_mass_flux(Ts, C1, C2, Ec, R), C3, C4, C5)
            if abs(y) < eps:
                return Ts
            if Ts < IL or Ts > IR or abs(delta_new) > abs(delta_old * 0.7):
                break
            it += 1
            if y < 0.0:
                IL = Ts
            elif y > 0.0:
                IR = Ts
            else:
                IL = IR = Ts
        Ts = 0.5 * (IL + IR)                                     # bisection step
    return Ts


@njit(cache=True, inline="always")
def _ignition_neighbourhood(i, j, k, r0, r1, r2, vfs, temps, press, numppc, react, prod, BP, T_ign, p_det):
    """The burn models' look at a cell's neighbours: lit, one with at most BP particles holds a
    material (volume fraction > 0.2) hotter than T_ign; the reactant temperature of the
    neighbour richest in reactant (T0) and the pressure of the one richest in product (P); hot,
    any material of any neighbour is hotter than T_ign; near_det, a neighbour's pressure is
    above p_det (DDT1's detonation threshold)."""
    vf_r = -1.0
    vf_p = -1.0
    T0 = 0.0
    P = 0.0
    lit = False
    hot = False
    near_det = False
    for a in range(i - r0, i + r0 + 1):
        for b in range(j - r1, j + r1 + 1):
            for c in range(k - r2, k + r2 + 1):
                if vfs[react][a, b, c] > vf_r:
                    vf_r = vfs[react][a, b, c]
                    T0 = temps[react][a, b, c]
                if vfs[prod][a, b, c] > vf_p:
                    vf_p = vfs[prod][a, b, c]
                    P = press[a, b, c]
                if press[a, b, c] > p_det:
                    near_det = True
                for m in range(len(temps)):
                    if temps[m][a, b, c] > T_ign:
                        hot = True
                        if numppc[a, b, c] <= BP and vfs[m][a, b, c] > 0.2:
                            lit = True
    return lit, T0, P, hot, near_det


@njit(cache=True)
def steady_burn_cells(gmass, node_low, cc_low, lo, hi, dims, dx, n_lo, n_hi, numppc, temps, vfs, press, v_solid,
                      mass_c, react, prod, BP, T_ign, p_thresh, CC, Ec, R, eps, min_mass, dt, burned, burning, Ts_out):
    """Steady_Burn (Ward, Son and Brewster's WSB law, as Uintah's Steady_Burn): a cell holding
    reactant particles whose node masses vary (min/max < 0.7) burns when one of its 27
    neighbours with at most BP particles has a material (volume fraction > 0.2) hotter than
    T_ign and the pressure of the neighbour richest in product is >= p_thresh. T0: the
    reactant temperature of the neighbour richest in reactant. Burned mass
    dt A m(Ts), Ts from Ts = Ts(m(Ts)); A = V / ((sum_d |n_d| dx_d) max_d |n_d|^(-1/3)) with n
    the unit gradient of the node masses; at most the cell's particle mass less min_mass."""
    s1, s2 = burned.shape[1], burned.shape[2]
    vol = dx[0] * dx[1] * dx[2]
    r0 = 1 if dims[0] else 0
    r1 = 1 if dims[1] else 0
    r2 = 1 if dims[2] else 0
    for i in range(lo[0], hi[0]):
        for j in range(lo[1], hi[1]):
            for k in range(lo[2], hi[2]):
                if numppc[i, j, k] <= 0.0:
                    continue
                mx, mn, g0, g1, g2 = _node_masses(gmass, node_low, i + cc_low[0], j + cc_low[1], k + cc_low[2],
                                                  dims, n_lo, n_hi)
                if not mn / mx < 0.7:
                    continue
                lit, T0, P, _, _ = _ignition_neighbourhood(i, j, k, r0, r1, r2, vfs, temps, press, numppc, react,
                                                           prod, BP, T_ign, np.inf)
                if not (lit and P >= p_thresh):
                    continue
                burning[i, j, k] = 1.0
                gx, gy, gz = g0 / dx[0], g1 / dx[1], g2 / dx[2]
                gn = np.sqrt(gx * gx + gy * gy + gz * gz) + 1e-100
                nx, ny, nz = abs(gx) / gn, abs(gy) / gn, abs(gz) / gn
                A = 0.0
                if nx + ny + nz > 0.0:
                    coeff = (1.0 / max(nx, max(ny, nz))) ** (1.0 / 3.0)
                    A = vol / ((dx[0] * nx + dx[1] * ny + dx[2] * nz) * coeff)
                C1, C2, C3, C4, C5 = _ts_constants(T0, P, v_solid[i, j, k], CC[0], CC[1], CC[2], CC[3], CC[4])
                Ts = wsb_surface_temperature(850.0, C1, C2, C3, C4, C5, Ec, R, eps)
                Ts_out[i, j, k] = Ts
                mb = dt * A * wsb_mass_flux(Ts, C1, C2, Ec, R)
                have = mass_c[(i * s1 + j) * s2 + k]
                if mb + min_mass > have:
                    mb = max(have - min_mass, 0.0)
                burned[i, j, k] = mb


@njit(cache=True)
def unsteady_cells_from_particles(px, pbeta, pts, anchor, dx, cc_low, lo, hi, init_beta, beta_c, ts_c):
    """Unsteady_Burn's memory: each cell starts from its particles' last (beta, Ts), the
    particle with the largest beta below init_beta (cells with none keep 0)."""
    for p in range(px.shape[0]):
        i = int(np.floor((px[p, 0] - anchor[0]) / dx[0])) - cc_low[0]
        j = int(np.floor((px[p, 1] - anchor[1]) / dx[1])) - cc_low[1]
        k = int(np.floor((px[p, 2] - anchor[2]) / dx[2])) - cc_low[2]
        if lo[0] <= i < hi[0] and lo[1] <= j < hi[1] and lo[2] <= k < hi[2]:
            if pbeta[p] < init_beta and pbeta[p] > beta_c[i, j, k]:
                beta_c[i, j, k] = pbeta[p]
                ts_c[i, j, k] = pts[p]


@njit(cache=True)
def unsteady_particles_from_cells(px, anchor, dx, cc_low, lo, hi, burning, beta_c, ts_c, init_beta, init_ts,
                                  pbeta, pts):
    """The particles of a burning cell keep its (beta, Ts); the others are reset to the initial pair."""
    for p in range(px.shape[0]):
        i = int(np.floor((px[p, 0] - anchor[0]) / dx[0])) - cc_low[0]
        j = int(np.floor((px[p, 1] - anchor[1]) / dx[1])) - cc_low[1]
        k = int(np.floor((px[p, 2] - anchor[2]) / dx[2])) - cc_low[2]
        pbeta[p] = init_beta
        pts[p] = init_ts
        if lo[0] <= i < hi[0] and lo[1] <= j < hi[1] and lo[2] <= k < hi[2] and burning[i, j, k] > 0.0:
            pbeta[p] = beta_c[i, j, k]
            pts[p] = ts_c[i, j, k]


@njit(cache=True)
def unsteady_burn_cells(gmass, node_low, cc_low, lo, hi, dims, dx, n_lo, n_hi, numppc, temps, vfs, press, v_solid,
                        mass_c, react, prod, BP, T_ign, p_thresh, CC, UC, Ec, R, eps, min_mass, dt, old_burning,
                        old_ts, old_beta, init_ts, init_beta, burned, burning, ts_c, beta_c):
    """Unsteady_Burn (Uintah's; the WSB steady burn relaxed in time): the surface cells and
    ignition of steady_burn_cells. A cell that did not burn last step takes (beta, Ts) of the
    neighbour that has burned longest (else the initial pair). With the steady (Ts*, m*) and
    beta* = (Ts* - T0) m* Cp/Kc, beta and Ts relax towards them over n = Nc Kc/(Cp v dt m*^2)
    and Ng n steps, and the unsteady flux is m = 2c / (sqrt(b^2 - 4c) + b), b = 2 Kc beta / Qc,
    c = 2 Ac R Kc Ts^2 exp(-Ec/(R Ts)) / (Ec Qc v), scaled m* (m/m*)^Bm. UC: Cp/Kc, Kc/Cp,
    2 Kc/Qc, 2 Ac R Kc/(Ec Qc), Nc, Ng, Bm. Returns the number of cells where b^2 < 4c
    (Uintah: the timestep is too large), whose burn is left 0."""
    s1, s2 = burned.shape[1], burned.shape[2]
    vol = dx[0] * dx[1] * dx[2]
    r0 = 1 if dims[0] else 0
    r1 = 1 if dims[1] else 0
    r2 = 1 if dims[2] else 0
    bad = 0
    for i in range(lo[0], hi[0]):
        for j in range(lo[1], hi[1]):
            for k in range(lo[2], hi[2]):
                if numppc[i, j, k] <= 0.0:
                    continue
                mx, mn, g0, g1, g2 = _node_masses(gmass, node_low, i + cc_low[0], j + cc_low[1], k + cc_low[2],
                                                  dims, n_lo, n_hi)
                if not mn / mx < 0.7:
                    continue
                lit, T0, P, _, _ = _ignition_neighbourhood(i, j, k, r0, r1, r2, vfs, temps, press, numppc, react,
                                                           prod, BP, T_ign, np.inf)
                if not (lit and P >= p_thresh):
                    continue
                gx, gy, gz = g0 / dx[0], g1 / dx[1], g2 / dx[2]
                gn = np.sqrt(gx * gx + gy * gy + gz * gz) + 1e-100
                nx, ny, nz = abs(gx) / gn, abs(gy) / gn, abs(gz) / gn
                A = 0.0
                if nx + ny + nz > 0.0:
                    coeff = (1.0 / max(nx, max(ny, nz))) ** (1.0 / 3.0)
                    A = vol / ((dx[0] * nx + dx[1] * ny + dx[2] * nz) * coeff)
                if beta_c[i, j, k] == 0.0 or ts_c[i, j, k] == 0.0:     # newly lit: the longest-burning neighbour's
                    most = old_burning[i, j, k]
                    bi, bj, bk = i, j, k
                    for a in range(i - r0, i + r0 + 1):
                        for b in range(j - r1, j + r1 + 1):
                            for c in range(k - r2, k + r2 + 1):
                                if old_burning[a, b, c] > most:
                                    most = old_burning[a, b, c]
                                    bi, bj, bk = a, b, c
                    if most > 0.0:
                        beta_c[i, j, k] = old_beta[bi, bj, bk]
                        ts_c[i, j, k] = old_ts[bi, bj, bk]
                    else:
                        beta_c[i, j, k] = init_beta
                        ts_c[i, j, k] = init_ts
                beta = beta_c[i, j, k]
                Ts = ts_c[i, j, k]
                v = v_solid[i, j, k]
                C1, C2, C3, C4, C5 = _ts_constants(T0, P, v, CC[0], CC[1], CC[2], CC[3], CC[4])
                Ts_s = wsb_surface_temperature(Ts, C1, C2, C3, C4, C5, Ec, R, eps)
                m_s = wsb_mass_flux(Ts_s, C1, C2, Ec, R)
                beta_s = (Ts_s - T0) * m_s * UC[0]
                if beta < init_beta and Ts > init_ts:
                    n_coef = UC[4] * UC[1] / v / (dt * m_s * m_s)
                    m_coef = UC[5] * n_coef
                    beta = (n_coef - 1.0) / n_coef * beta + beta_s / n_coef if n_coef > 1.0 else beta_s
                    Ts = (m_coef - 1.0) / m_coef * Ts + Ts_s / m_coef if m_coef > 1.0 else Ts_s
                    bb = UC[2] * beta
                    cc = UC[3] / v * Ts * Ts * np.exp(-Ec / (R * Ts))
                    para = bb * bb - 4.0 * cc
                    if para < 0.0:
                        bad += 1
                        continue
                    m_burn = 2.0 * cc / (np.sqrt(para) + bb)
                    if UC[6] != 1.0:
                        m_burn = m_s * (m_burn / m_s) ** UC[6]
                else:
                    beta = beta_s
                    Ts = Ts_s
                    m_burn = m_s
                beta_c[i, j, k] = beta
                ts_c[i, j, k] = Ts
                burning[i, j, k] = old_burning[i, j, k] + 1.0
                mb = dt * A * m_burn
                have = mass_c[(i * s1 + j) * s2 + k]
                if mb + min_mass > have:
                    mb = max(have - min_mass, 0.0)
                burned[i, j, k] = mb
    return bad


@njit(cache=True)
def scalar_diffusion_source(f, diffusivity, src, dims, lo, hi, dx, dt):
    """Uintah's scalarDiffusionOperator for a constant D (PassiveScalar): src = -dt sum over the
    cell's faces of flux * area, flux = -D_face (f_R - f_L) / dx, D_face = 2 D D / (2 D + 1e-100),
    over the cells [lo, hi) (not divided by the cell volume, as Uintah)."""
    d_face = 2.0 * diffusivity * diffusivity / (diffusivity + diffusivity + 1e-100)
    area = np.array([dx[1] * dx[2], dx[0] * dx[2], dx[0] * dx[1]])
    for i in range(lo[0], hi[0]):
        for j in range(lo[1], hi[1]):
            for k in range(lo[2], hi[2]):
                s = 0.0
                for d in range(3):
                    if not dims[d]:
                        continue
                    di, dj, dk = (1, 0, 0) if d == 0 else ((0, 1, 0) if d == 1 else (0, 0, 1))
                    flux_hi = -d_face * (f[i + di, j + dj, k + dk] - f[i, j, k]) / dx[d]
                    flux_lo = -d_face * (f[i, j, k] - f[i - di, j - dj, k - dk]) / dx[d]
                    s += (flux_hi - flux_lo) * area[d]
                src[i, j, k] = -s * dt


@njit(cache=True)
def scalar_mass_sum(rho, f, vol, lo, hi):
    """sum of (rho V) f over the cells [lo, hi)."""
    total = 0.0
    for i in range(lo[0], hi[0]):
        for j in range(lo[1], hi[1]):
            for k in range(lo[2], hi[2]):
                total += rho[i, j, k] * vol * f[i, j, k]
    return total


@njit(cache=True)
def scalar_upper_face_flux(rho, f, vol, face_vel, d, lo, hi, shift):
    """sum of u_face (rho V) f over the extra cells of the domain's upper face in direction d
    (edges excluded), u_face the boundary face's velocity (Uintah's conservationTest)."""
    a, b = (d + 1) % 3, (d + 2) % 3
    total = 0.0
    c = np.zeros(3, dtype=np.int64)
    for p in range(lo[a], hi[a]):
        for q in range(lo[b], hi[b]):
            c[d], c[a], c[b] = hi[d], p, q
            i, j, k = c[0], c[1], c[2]
            total += face_vel[i - shift[0], j - shift[1], k - shift[2]] * (rho[i, j, k] * vol * f[i, j, k])
    return total


@njit(cache=True)
def move_tracers(x_old, disp_old, vel_cc, anchor, dx, cc_low, dom_lo, dom_hi, dt, x_new, disp_new, vel_new, cells):
    """Tracer particles carried by the cell velocity at the start of the step (Uintah's
    TracerParticles::moveParticles): x+ = x + u_cell dt, the displacement and velocity with it;
    a particle that leaves the closed domain box gets x+ = NaN (relocation deletes it). cells:
    the particles' local cell indices in the CC arrays (for the cloned cell values)."""
    for p in range(x_old.shape[0]):
        for d in range(3):
            cells[p, d] = int(np.floor((x_old[p, d] - anchor[d]) / dx[d])) - cc_low[d]
        u = vel_cc[cells[p, 0], cells[p, 1], cells[p, 2]]
        out = False
        for d in range(3):
            x_new[p, d] = x_old[p, d] + u[d] * dt
            disp_new[p, d] = disp_old[p, d] + (x_new[p, d] - x_old[p, d])
            vel_new[p, d] = u[d]
            out = out or x_new[p, d] < dom_lo[d] or x_new[p, d] > dom_hi[d]
        if out:
            for d in range(3):
                x_new[p, d] = np.nan


@njit(cache=True, inline="always")
def _mt_seed(mt, seed):
    """The 32-bit Mersenne Twister's state from one seed (init_genrand; Uintah's MTRand::seed)."""
    mt[0] = seed & 0xFFFFFFFF
    for i in range(1, 624):
        mt[i] = (1812433253 * (mt[i - 1] ^ (mt[i - 1] >> 30)) + i) & 0xFFFFFFFF


@njit(cache=True, inline="always")
def _mt_reload(mt):
    for k in range(624):
        y = (mt[k] & 0x80000000) | (mt[(k + 1) % 624] & 0x7FFFFFFF)
        mt[k] = mt[(k + 397) % 624] ^ (y >> 1) ^ (0x9908B0DF if y & 1 else 0)


@njit(cache=True, inline="always")
def _mt_temper(y):
    y ^= y >> 11
    y ^= (y << 7) & 0x9D2C5680
    y ^= (y << 15) & 0xEFC60000
    return y ^ (y >> 18)


@njit(cache=True)
def seed_tracers(cells, npc, anchor, dx, cc_low, count, x_out, id_out):
    """npc particles in each cell (global indices, (n, 3)) at Uintah's random points
    (TracerParticles::distributeParticles): the generator seeded with i + j + k of the cell, three
    draws in [0, 1] per particle, x = (centre - dx/2) + draw dx; the IDs i << 16 | j << 32 | k << 48
    or'ed with the cell's running count (nPPC, local indices from cc_low), which is advanced."""
    mt = np.empty(624, np.uint64)
    n = 0
    for c in range(cells.shape[0]):
        _mt_seed(mt, np.uint64(cells[c, 0] + cells[c, 1] + cells[c, 2]))
        _mt_reload(mt)
        used = 0
        ci, cj, ck = cells[c, 0] - cc_low[0], cells[c, 1] - cc_low[1], cells[c, 2] - cc_low[2]
        cell_id = (cells[c, 0] << 16) | (cells[c, 1] << 32) | (cells[c, 2] << 48)
        for p in range(npc):
            for d in range(3):
                if used == 624:
                    _mt_reload(mt)
                    used = 0
                r = float(_mt_temper(mt[used])) * (1.0 / 4294967295.0)
                used += 1
                centre = anchor[d] + dx[d] * cells[c, d] + dx[d] * 0.5      # Uintah's getCellPosition
                x_out[n, d] = (centre - dx[d] / 2.0) + r * dx[d]
            id_out[n] = cell_id | count[ci, cj, ck]
            count[ci, cj, ck] += 1
            n += 1


@njit(cache=True)
def solid_sources(cmass, mass_src, mom_src, eng_src, min_mass, olo, ohi, mass_L, mom_L, eng_L, mom_mpm):
    """Uintah's computeLagrangianValuesMPM where a model takes mass from a solid (mass_src < 0):
    m^L = max(cMass + m_src, min_mass); (mu)^L + mom_src and (me)^L each rescaled to the mass
    left (cMass + m_src) / m^L, the momentum keeping its sign and at least min_mass / cMass of
    its magnitude, the energy at least min_mass / cMass of itself. mom_mpm takes the same change
    of momentum (the rate dV/dt holds the exchange and grad p only)."""
    for i in range(olo[0], ohi[0]):
        for j in range(olo[1], ohi[1]):
            for k in range(olo[2], ohi[2]):
                ms = mass_src[i, j, k]
                if ms == 0.0:
                    continue
                cm = cmass[i, j, k]
                left = cm + ms
                m = max(left, min_mass)
                for d in range(3):
                    old = mom_L[i, j, k, d]
                    floor = min_mass * old / cm
                    tmp = old + mom_src[i, j, k, d]
                    sign = (tmp + 1e-100) / abs(tmp + 1e-100)
                    new = sign * max(abs(tmp / m * left), abs(floor))
                    mom_mpm[i, j, k, d] += new - old
                    mom_L[i, j, k, d] = new
                e = eng_L[i, j, k]
                eng_L[i, j, k] = max(e / m * left + eng_src[i, j, k], min_mass * e / cm)
                mass_L[i, j, k] = m
