"""Numba kernels of the ICE Lagrangian phase (paper 000 sec. 3.3 steps 2-11).

Conventions: every grid array is a patch's stored array (halo included); `lo`, `hi`
are local index ranges (int64[3]). Face arrays (SFCX/Y/Z) have their own origin:
`sh = low_index(SFC) - low_index(CC)` maps face (i,j,k) to its right/upper cell
(i,j,k)+sh; the left cell is one step back along the face normal `dd`. Materials of
a multi-material kernel come as tuples of arrays (one entry per material), so one
compiled kernel serves any number of materials. Kernels loop only over the
directions that exist: a 2D run never touches a third face direction. EOS codes are
eos.py's (MPMICE's solids: Murnaghan with n = 1, or SOLID_JWL for visco_scram's <useJWLEOS>).
"""
from __future__ import annotations

import numpy as np
from numba import njit

from .eos import (IDEAL_GAS, THOMSEN_HARTKA, TST, eos_alpha, eos_cold_energy, eos_press_eos, eos_rho_micro,
                  eos_sound_speed2, ideal_gas_alpha, ideal_gas_press_eos, ideal_gas_sound_speed2, tst_alpha)
from .specific_heat import cv_at, cv_at_flat

TINY = 1.0e-100


@njit(cache=True, error_model="numpy")
def equilibrate_one(rho, temp, sp_vol, press, vol_frac, cs, code, params, cv, gamma, lo, hi):
    """Eq. 13 for one material: theta = 1, rho_micro = rho; p and c from the EOS (cv and gamma
    one number, or one per cell where a model gives the mixture's).

    Kernels here loop over rows along the last axis through row slices indexed from 0
    (no negative-index wraparound: the loops vectorize); ICE's tasks pass arrays with the
    collapsed axes first (Boxes.view), so a 2D row is a long one."""
    n = hi[2] - lo[2]
    for i in range(lo[0], hi[0]):
        for j in range(lo[1], hi[1]):
            r, t = rho[i, j, lo[2]:hi[2]], temp[i, j, lo[2]:hi[2]]
            p_, v_, f_, c_ = press[i, j, lo[2]:hi[2]], sp_vol[i, j, lo[2]:hi[2]], \
                vol_frac[i, j, lo[2]:hi[2]], cs[i, j, lo[2]:hi[2]]
            if code == IDEAL_GAS:          # the same operations without the EOS dispatch: vectorizes
                for k in range(n):
                    cvk = cv_at(cv, i, j, lo[2] + k)
                    gk = cv_at(gamma, i, j, lo[2] + k)
                    p_[k] = ideal_gas_press_eos(r[k], t[k], cvk, gk)[0]
                    v_[k] = 1.0 / r[k]
                    f_[k] = 1.0
                    c_[k] = np.sqrt(max(ideal_gas_sound_speed2(r[k], t[k], cvk, gk), TINY))
                continue
            for k in range(n):
                cvk = cv_at(cv, i, j, lo[2] + k)
                gk = cv_at(gamma, i, j, lo[2] + k)
                p, dpdr, dpde = eos_press_eos(code, params, r[k], t[k], cvk, gk)
                p_[k] = p
                v_[k] = 1.0 / r[k]
                f_[k] = 1.0
                c_[k] = np.sqrt(max(eos_sound_speed2(code, params, r[k], t[k], cvk, gk), TINY))

@njit(cache=True, error_model="numpy")
def equilibrate_ideal(rhos, temps, sp_new, vfs, css, press, cvs, gammas, lo, hi):
    """Eq. 13 for ideal gases, solved exactly: theta_m = rho_m (gamma_m - 1) cv_m T_m / p, so
    sum theta = 1 gives p = sum rho_m (gamma_m - 1) cv_m T_m; then rho_micro_m, theta_m, c_m.
    (equilibration.equilibrate's Newton iteration converges to the same p within its tolerance.)"""
    n = len(rhos)
    nk = hi[2] - lo[2]
    k0 = lo[2]
    for i in range(lo[0], hi[0]):
        for j in range(lo[1], hi[1]):
            p = press[i, j, k0:k0 + nk]
            for k in range(nk):
                p[k] = 0.0
            for m in range(n):
                r, t = rhos[m][i, j, k0:k0 + nk], temps[m][i, j, k0:k0 + nk]
                f = (gammas[m] - 1.0) * cvs[m]
                for k in range(nk):
                    p[k] += r[k] * f * t[k]
            for m in range(n):
                r, t = rhos[m][i, j, k0:k0 + nk], temps[m][i, j, k0:k0 + nk]
                v, th, c = sp_new[m][i, j, k0:k0 + nk], vfs[m][i, j, k0:k0 + nk], css[m][i, j, k0:k0 + nk]
                cv, g = cvs[m], gammas[m]
                for k in range(nk):
                    rm = p[k] / ((g - 1.0) * cv * t[k])
                    v[k] = 1.0 / rm
                    th[k] = r[k] / rm
                    c[k] = np.sqrt(max(ideal_gas_sound_speed2(rm, t[k], cv, g), TINY))


@njit(cache=True, error_model="numpy")
def face_velocity(rho, vel, sp_vol, press, uf, sh, dd, comp, flo, fhi, dt, dx, g):
    """Eq. 28: mass-weighted average minus dt * harmonic specific volume * dp/dx (+ dt g)."""
    k0, k1 = flo[2], fhi[2]
    n = k1 - k0
    for i in range(flo[0], fhi[0]):
        for j in range(flo[1], fhi[1]):
            a, b = i + sh[0], j + sh[1]
            l0, l1 = a - dd[0], b - dd[1]
            r0 = k0 + sh[2]
            q0 = r0 - dd[2]
            rR, rL = rho[a, b, r0:r0 + n], rho[l0, l1, q0:q0 + n]
            uR, uL = vel[a, b, r0:r0 + n, comp], vel[l0, l1, q0:q0 + n, comp]
            vR, vL = sp_vol[a, b, r0:r0 + n], sp_vol[l0, l1, q0:q0 + n]
            pR, pL = press[a, b, r0:r0 + n], press[l0, l1, q0:q0 + n]
            out = uf[i, j, k0:k1]
            for k in range(n):
                avg = (rL[k] * uL[k] + rR[k] * uR[k]) / (rL[k] + rR[k])
                out[k] = avg - dt * (2.0 * vL[k] * vR[k] / (vL[k] + vR[k])) * (pR[k] - pL[k]) / dx + dt * g

@njit(cache=True)
def solve_small(a, b, n):
    """Gaussian elimination without pivoting (a is row diagonally dominant); b is overwritten."""
    for p in range(n):
        for r in range(p + 1, n):
            f = a[r, p] / a[p, p]
            for c in range(p, n):
                a[r, c] -= f * a[p, c]
            b[r] -= f * b[p]
    for r in range(n - 1, -1, -1):
        s = b[r]
        for c in range(r + 1, n):
            s -= a[r, c] * b[c]
        b[r] = s / a[r, r]


@njit(cache=True, error_model="numpy")
def exchange_faces(ufs, vfs, sps, out, sh, dd, flo, fhi, dt, K, kcell=None):
    """Eqs. 28+38 on faces: implicit momentum exchange of the face velocities of all materials.

    With face-averaged theta and v: u_m - u_m* = sum_n dt theta_n K_mn v_m (u_n - u_m);
    theta is the mean of the two cells', v their harmonic mean (Uintah's vel_FC_exchange).
    Two materials: rows of faces with the 2 x 2 solve written out (the same operations).
    kcell (the slip model, slip_exchange.py): a coefficient per cell; theta_n K_mn is then
    the mean of the two cells' theta_n kcell, times K_mn (ones).
    """
    n = len(ufs)
    if n == 2 and kcell is None:
        k0, k1 = flo[2], fhi[2]
        nk = k1 - k0
        for i in range(flo[0], fhi[0]):
            for j in range(flo[1], fhi[1]):
                x, y = i + sh[0], j + sh[1]
                l0, l1 = x - dd[0], y - dd[1]
                z0 = k0 + sh[2]
                q0 = z0 - dd[2]
                fR0, fL0 = vfs[0][x, y, z0:z0 + nk], vfs[0][l0, l1, q0:q0 + nk]
                fR1, fL1 = vfs[1][x, y, z0:z0 + nk], vfs[1][l0, l1, q0:q0 + nk]
                sR0, sL0 = sps[0][x, y, z0:z0 + nk], sps[0][l0, l1, q0:q0 + nk]
                sR1, sL1 = sps[1][x, y, z0:z0 + nk], sps[1][l0, l1, q0:q0 + nk]
                u0, u1 = ufs[0][i, j, k0:k1], ufs[1][i, j, k0:k1]
                o0, o1 = out[0][i, j, k0:k1], out[1][i, j, k0:k1]
                for k in range(nk):
                    o0[k], o1[k] = _solve2(u0[k], u1[k], 0.5 * (fR0[k] + fL0[k]), 0.5 * (fR1[k] + fL1[k]),
                                           2.0 * (sL0[k] * sR0[k]) / (sL0[k] + sR0[k]),
                                           2.0 * (sL1[k] * sR1[k]) / (sL1[k] + sR1[k]),
                                           K[0, 1], K[1, 0], dt, 1.0, 1.0, False)
        return
    a = np.empty((n, n))
    b = np.empty(n)
    th = np.empty(n)
    sv = np.empty(n)
    for i in range(flo[0], fhi[0]):
        for j in range(flo[1], fhi[1]):
            for k in range(flo[2], fhi[2]):
                x, y, z = i + sh[0], j + sh[1], k + sh[2]
                l0, l1, l2 = x - dd[0], y - dd[1], z - dd[2]
                for m in range(n):
                    if kcell is None:
                        th[m] = 0.5 * (vfs[m][x, y, z] + vfs[m][l0, l1, l2])
                    else:
                        th[m] = 0.5 * (vfs[m][x, y, z] * kcell[x, y, z] + vfs[m][l0, l1, l2] * kcell[l0, l1, l2])
                    sR, sL = sps[m][x, y, z], sps[m][l0, l1, l2]
                    sv[m] = 2.0 * (sL * sR) / (sL + sR)
                    b[m] = ufs[m][i, j, k]
                _exchange_matrix(a, th, sv, K, dt, n, None)
                solve_small(a, b, n)
                for m in range(n):
                    out[m][i, j, k] = b[m]


@njit(cache=True, error_model="numpy")
def _solve2(b0, b1, th0, th1, sv0, sv1, K01, K10, dt, cv0, cv1, heat):
    """(I + B) x = b for two materials: _exchange_matrix then solve_small, operation for operation."""
    a00, a01, f, a11 = _factor2(th0, th1, sv0, sv1, K01, K10, dt, cv0, cv1, heat)
    return _back2(b0, b1, a00, a01, f, a11)


@njit(cache=True, error_model="numpy")
def _factor2(th0, th1, sv0, sv1, K01, K10, dt, cv0, cv1, heat):
    """The elimination of the 2 x 2 exchange matrix: (a00, a01, the row factor, the reduced a11)."""
    beta01 = dt * th1 * K01 * sv0
    beta10 = dt * th0 * K10 * sv1
    if heat:
        beta01 /= cv0
        beta10 /= cv1
    a00 = 1.0 + beta01
    a01 = -beta01
    a10 = -beta10
    a11 = 1.0 + beta10
    f = a10 / a00
    a11 -= f * a01
    return a00, a01, f, a11


@njit(cache=True, error_model="numpy")
def _back2(b0, b1, a00, a01, f, a11):
    """Forward elimination of the right-hand side and back substitution."""
    b1 -= f * b0
    x1 = b1 / a11
    x0 = (b0 - a01 * x1) / a00
    return x0, x1


@njit(cache=True)
def _exchange_matrix(a, th, sv, K, dt, n, cv):
    """(I + B): B_mn = -dt theta_n K_mn v_m (/cv_m for heat), B_mm = -sum_n B_mn."""
    for m in range(n):
        diag = 1.0
        for q in range(n):
            if q == m:
                continue
            beta = dt * th[q] * K[m, q] * sv[m]
            if cv is not None:
                beta /= cv[m]
            a[m, q] = -beta
            diag += beta
        a[m, m] = diag


@njit(cache=True, error_model="numpy")
def div_theta_u(vf, one, ux, uy, uz, shx, shy, shz, dims, lo, hi, dt, dx, out):
    """Adds dt * div(theta u*) (donor-cell theta on faces) of one material to `out` (eq. 29).

    `one`: a single material, theta = 1 and the divergence is that of u*.
    """
    n = hi[2] - lo[2]
    k0 = lo[2]
    for i in range(lo[0], hi[0]):
        for j in range(lo[1], hi[1]):
            o = out[i, j, k0:k0 + n]
            th = vf[i, j, k0:k0 + n]
            # the three directions' lower (a) and upper (b) faces of the row, and the neighbour thetas
            xa = ux[i - shx[0], j - shx[1], k0 - shx[2]:k0 - shx[2] + n] if dims[0] else ux[0, 0, 0:0]
            xb = ux[i - shx[0] + 1, j - shx[1], k0 - shx[2]:k0 - shx[2] + n] if dims[0] else ux[0, 0, 0:0]
            ya = uy[i - shy[0], j - shy[1], k0 - shy[2]:k0 - shy[2] + n] if dims[1] else uy[0, 0, 0:0]
            yb = uy[i - shy[0], j - shy[1] + 1, k0 - shy[2]:k0 - shy[2] + n] if dims[1] else uy[0, 0, 0:0]
            za = uz[i - shz[0], j - shz[1], k0 - shz[2]:k0 - shz[2] + n] if dims[2] else uz[0, 0, 0:0]
            zb = uz[i - shz[0], j - shz[1], k0 - shz[2] + 1:k0 - shz[2] + 1 + n] if dims[2] else uz[0, 0, 0:0]
            tx0 = vf[i - 1, j, k0:k0 + n] if dims[0] else vf[0, 0, 0:0]
            tx1 = vf[i + 1, j, k0:k0 + n] if dims[0] else vf[0, 0, 0:0]
            ty0 = vf[i, j - 1, k0:k0 + n] if dims[1] else vf[0, 0, 0:0]
            ty1 = vf[i, j + 1, k0:k0 + n] if dims[1] else vf[0, 0, 0:0]
            tz = vf[i, j, k0 - 1:k0 + n + 1] if dims[2] else vf[0, 0, 0:0]
            for k in range(n):
                s = 0.0
                if dims[0]:
                    s += (_upwind(xb[k], th[k], tx1[k], one) - _upwind(xa[k], tx0[k], th[k], one)) / dx[0]
                if dims[1]:
                    s += (_upwind(yb[k], th[k], ty1[k], one) - _upwind(ya[k], ty0[k], th[k], one)) / dx[1]
                if dims[2]:
                    s += (_upwind(zb[k], th[k], tz[k + 2], one) - _upwind(za[k], tz[k], th[k], one)) / dx[2]
                o[k] += dt * s


@njit(cache=True, error_model="numpy")
def _upwind(u, below, above, one):
    """u * theta of the donor cell of a face with theta `below` / `above` on its two sides."""
    if one:
        return u
    return u * below if u >= 0.0 else u * above

@njit(cache=True)
def _vflux(vf, u, i, j, k, di, dj, dk, one):
    """u * theta of the donor cell of the face between (i,j,k) and (i,j,k)+d."""
    if one:
        return u
    if u >= 0.0:
        return u * vf[i, j, k]
    return u * vf[i + di, j + dj, k + dk]


@njit(cache=True, error_model="numpy")
def update_pressure(press_eq, div, kap_sum, delP, press, lo, hi, p_floor):
    """Eqs. 29-30: delP = -sum dt div(theta u*) / sum theta kappa; p = max(p_eq + delP, p_floor).

    p_floor: -inf in ICE; 1e-12 in MPMICE (Uintah's clamp), where a solid in tension drives
    p_eq + delP negative and V theta kappa p delP would then heat the expanding trace gas."""
    n = hi[2] - lo[2]
    for i in range(lo[0], hi[0]):
        for j in range(lo[1], hi[1]):
            pe, dv, ks = press_eq[i, j, lo[2]:hi[2]], div[i, j, lo[2]:hi[2]], kap_sum[i, j, lo[2]:hi[2]]
            dp, p = delP[i, j, lo[2]:hi[2]], press[i, j, lo[2]:hi[2]]
            for k in range(n):
                d = -dv[k] / ks[k]
                dp[k] = d
                p[k] = max(pe[k] + d, p_floor)

@njit(cache=True, error_model="numpy")
def pressure_from_mass_exchange(press, press_eq, delP, out, lo, hi):
    """delP_MassX = p - p_eq - delP_Dilatate (eq. 30's mass-exchange term), interior cells."""
    for i in range(lo[0], hi[0]):
        for j in range(lo[1], hi[1]):
            for k in range(lo[2], hi[2]):
                out[i, j, k] = press[i, j, k] - press_eq[i, j, k] - delP[i, j, k]


@njit(cache=True)
def hydrostatic_adjust(press, rho_micro, g, origin, anchor, dx, olo, ohi):
    """p += rho_micro g_d (x_d - x_ref,d) in cells olo..ohi (origin: the position of local cell
    0's low corner), d the (last) direction of gravity, x_ref the centre of cell 0 (Uintah's
    hydrostaticPressureAdjustment at initialization)."""
    d = 0
    for a in range(3):
        if g[a] != 0.0:
            d = a
    ref = anchor[d] + 0.5 * dx[d]
    for i in range(olo[0], ohi[0]):
        for j in range(olo[1], ohi[1]):
            for k in range(olo[2], ohi[2]):
                n = (i, j, k)[d]
                x = origin[d] + (n + 0.5) * dx[d]
                press[i, j, k] += rho_micro[i, j, k] * g[d] * (x - ref)


@njit(cache=True)
def clamp_sp_vol_lagrangian(sp_vol_L, sp_vol, tiny_rho, vol, lo, hi):
    """<ClampSpecificVolume>: m v >= tiny_rho V v in the interior cells (Uintah's
    computeLagrangianSpecificVolume), so that a draining cell keeps a positive volume."""
    for i in range(lo[0], hi[0]):
        for j in range(lo[1], hi[1]):
            for k in range(lo[2], hi[2]):
                sp_vol_L[i, j, k] = max(sp_vol_L[i, j, k], tiny_rho * vol * sp_vol[i, j, k])


@njit(cache=True)
def add_kappa_times(vf, sp_vol, cs, delP_MassX, out, lo, hi):
    """out += theta v / c^2 delP_MassX for one material: summed over materials, Uintah's
    term2 (impICE's massExchTerm = sumKappa delP_MassX), interior cells."""
    for i in range(lo[0], hi[0]):
        for j in range(lo[1], hi[1]):
            for k in range(lo[2], hi[2]):
                c = cs[i, j, k]
                out[i, j, k] += vf[i, j, k] * sp_vol[i, j, k] / (c * c) * delP_MassX[i, j, k]


@njit(cache=True, error_model="numpy")
def momentum_source(mom_L, rho, vel, vol, out, lo, hi):
    """mom_source_CC = mom_L - m u^n, m = rho^n V (eq. 34's sources times dt), interior cells."""
    for i in range(lo[0], hi[0]):
        for j in range(lo[1], hi[1]):
            for k in range(lo[2], hi[2]):
                m = rho[i, j, k] * vol
                for d in range(3):
                    out[i, j, k, d] = mom_L[i, j, k, d] - vel[i, j, k, d] * m


@njit(cache=True, error_model="numpy")
def add_theta_kappa(vf, sp_vol, cs, out, lo, hi):
    """out += theta kappa, kappa = v / c^2 (isothermal compressibility of eq. 47, as Uintah)."""
    n = hi[2] - lo[2]
    for i in range(lo[0], hi[0]):
        for j in range(lo[1], hi[1]):
            f, v = vf[i, j, lo[2]:hi[2]], sp_vol[i, j, lo[2]:hi[2]]
            c_, o = cs[i, j, lo[2]:hi[2]], out[i, j, lo[2]:hi[2]]
            for k in range(n):
                c = c_[k]
                o[k] += f[k] * v[k] / (c * c)

@njit(cache=True, error_model="numpy")
def face_pressure(press, rho_sum, pf, sh, dd, flo, fhi):
    """Eq. 31: p* = (pL/rhoL + pR/rhoR) / (1/rhoL + 1/rhoR), rho summed over materials."""
    k0, k1 = flo[2], fhi[2]
    n = k1 - k0
    for i in range(flo[0], fhi[0]):
        for j in range(flo[1], fhi[1]):
            a, b = i + sh[0], j + sh[1]
            l0, l1 = a - dd[0], b - dd[1]
            r0 = k0 + sh[2]
            q0 = r0 - dd[2]
            rR, rL = rho_sum[a, b, r0:r0 + n], rho_sum[l0, l1, q0:q0 + n]
            pR, pL = press[a, b, r0:r0 + n], press[l0, l1, q0:q0 + n]
            out = pf[i, j, k0:k1]
            for k in range(n):
                out[k] = (pL[k] * rR[k] + pR[k] * rL[k]) / (rL[k] + rR[k])

@njit(cache=True, error_model="numpy")
def lagrangian(rho, vel, temp, vf, sp_vol, cs, press, delP, px, py, pz, shx, shy, shz, dims,
               mass_L, mom_L, eng_L, olo, ohi, lo, hi, vol, dx, dt, cv, g, use_g, code, params, gamma, tmv,
               comp=None):
    """Eqs. 33-37 for one material: m, m u, m e plus pressure-gradient and flow-work sources.

    Everywhere (extra cells included) m u and m e start from the current state; the
    sources act on interior cells: -dt V theta grad p* (+ dt m g), V theta kappa p_w delP.
    ICE carries e = cv T, so the flow work uses p_w = p + (T (dp/dT)_v - p_eos): for an
    ideal gas p_w = p exactly (as Uintah); for a stiffened gas it is p + Pinf, which
    keeps cv dT = -T (dp/dT)_v dv consistent with the EOS; Thomsen_Hartka_water takes p_w = p
    (Uintah's, whose values pysus reproduces for it). The flow work's volume is the cell's,
    or with MPMICE tmv, the cell's total material volume (Uintah's TMV_CC; tmv of size 0:
    the cell's). comp[d]: the momentum component along axis d (arrays seen with permuted
    axes; None = the identity).
    """
    c0, c1, c2 = (0, 1, 2) if comp is None else (comp[0], comp[1], comp[2])
    n = ohi[2] - olo[2]
    for i in range(olo[0], ohi[0]):
        for j in range(olo[1], ohi[1]):
            r, t, u = rho[i, j, olo[2]:ohi[2]], temp[i, j, olo[2]:ohi[2]], vel[i, j, olo[2]:ohi[2]]
            ms, es, mu = mass_L[i, j, olo[2]:ohi[2]], eng_L[i, j, olo[2]:ohi[2]], mom_L[i, j, olo[2]:ohi[2]]
            for k in range(n):
                m = r[k] * vol
                ms[k] = m
                es[k] = m * cv_at(cv, i, j, olo[2] + k) * t[k]
                for c in range(3):
                    mu[k, c] = m * u[k, c]
    n = hi[2] - lo[2]
    k0 = lo[2]
    for i in range(lo[0], hi[0]):
        for j in range(lo[1], hi[1]):
            xa = px[i - shx[0], j - shx[1], k0 - shx[2]:k0 - shx[2] + n] if dims[0] else px[0, 0, 0:0]
            xb = px[i - shx[0] + 1, j - shx[1], k0 - shx[2]:k0 - shx[2] + n] if dims[0] else px[0, 0, 0:0]
            ya = py[i - shy[0], j - shy[1], k0 - shy[2]:k0 - shy[2] + n] if dims[1] else py[0, 0, 0:0]
            yb = py[i - shy[0], j - shy[1] + 1, k0 - shy[2]:k0 - shy[2] + n] if dims[1] else py[0, 0, 0:0]
            za = pz[i - shz[0], j - shz[1], k0 - shz[2]:k0 - shz[2] + n] if dims[2] else pz[0, 0, 0:0]
            zb = pz[i - shz[0], j - shz[1], k0 - shz[2] + 1:k0 - shz[2] + 1 + n] if dims[2] else pz[0, 0, 0:0]
            th_, v_, cs_ = vf[i, j, k0:k0 + n], sp_vol[i, j, k0:k0 + n], cs[i, j, k0:k0 + n]
            t_, p_, d_ = temp[i, j, k0:k0 + n], press[i, j, k0:k0 + n], delP[i, j, k0:k0 + n]
            ms, es, mu = mass_L[i, j, k0:k0 + n], eng_L[i, j, k0:k0 + n], mom_L[i, j, k0:k0 + n]
            for k in range(n):
                th = th_[k]
                v_work = tmv[i, j, k0 + k] if tmv.size else vol
                f = -dt * vol * th
                if dims[0]:
                    mu[k, c0] += f * (xb[k] - xa[k]) / dx[0]
                if dims[1]:
                    mu[k, c1] += f * (yb[k] - ya[k]) / dx[1]
                if dims[2]:
                    mu[k, c2] += f * (zb[k] - za[k]) / dx[2]
                if use_g:
                    for c in range(3):
                        mu[k, c] += dt * ms[k] * g[c]
                cc = cs_[k] ** 2
                t = t_[k]
                cvk = cv_at(cv, i, j, k0 + k)
                if code == IDEAL_GAS:
                    pe, dpdr, dpde = ideal_gas_press_eos(1.0 / v_[k], t, cvk, gamma)
                else:
                    pe, dpdr, dpde = eos_press_eos(code, params, 1.0 / v_[k], t, cvk, gamma)
                pw = p_[k] if code == THOMSEN_HARTKA else p_[k] + (dpde * cvk * t - pe)
                es[k] += v_work * th * v_[k] / cc * pw * d_[k]


@njit(cache=True)
def exchange_cells(masses, moms, engs, vfs, sps, cvs, mom_out, eng_out, lo, hi, dt, K, H):
    """Eqs. 38-39, pointwise implicit for any number of materials (stable for K = 1e15).

    Velocities: (I + B_K) u^L = u^L-; temperatures: (I + B_H / cv) T^L = T^L-, with
    B from _exchange_matrix; both conserve the mixture's momentum and energy. The
    systems are solved for the deviation from the mass- (m cv-) weighted mean, which
    the exchange leaves unchanged, so round-off stays at the level of the deviations
    even when K = 1e15 makes the matrix badly conditioned.
    """
    n = len(masses)
    if n == 2:
        _exchange_cells2(masses, moms, engs, vfs, sps, cvs, mom_out, eng_out, lo, hi, dt, K, H)
        return
    _exchange_cells_n(masses, moms, engs, vfs, sps, cvs, mom_out, eng_out, lo, hi, dt, K, H, False, False)


@njit(cache=True)
def exchange_cells_variable(masses, moms, engs, vfs, sps, cvs, mom_out, eng_out, lo, hi, dt, K, H, var_mom, var_heat):
    """exchange_cells with Uintah's <CoefficientModel> linearVariation: where var_mom (var_heat)
    each cell's momentum (heat) coefficients come from its Lagrangian masses
    (mass_ratio_coefficients) instead of K (H)."""
    _exchange_cells_n(masses, moms, engs, vfs, sps, cvs, mom_out, eng_out, lo, hi, dt, K, H, var_mom, var_heat)


@njit(cache=True)
def mass_ratio_coefficients(Q, masses, i, j, k, n):
    """Uintah's linearVariation exchange coefficient of each material pair m < q in cell (i, j, k)
    (ExchangeCoefficients::getVariableExchangeCoeff): r = (m_q / m_m)^2, Q = max(r, 1/r) clamped to
    [1e5, 1e12], so materials of like mass exchange at 1e5 and a trace material locks to its host."""
    for m in range(n):
        Q[m, m] = 0.0
        for q in range(m + 1, n):
            ratio = masses[q][i, j, k] / masses[m][i, j, k]
            r = ratio * ratio
            c = r if r >= 1.0 else 1.0 / r
            c = min(max(c, 1e5), 1e12)
            Q[m, q] = c
            Q[q, m] = c


@njit(cache=True)
def _exchange_cells_n(masses, moms, engs, vfs, sps, cvs, mom_out, eng_out, lo, hi, dt, K, H, var_mom, var_heat):
    """exchange_cells for any number of materials, one cell at a time (see exchange_cells)."""
    n = len(masses)
    K = K.copy()
    H = H.copy()
    a = np.empty((n, n))
    b = np.empty(n)
    th = np.empty(n)
    sv = np.empty(n)
    cvv = np.empty(n)
    for m in range(n):
        cvv[m] = cvs[m]
    for i in range(lo[0], hi[0]):
        for j in range(lo[1], hi[1]):
            for k in range(lo[2], hi[2]):
                for m in range(n):
                    th[m] = vfs[m][i, j, k]
                    sv[m] = sps[m][i, j, k]
                if var_mom:
                    mass_ratio_coefficients(K, masses, i, j, k, n)
                if var_heat:
                    mass_ratio_coefficients(H, masses, i, j, k, n)
                msum = 0.0
                esum = 0.0
                for m in range(n):
                    msum += masses[m][i, j, k]
                    esum += masses[m][i, j, k] * cvv[m]
                for c in range(3):
                    ubar = 0.0
                    for m in range(n):
                        ubar += moms[m][i, j, k, c]
                    ubar /= msum
                    for m in range(n):
                        b[m] = moms[m][i, j, k, c] / masses[m][i, j, k] - ubar
                    _exchange_matrix(a, th, sv, K, dt, n, None)
                    solve_small(a, b, n)
                    for m in range(n):
                        mom_out[m][i, j, k, c] = (ubar + b[m]) * masses[m][i, j, k]
                tbar = 0.0
                for m in range(n):
                    tbar += engs[m][i, j, k]
                tbar /= esum
                for m in range(n):
                    b[m] = engs[m][i, j, k] / (masses[m][i, j, k] * cvv[m]) - tbar
                _exchange_matrix(a, th, sv, H, dt, n, cvv)
                solve_small(a, b, n)
                for m in range(n):
                    eng_out[m][i, j, k] = (tbar + b[m]) * masses[m][i, j, k] * cvv[m]


@njit(cache=True, error_model="numpy")
def _exchange_cells2(masses, moms, engs, vfs, sps, cvs, mom_out, eng_out, lo, hi, dt, K, H):
    """exchange_cells for two materials over rows, the 2 x 2 solves written out (same operations)."""
    nk = hi[2] - lo[2]
    k0 = lo[2]
    cv0, cv1 = cvs[0], cvs[1]
    for i in range(lo[0], hi[0]):
        for j in range(lo[1], hi[1]):
            m0, m1 = masses[0][i, j, k0:k0 + nk], masses[1][i, j, k0:k0 + nk]
            p0, p1 = moms[0][i, j, k0:k0 + nk], moms[1][i, j, k0:k0 + nk]
            e0, e1 = engs[0][i, j, k0:k0 + nk], engs[1][i, j, k0:k0 + nk]
            f0, f1 = vfs[0][i, j, k0:k0 + nk], vfs[1][i, j, k0:k0 + nk]
            s0, s1 = sps[0][i, j, k0:k0 + nk], sps[1][i, j, k0:k0 + nk]
            q0, q1 = mom_out[0][i, j, k0:k0 + nk], mom_out[1][i, j, k0:k0 + nk]
            g0, g1 = eng_out[0][i, j, k0:k0 + nk], eng_out[1][i, j, k0:k0 + nk]
            for k in range(nk):
                msum = m0[k] + m1[k]
                esum = m0[k] * cv0 + m1[k] * cv1
                a00, a01, fr, a11 = _factor2(f0[k], f1[k], s0[k], s1[k], K[0, 1], K[1, 0], dt, 1.0, 1.0, False)
                for c in range(3):
                    ubar = (p0[k, c] + p1[k, c]) / msum
                    x0, x1 = _back2(p0[k, c] / m0[k] - ubar, p1[k, c] / m1[k] - ubar, a00, a01, fr, a11)
                    q0[k, c] = (ubar + x0) * m0[k]
                    q1[k, c] = (ubar + x1) * m1[k]
                tbar = (e0[k] + e1[k]) / esum
                x0, x1 = _solve2(e0[k] / (m0[k] * cv0) - tbar, e1[k] / (m1[k] * cv1) - tbar, f0[k], f1[k], s0[k],
                                 s1[k], H[0, 1], H[1, 0], dt, cv0, cv1, True)
                g0[k] = (tbar + x0) * m0[k] * cv0
                g1[k] = (tbar + x1) * m1[k] * cv1


@njit(cache=True)
def sp_vol_lagrangian_one(mass_L, sp_vol, vf, cs, delP, out, lo, hi, vol):
    """Eq. 40 for one material: (m v)^L = m v - V theta kappa delP (f_theta = 1, no Tdot terms)."""
    for i in range(lo[0], hi[0]):
        for j in range(lo[1], hi[1]):
            for k in range(lo[2], hi[2]):
                v = sp_vol[i, j, k]
                kap = v / cs[i, j, k] ** 2
                out[i, j, k] = max(mass_L[i, j, k] * v - vol * vf[i, j, k] * kap * delP[i, j, k], TINY)


@njit(cache=True, error_model="numpy")
def sp_vol_lagrangian_many(masses, sps, vfs, css, delP, engs, temps_old, codes, params, cvs, gammas,
                           outs, lo, hi, vol, dt, press):
    """Eq. 40: (m v)^L = m v + V [-theta kappa delP + dt (theta beta Tdot - f_theta sum theta beta Tdot)],
    beta at the start-of-step temperature and v (Uintah's; TST's at v and the cell's pressure)."""
    n = len(masses)
    nk = hi[2] - lo[2]
    k0 = lo[2]
    tb = np.empty((n, nk))
    fth = np.empty((n, nk))
    ksum = np.empty(nk)
    bsum = np.empty(nk)
    for i in range(lo[0], hi[0]):
        for j in range(lo[1], hi[1]):
            for k in range(nk):
                ksum[k] = 0.0
                bsum[k] = 0.0
            for m in range(n):
                sp, vf, cs = sps[m][i, j, k0:k0 + nk], vfs[m][i, j, k0:k0 + nk], css[m][i, j, k0:k0 + nk]
                to, en, ms = temps_old[m][i, j, k0:k0 + nk], engs[m][i, j, k0:k0 + nk], masses[m][i, j, k0:k0 + nk]
                cv, g, ideal = cvs[m], gammas[m], codes[m] == IDEAL_GAS
                for k in range(nk):
                    v = sp[k]
                    th = vf[k]
                    fth[m, k] = th * v / cs[k] ** 2
                    ksum[k] += fth[m, k]
                    t_L = en[k] / (ms[k] * cv)
                    if ideal:       # beta at the start-of-step temperature (Uintah's getAlpha(temp_CC old))
                        beta = ideal_gas_alpha(1.0 / v, to[k], cv, g)
                    elif codes[m] == TST:       # Uintah's TST::getAlpha(v, p)
                        pm = params[m]
                        beta = tst_alpha(v, press[i, j, k0 + k], cv, pm[0], pm[1], pm[2], pm[3], pm[4])
                    else:
                        beta = eos_alpha(codes[m], params[m], 1.0 / v, to[k], cv, g)
                    tb[m, k] = th * beta * (t_L - to[k]) / dt
                    bsum[k] += tb[m, k]
            dp = delP[i, j, k0:k0 + nk]
            for m in range(n):
                sp, ms, out = sps[m][i, j, k0:k0 + nk], masses[m][i, j, k0:k0 + nk], outs[m][i, j, k0:k0 + nk]
                for k in range(nk):
                    src = -fth[m, k] * dp[k] + dt * (tb[m, k] - fth[m, k] / ksum[k] * bsum[k])
                    out[k] = max(ms[k] * sp[k] + vol * src, TINY)


@njit(cache=True, error_model="numpy")
def stable_dt(vel, speed_sound, dims, dx, lo, hi, comp, knob):
    """Uintah's 'aggressive' CFL limit: min over cells and the directions in dims of
    dx / (knob c + |u|) for one material (the caller multiplies by the CFL number).
    comp[d]: the velocity component along axis d (arrays seen with permuted axes)."""
    best = np.inf
    for i in range(lo[0], hi[0]):
        for j in range(lo[1], hi[1]):
            for k in range(lo[2], hi[2]):
                c = knob * speed_sound[i, j, k]
                u = vel[i, j, k]
                for d in range(3):
                    if dims[d]:
                        best = min(best, dx[d] / (c + abs(u[comp[d]])))
    return best


@njit(cache=True)
def stable_dt_swept(vel, speed_sound, sp_vol, cp, count_dirs, has_neighbours, dx, lo, hi, knob, conductivity,
                    viscosity, grav_vel):
    """Uintah's 'conservative' limit: min over cells of vol / (outflow volume swept per unit
    time through the cell's faces), each face moving at the face velocity plus the larger
    neighbouring sound speed (times knob), the neighbours' relative speed, sqrt(dx |g|) and a
    diffusion speed (the caller multiplies by the CFL number). Needs one ghost layer."""
    best = np.inf
    vol = dx[0] * dx[1] * dx[2]
    dx_length = np.sqrt(dx[0] * dx[0] + dx[1] * dx[1] + dx[2] * dx[2])
    for i in range(lo[0], hi[0]):
        for j in range(lo[1], hi[1]):
            for k in range(lo[2], hi[2]):
                diffusion_vel = max(conductivity * sp_vol[i, j, k] / cp, viscosity) / dx_length
                swept = 0.0
                for d in range(3):
                    if not count_dirs[d]:
                        continue
                    s = 1 if has_neighbours[d] else 0
                    il, jl, kl = i - s * (d == 0), j - s * (d == 1), k - s * (d == 2)
                    ir, jr, kr = i + s * (d == 0), j + s * (d == 1), k + s * (d == 2)
                    c = max(speed_sound[il, jl, kl], speed_sound[ir, jr, kr])
                    u_l, u_c, u_r = vel[il, jl, kl, d], vel[i, j, k, d], vel[ir, jr, kr, d]
                    spread = knob * c + abs(u_r - u_l) + grav_vel + diffusion_vel
                    area = vol / dx[d]
                    swept += max(0.0, (0.5 * (u_r + u_c) + spread) * area)
                    swept += max(0.0, -(0.5 * (u_l + u_c) - spread) * area)
                if swept > 0.0:
                    best = min(best, vol / swept)
    return best


@njit(cache=True)
def mach_number(vel, sound, out, lo, hi):
    """|u| / c, c the speedSound_CC of the step's equilibration (Uintah's computeMach)."""
    for i in range(lo[0], hi[0]):
        for j in range(lo[1], hi[1]):
            for k in range(lo[2], hi[2]):
                u = vel[i, j, k]
                out[i, j, k] = np.sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]) / sound[i, j, k]


@njit(cache=True)
def conserved_sums(rho, vel, temp, cv, vol, lo, hi, out):
    """out += [mass, kinetic energy, internal energy, momentum x, y, z] over cells [lo, hi)."""
    for i in range(lo[0], hi[0]):
        for j in range(lo[1], hi[1]):
            for k in range(lo[2], hi[2]):
                m = rho[i, j, k] * vol
                u0, u1, u2 = vel[i, j, k, 0], vel[i, j, k, 1], vel[i, j, k, 2]
                out[0] += m
                out[1] += 0.5 * m * (u0 * u0 + u1 * u1 + u2 * u2)
                out[2] += m * cv_at(cv, i, j, k) * temp[i, j, k]
                out[3] += m * u0
                out[4] += m * u1
                out[5] += m * u2


@njit(cache=True)
def upper_face_fluxes(rho, vel, temp, cv, vol, face_vel, d, lo, hi, shift, delt, out):
    """out -= delT u_face [m, KE, IE, m u] over the extra cells of the upper face in
    direction d (edges excluded): the boundary-flux part of Uintah's conservationTest."""
    a, b = (d + 1) % 3, (d + 2) % 3
    for p in range(lo[a], hi[a]):
        for q in range(lo[b], hi[b]):
            c = [0, 0, 0]
            c[d], c[a], c[b] = hi[d], p, q
            i, j, k = c[0], c[1], c[2]
            u_face = face_vel[i - shift[0], j - shift[1], k - shift[2]]
            m = rho[i, j, k] * vol
            u0, u1, u2 = vel[i, j, k, 0], vel[i, j, k, 1], vel[i, j, k, 2]
            w = delt * u_face * m
            out[0] -= w
            out[1] -= w * 0.5 * (u0 * u0 + u1 * u1 + u2 * u2)
            out[2] -= w * cv_at(cv, i, j, k) * temp[i, j, k]
            out[3] -= w * u0
            out[4] -= w * u1
            out[5] -= w * u2


@njit(cache=True)
def speed_sound_fill(sp_vol, temp, out, code, params, cv, gamma):
    """Uintah's initial speedSound_CC: c^2 = dp/drho + dp/de p / rho^2 at (rho_micro, T)."""
    for n in range(sp_vol.size):
        if sp_vol[n] <= 0.0:            # a ghost cell not filled yet
            out[n] = 0.0
            continue
        rho = 1.0 / sp_vol[n]
        p, dp_drho, dp_de = eos_press_eos(code, params, rho, temp[n], cv_at_flat(cv, n), gamma)
        out[n] = np.sqrt(max(dp_drho + dp_de * p / (rho * rho), TINY))


@njit(cache=True)
def press_fill(rho_micro, temp, out, code, params, cv, gamma):
    """EOS pressure p(rho_micro, T) for flat arrays (initial condition)."""
    for n in range(rho_micro.size):
        out[n] = eos_press_eos(code, params, rho_micro[n], temp[n], cv_at_flat(cv, n), gamma)[0]


@njit(cache=True)
def rho_micro_fill(press, temp, out, guess, code, params, cv, gamma):
    """rho_micro(p, T) from the EOS for flat arrays (initial condition)."""
    for n in range(press.size):
        out[n] = eos_rho_micro(code, params, press[n], temp[n], cv_at_flat(cv, n), gamma, guess)


@njit(cache=True)
def stable_dt_diffusion_cells(cv, gamma, conductivity, viscosity, sp_vol, lo, hi, knob, inv_sum):
    """The diffusion limit 0.5 / (inv_sum D) of Uintah's aggressive delT with the cells' own
    cp = cv gamma, thermal conductivity and viscosity (knob_for_diffusion scaling both):
    D = max(k v / cp, mu v) per cell, the smallest limit over the cells lo..hi."""
    dt = np.inf
    for i in range(lo[0], hi[0]):
        for j in range(lo[1], hi[1]):
            for k in range(lo[2], hi[2]):
                cp = cv[i, j, k] * gamma[i, j, k]
                v = sp_vol[i, j, k]
                inv_thermal = cp / (v * knob * conductivity[i, j, k] + TINY)
                inv_kinematic = 1.0 / (knob * viscosity[i, j, k] * v + TINY)
                dt = min(dt, 0.5 * min(inv_thermal, inv_kinematic) / inv_sum)
    return dt


@njit(cache=True)
def diffusion_source(q, vf, coef, out, dims, lo, hi, dx, dt, vol):
    """Viscous / heat-conduction source (eqs. 8-9): out = dt V div(theta c grad q), per component.

    q is (..., ncomp), coef the cells' coefficient; face coefficients are harmonic means of
    theta c of the two cells (Uintah's q_flux_FC).
    """
    nc = q.shape[3]
    for i in range(lo[0], hi[0]):
        for j in range(lo[1], hi[1]):
            for k in range(lo[2], hi[2]):
                c0 = coef[i, j, k] * vf[i, j, k]
                for c in range(nc):
                    s = 0.0
                    for d in range(3):
                        if not dims[d]:
                            continue
                        di, dj, dk = (1, 0, 0) if d == 0 else ((0, 1, 0) if d == 1 else (0, 0, 1))
                        cp = coef[i + di, j + dj, k + dk] * vf[i + di, j + dj, k + dk]
                        cm = coef[i - di, j - dj, k - dk] * vf[i - di, j - dj, k - dk]
                        kp = 2.0 * c0 * cp / (c0 + cp + TINY)
                        km = 2.0 * c0 * cm / (c0 + cm + TINY)
                        s += (kp * (q[i + di, j + dj, k + dk, c] - q[i, j, k, c])
                              - km * (q[i, j, k, c] - q[i - di, j - dj, k - dk, c])) / (dx[d] * dx[d])
                    out[i, j, k, c] = dt * vol * s


@njit(cache=True)
def sutherland_viscosity(mu, temp, a, b, lo, hi):
    """Uintah's Sutherland model: mu = a sqrt(T) / (1 + b / T), T clamped to [300, 5000] K,
    in the cells lo..hi."""
    for i in range(lo[0], hi[0]):
        for j in range(lo[1], hi[1]):
            for k in range(lo[2], hi[2]):
                t = min(max(temp[i, j, k], 300.0), 5000.0)
                mu[i, j, k] = a * np.sqrt(t) / (1.0 + b / t)


@njit(cache=True)
def face_stress(vel, vf, mu, i, j, k, d, dims, dx, t):
    """t = tau . n_d, the Newtonian stress mu (grad v + grad v^T) - 2/3 mu (div v) I on the
    d-face between cells L = (i, j, k) - e_d and R = (i, j, k), as Uintah's computeTauX/Y/Z;
    mu: the cells' dynamic viscosity (Uintah's viscosity label).

    dv_c/dx_d = (v_R - v_L) / dx_d; across the face (e != d) the difference of the two edge
    means (each the mean of the 4 cells around the edge). Face viscosity: harmonic mean of
    theta mu of L and R. One-cell directions add no gradient.
    """
    di, dj, dk = (1, 0, 0) if d == 0 else ((0, 1, 0) if d == 1 else (0, 0, 1))
    il, jl, kl = i - di, j - dj, k - dk
    c0 = mu[i, j, k] * vf[i, j, k]
    c1 = mu[il, jl, kl] * vf[il, jl, kl]
    mf = 2.0 * c0 * c1 / (c0 + c1 + TINY)
    g = np.zeros((3, 3))                       # g[c, e] = dv_c / dx_e on the face
    for e in range(3):
        if not dims[e]:
            continue
        if e == d:
            for c in range(3):
                g[c, e] = (vel[i, j, k, c] - vel[il, jl, kl, c]) / dx[d]
        else:
            ei, ej, ek = (1, 0, 0) if e == 0 else ((0, 1, 0) if e == 1 else (0, 0, 1))
            q = 0.25 / dx[e]
            for c in range(3):
                g[c, e] = q * (vel[i + ei, j + ej, k + ek, c] - vel[i - ei, j - ej, k - ek, c]
                               + vel[il + ei, jl + ej, kl + ek, c] - vel[il - ei, jl - ej, kl - ek, c])
    div = g[0, 0] + g[1, 1] + g[2, 2]
    for c in range(3):
        t[c] = mf * (g[c, d] + g[d, c])
        if c == d:
            t[c] -= 2.0 / 3.0 * mf * div


@njit(cache=True)
def viscous_stress_source(vel, vf, mu, out, dims, lo, hi, dx, vol):
    """Newtonian viscous force out = V div(tau), Uintah's viscous_src_CC (viscousShearStress):
    each face stress (face_stress) is computed once and leaves L as it enters R
    (conservative). No bulk viscosity; no viscous heating (Uintah's ICE has none either).
    vel: Uintah's velTau_CC (vel_tau_boundary on the domain's faces)."""
    t = np.zeros(3)
    for i in range(lo[0], hi[0]):
        for j in range(lo[1], hi[1]):
            for k in range(lo[2], hi[2]):
                out[i, j, k, 0] = 0.0
                out[i, j, k, 1] = 0.0
                out[i, j, k, 2] = 0.0
    for d in range(3):
        if not dims[d]:
            continue
        di, dj, dk = (1, 0, 0) if d == 0 else ((0, 1, 0) if d == 1 else (0, 0, 1))
        f = vol / dx[d]
        for i in range(lo[0], hi[0] + di):
            for j in range(lo[1], hi[1] + dj):
                for k in range(lo[2], hi[2] + dk):
                    face_stress(vel, vf, mu, i, j, k, d, dims, dx, t)
                    up = i < hi[0] and j < hi[1] and k < hi[2]          # R is interior
                    dn = i - di >= lo[0] and j - dj >= lo[1] and k - dk >= lo[2]    # L is interior
                    for c in range(3):
                        if up:
                            out[i, j, k, c] -= f * t[c]
                        if dn:
                            out[i - di, j - dj, k - dk, c] += f * t[c]


@njit(cache=True)
def tau_face(vel, vf, mu, tau, d, sh, flo, fhi, dims, dx):
    """Uintah's tau_X_FC / tau_Y_FC / tau_Z_FC diagnostic: face_stress on every face of
    direction d (face index f is the face below cell f + sh)."""
    t = np.zeros(3)
    for i in range(flo[0], fhi[0]):
        for j in range(flo[1], fhi[1]):
            for k in range(flo[2], fhi[2]):
                face_stress(vel, vf, mu, i + sh[0], j + sh[1], k + sh[2], d, dims, dx, t)
                for c in range(3):
                    tau[i, j, k, c] = t[c]


@njit(cache=True)
def vel_tau_boundary(vel, d, side, lo, hi, tlo, thi):
    """Uintah's velTau_CC on one domain face: the extra cell becomes 2 v_ec - v_in, so that the
    face value (v_in + v_tau) / 2 is the boundary value v_ec and a wall's gradient is taken
    over half a cell (ICE::computeVelTau_CCFace). Along the face: cells tlo..thi (the
    domain's edge cells left out; ghost cells of neighbours and periodic images included, as
    Uintah's ghost exchange of velTau_CC gives them)."""
    e = lo[d] - 1 if side == 0 else hi[d]
    n = lo[d] if side == 0 else hi[d] - 1
    d1, d2 = (d + 1) % 3, (d + 2) % 3
    ijk = np.zeros(3, dtype=np.int64)
    for a in range(tlo[d1], thi[d1]):
        for b in range(tlo[d2], thi[d2]):
            ijk[d1], ijk[d2] = a, b
            for c in range(3):
                ijk[d] = e
                ve = vel[ijk[0], ijk[1], ijk[2], c]
                ijk[d] = n
                vi = vel[ijk[0], ijk[1], ijk[2], c]
                ijk[d] = e
                vel[ijk[0], ijk[1], ijk[2], c] = 2.0 * ve - vi


# -- optional conservative total energy (<conserveTotalEnergy>, a pysus extension) ---------------
@njit(cache=True)
def total_energy_lagrangian(rho, vel, temp, vf, sp_vol, one, px, py, pz, ux, uy, uz, shx, shy, shz, dims,
                            out, olo, ohi, lo, hi, vol, dx, dt, cv, g, use_g, code, params):
    """E^L = m (cv T + e_c(rho_micro) + |u|^2/2) - dt sum_faces A theta* p* u* (+ dt m u.g) of one material.

    The face work p* u* (face pressure of eq. 31 times the exchanged face velocity,
    donor-cell theta as in eq. 29) leaves one cell and enters its neighbour, so the
    sum over a closed domain (u* = 0 on its walls) is unchanged to round-off.
    e_c: the EOS's cold energy (eos_cold_energy; 0 for an ideal gas).
    """
    for i in range(olo[0], ohi[0]):
        for j in range(olo[1], ohi[1]):
            for k in range(olo[2], ohi[2]):
                m = rho[i, j, k] * vol
                u0, u1, u2 = vel[i, j, k, 0], vel[i, j, k, 1], vel[i, j, k, 2]
                e = cv_at(cv, i, j, k) * temp[i, j, k]
                if code != IDEAL_GAS:
                    e += eos_cold_energy(code, params, 1.0 / sp_vol[i, j, k])
                out[i, j, k] = m * (e + 0.5 * (u0 * u0 + u1 * u1 + u2 * u2))
    for i in range(lo[0], hi[0]):
        for j in range(lo[1], hi[1]):
            for k in range(lo[2], hi[2]):
                s = 0.0
                if dims[0]:
                    a, b, c = i - shx[0], j - shx[1], k - shx[2]
                    s += (px[a + 1, b, c] * _vflux(vf, ux[a + 1, b, c], i, j, k, 1, 0, 0, one)
                          - px[a, b, c] * _vflux(vf, ux[a, b, c], i - 1, j, k, 1, 0, 0, one)) / dx[0]
                if dims[1]:
                    a, b, c = i - shy[0], j - shy[1], k - shy[2]
                    s += (py[a, b + 1, c] * _vflux(vf, uy[a, b + 1, c], i, j, k, 0, 1, 0, one)
                          - py[a, b, c] * _vflux(vf, uy[a, b, c], i, j - 1, k, 0, 1, 0, one)) / dx[1]
                if dims[2]:
                    a, b, c = i - shz[0], j - shz[1], k - shz[2]
                    s += (pz[a, b, c + 1] * _vflux(vf, uz[a, b, c + 1], i, j, k, 0, 0, 1, one)
                          - pz[a, b, c] * _vflux(vf, uz[a, b, c], i, j, k - 1, 0, 0, 1, one)) / dx[2]
                out[i, j, k] -= dt * vol * s
                if use_g:
                    m = rho[i, j, k] * vol
                    out[i, j, k] += dt * m * (vel[i, j, k, 0] * g[0] + vel[i, j, k, 1] * g[1] + vel[i, j, k, 2] * g[2])


@njit(cache=True)
def share_total_energy(masses, moms, engs, cvs, tots_in, tots_out, olo, ohi, lo, hi):
    """Several materials: each material's total energy is its own m (e + |u|^2/2) (ICE's
    internal energy and momentum: eqs. 35-39 decide how energy splits among materials),
    plus a share m_m cv_m / sum(m cv) of the cell's difference between the conserved
    mixture total sum(tots_in) and sum of m (e + |u|^2/2). The difference (what the
    internal-energy form loses: kinetic energy destroyed by exchange and advection, work
    not matching p dV) thus heats every material of the cell by the same dT, and the sum
    over materials equals sum(tots_in) to round-off. Extra cells: no share."""
    n = len(masses)
    for i in range(olo[0], ohi[0]):
        for j in range(olo[1], ohi[1]):
            for k in range(olo[2], ohi[2]):
                inner = lo[0] <= i < hi[0] and lo[1] <= j < hi[1] and lo[2] <= k < hi[2]
                target = 0.0
                have = 0.0
                heat = 0.0
                for m in range(n):
                    ms = masses[m][i, j, k]
                    p0, p1, p2 = moms[m][i, j, k, 0], moms[m][i, j, k, 1], moms[m][i, j, k, 2]
                    own = engs[m][i, j, k] + 0.5 * (p0 * p0 + p1 * p1 + p2 * p2) / ms
                    tots_out[m][i, j, k] = own
                    target += tots_in[m][i, j, k]
                    have += own
                    heat += ms * cvs[m]
                if inner:
                    dT = (target - have) / heat
                    for m in range(n):
                        tots_out[m][i, j, k] += dT * masses[m][i, j, k] * cvs[m]


@njit(cache=True, error_model="numpy")
def lagrangian_to_primitive(mass, mom, eng, cv, vel, temp, lo, hi):
    """vel = mom_L / mass_L, T = int_eng_L / (mass_L cv) in the cells lo..hi (extra cells too)."""
    for i in range(lo[0], hi[0]):
        for j in range(lo[1], hi[1]):
            for k in range(lo[2], hi[2]):
                for c in range(3):
                    vel[i, j, k, c] = mom[i, j, k, c] / mass[i, j, k]
                temp[i, j, k] = eng[i, j, k] / (mass[i, j, k] * cv_at(cv, i, j, k))


@njit(cache=True, error_model="numpy")
def primitive_to_lagrangian(mass, vel, temp, cv, mom, eng, lo, hi):
    """mom_L_ME = vel mass_L, int_eng_L_ME = T cv mass_L in the cells lo..hi (Uintah's order)."""
    for i in range(lo[0], hi[0]):
        for j in range(lo[1], hi[1]):
            for k in range(lo[2], hi[2]):
                for c in range(3):
                    mom[i, j, k, c] = vel[i, j, k, c] * mass[i, j, k]
                eng[i, j, k] = temp[i, j, k] * cv_at(cv, i, j, k) * mass[i, j, k]
