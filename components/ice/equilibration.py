"""Eq. 13 of paper 000 for several materials of any EOS: the equilibration pressure by Newton
per cell (ICE's computeEquilibrationPressure; MPMICE's step 2 over solids and fluids, each solid
with its constitutive model's EOS as Uintah's computePressEOSCM: eos.py's SOLID_UCNH .. SOLID_JWLPP,
a visco_scram solid's JWL SOLID_JWL, or ICE's Murnaghan with n = 1 for rmpmice's unscaled
prescribed solids: mpmice/setup.py).

The first Newton iteration runs a row of cells at a time in loops that vectorize; the
Murnaghan n = 1 EOS skips its powers of 1 and 0; the round-off cycle of a cell full of a stiff
solid is recognised instead of iterated to max_iter. Each cell still does the plain per-cell
iteration's operations in the same order (tests/mpmice/test_kernels_bitwise.py compares them).
"""
from __future__ import annotations

import numpy as np
from numba import njit

from components.ice.eos import (IDEAL_GAS, MURNAGHAN, SOLID_HYPER, SOLID_UCNH, THOMSEN_HARTKA, _dp_dtemp, eos_press_eos,
                                eos_rho_micro, eos_sound_speed2, ideal_gas_press_eos, ideal_gas_rho_micro,
                                murnaghan_press_eos)
from components.ice.kernels import TINY


@njit(cache=True)
def _press_eos(code, params, m, rho, temp, cv, gamma):
    """eos_press_eos of material m (row m of params, read in place), with the ideal gas
    called directly and the solids' Murnaghan n = 1 (setup.py) without its powers of 1
    and 0 (x ** 1 = x and x ** 0 = 1 exactly): bitwise the same values."""
    if code == IDEAL_GAS:
        return ideal_gas_press_eos(rho, temp, cv, gamma)
    if code == MURNAGHAN and params[m, 1] == 1.0:
        K, rho0, P0 = params[m, 0], params[m, 2], params[m, 3]
        if rho >= rho0:
            return P0 + (1.0 / K) * (rho / rho0 - 1.0), 1.0 / (K * rho0), 0.0
        return murnaghan_press_eos(rho, K, 1.0, rho0, P0)
    return eos_press_eos(code, params[m], rho, temp, cv, gamma)


@njit(cache=True)
def _rho_micro(code, params, m, press, temp, cv, gamma, rho_guess):
    """eos_rho_micro of material m, the ideal gas and Murnaghan n = 1 above P0 directly
    (bitwise the same)."""
    if code == IDEAL_GAS:
        return ideal_gas_rho_micro(press, temp, cv, gamma)
    if code == MURNAGHAN and params[m, 1] == 1.0 and press >= params[m, 3]:
        return params[m, 2] * (params[m, 0] * (press - params[m, 3]) + 1.0)
    return eos_rho_micro(code, params[m], press, temp, cv, gamma, rho_guess)


@njit(cache=True, error_model="numpy")
def _eos_row(code, params, m, rm, t, cv, gamma, pe, dpr):
    """_press_eos of material m over a row of cells: the ideal gas, Murnaghan n = 1 at rho >= rho0
    and the solids' SOLID_UCNH / SOLID_HYPER curves (eos.py, the same operations) in loops that
    vectorize; the rest (the low branches' powers) per cell."""
    nk = rm.shape[0]
    if code == IDEAL_GAS:
        for c in range(nk):
            pe[c], dpr[c], _ = ideal_gas_press_eos(rm[c], t[c], cv, gamma)
    elif code == MURNAGHAN and params[m, 1] == 1.0:
        K, rho0, P0 = params[m, 0], params[m, 2], params[m, 3]
        low = 0
        for c in range(nk):
            pe[c] = P0 + (1.0 / K) * (rm[c] / rho0 - 1.0)
            dpr[c] = 1.0 / (K * rho0)
            low += not rm[c] >= rho0
        if low:
            for c in range(nk):
                if not rm[c] >= rho0:
                    pe[c], dpr[c], _ = murnaghan_press_eos(rm[c], K, 1.0, rho0, P0)
    elif code == SOLID_UCNH or code == SOLID_HYPER:
        K, rho0, p_ref, modified = params[m, 0], params[m, 1], params[m, 2], params[m, 3] != 0.0
        low = 0
        if code == SOLID_UCNH:
            for c in range(nk):
                J = rho0 / rm[c]
                pe[c] = p_ref - 0.5 * K * (J - 1.0 / J)
                dpr[c] = 0.5 * K * (1.0 + J * J) / rho0
                low += rm[c] < rho0
        else:
            inv_rho0 = 1.0 / rho0
            for c in range(nk):
                pe[c] = p_ref + 0.5 * K * (rm[c] * inv_rho0 - rho0 / rm[c])
                dpr[c] = 0.5 * K * (rho0 / (rm[c] * rm[c]) + inv_rho0)
                low += rm[c] < rho0
        if modified and low:
            for c in range(nk):
                if rm[c] < rho0:
                    pe[c], dpr[c], _ = eos_press_eos(code, params[m], rm[c], t[c], cv, gamma)
    else:
        for c in range(nk):
            pe[c], dpr[c], _ = eos_press_eos(code, params[m], rm[c], t[c], cv, gamma)


@njit(cache=True, error_model="numpy")
def _rho_micro_row(code, params, m, p, t, cv, gamma, rm):
    """_rho_micro of material m over a row of cells (rm: the guess in, the result out)."""
    nk = rm.shape[0]
    if code == IDEAL_GAS:
        for c in range(nk):
            rm[c] = ideal_gas_rho_micro(p[c], t[c], cv, gamma)
    elif code == MURNAGHAN and params[m, 1] == 1.0:
        K, rho0, P0 = params[m, 0], params[m, 2], params[m, 3]
        low = 0
        for c in range(nk):
            hi = p[c] >= P0
            rm[c] = rho0 * (K * (p[c] - P0) + 1.0) if hi else rm[c]
            low += not hi
        if low:
            for c in range(nk):
                if not p[c] >= P0:
                    rm[c] = eos_rho_micro(code, params[m], p[c], t[c], cv, gamma, rm[c])
    elif code == SOLID_UCNH or code == SOLID_HYPER:
        K, rho0, p_ref, modified = params[m, 0], params[m, 1], params[m, 2], params[m, 3] != 0.0
        low = 0
        if code == SOLID_UCNH:
            for c in range(nk):
                p_g = p[c] - p_ref
                rm[c] = rho0 / K * (p_g + np.sqrt(K * K + p_g * p_g))
                low += p_g < 0.0
        else:
            for c in range(nk):
                g = (p[c] - p_ref) / K
                rm[c] = rho0 * (g + np.sqrt(g * g + 1.0))
                low += g < 0.0
        if modified and low:
            for c in range(nk):
                if p[c] - p_ref < 0.0:
                    rm[c] = eos_rho_micro(code, params[m], p[c], t[c], cv, gamma, rm[c])
    else:
        for c in range(nk):
            rm[c] = eos_rho_micro(code, params[m], p[c], t[c], cv, gamma, rm[c])


# Uintah's MPMICE: an iterate below 100 DBL_EPSILON is replaced by |dp|; the binary search's
# tolerance on |1 - sum theta| and its bracket [DBL_EPSILON, 1/DBL_EPSILON]
DBL_EPSILON = 2.220446049250313e-16
UINTAH_CONVERGENCE = 100.0 * DBL_EPSILON


@njit(cache=True, inline="always")
def _next_iterate(p, dp, uintah_mpmice):
    """p + dp, kept positive: pysus's ICE takes a tenth of p where p + dp < p/10 (an ideal gas's
    Newton step overshoots to p < 0 once the root is below p/2); Uintah's MPMICE takes |dp| where
    p + dp < 100 DBL_EPSILON (MPMICE::computeEquilibrationPressure; ICE's own has no such clamp
    and stops the run where the iterate ends below 0)."""
    pn = p + dp
    if uintah_mpmice:
        return abs(dp) if pn < UINTAH_CONVERGENCE else pn
    return 0.1 * p if p > 0.0 and pn < 0.1 * p else pn


@njit(cache=True, error_model="numpy")
def _theta_sum(c, press, R, T, RM, codes, params, cvs, gammas, rm_out):
    """sum_m rho_m / rho_micro_m(press) of cell c (rm_out[m]: those densities; RM the guesses)."""
    s = 0.0
    for m in range(R.shape[0]):
        rm_out[m] = _rho_micro(codes[m], params, m, press, T[m, c], cvs[m], gammas[m], RM[m, c])
        s += R[m, c] / rm_out[m]
    return s


@njit(cache=True, error_model="numpy")
def _binary_search_cell(c, p_old, P, R, T, RM, PE, DP, codes, params, cvs, gammas, max_iter, rm, rm_l, rm_r):
    """Uintah's MPMICE::binaryPressureSearch for a cell whose Newton iteration ran out of iterations
    without converging: from the old pressure, Pm evaluated each pass, the bracket [Pleft, Pright]
    starting at [DBL_EPSILON, 1/DBL_EPSILON] halved by the sign of (1 - sum_R)(1 - sum_L), until
    |1 - sum theta(Pm)| <= 100 DBL_EPSILON; unconverged after max_iter passes, as Uintah's, the
    next Pm with the densities of the last one evaluated. Returns the passes."""
    n = R.shape[0]
    pm = p_old
    p_left = p_right = p_temp = 0.0
    count = 0
    converged = False
    while count < max_iter and not converged:
        count += 1
        s = _theta_sum(c, pm, R, T, RM, codes, params, cvs, gammas, rm)
        for m in range(n):
            RM[m, c] = rm[m]
        if abs(1.0 - s) <= UINTAH_CONVERGENCE:
            converged = True
            P[c] = pm
        if count == 1:
            p_left = DBL_EPSILON
            p_right = 1.0 / DBL_EPSILON
            p_temp = 0.5 * (p_left + p_right)
        s_r = _theta_sum(c, p_right, R, T, RM, codes, params, cvs, gammas, rm_r)
        s_l = _theta_sum(c, p_left, R, T, RM, codes, params, cvs, gammas, rm_l)
        if (1.0 - s_r) * (1.0 - s_l) < 0.0:
            p_temp = p_left
            p_left = 0.5 * (p_left + p_right)
        else:
            p_right = p_left
            p_left = p_temp
            p_left = 0.5 * (p_left + p_right)
        pm = 0.5 * (p_left + p_right)
    if not converged:
        P[c] = pm
    for m in range(n):
        PE[m, c], DP[m, c], _ = _press_eos(codes[m], params, m, RM[m, c], T[m, c], cvs[m], gammas[m])
    return count


@njit(cache=True, error_model="numpy")
def _newton_cell(c, P, R, T, RM, PE, DP, codes, params, cvs, gammas, tol, max_iter, rm1, rm2, uintah_mpmice):
    """Iterations 2.. of one cell of equilibrate (its state after iteration 1 in P, RM, PE,
    DP column c): the plain per-cell Newton loop, with the round-off cycle taken at once. Returns
    the iteration count and whether it converged (or cycled)."""
    n = RM.shape[0]
    p = P[c]
    p1 = p
    p2 = np.nan
    for m in range(n):
        rm1[m] = RM[m, c]
    it = 1
    while it < max_iter:
        it += 1
        A = 0.0
        B = 0.0
        C = 0.0
        for m in range(n):
            A += R[m, c] / RM[m, c]
            y = max(DP[m, c], TINY) * RM[m, c] * RM[m, c] / R[m, c]
            B += (p - PE[m, c]) / y
            C += 1.0 / y
        dp = (A - 1.0 - B) / C
        p = _next_iterate(p, dp, uintah_mpmice)
        if uintah_mpmice and not p <= 1.0 / DBL_EPSILON:
            # |dp| grows without bound: Uintah's iterate goes on to inf and NaN and never converges, its
            # binary search (bracket up to 1/DBL_EPSILON) then starts from the old pressure
            P[c] = p
            return it, False
        for m in range(n):
            RM[m, c] = _rho_micro(codes[m], params, m, p, T[m, c], cvs[m], gammas[m], RM[m, c])
            PE[m, c], DP[m, c], _ = _press_eos(codes[m], params, m, RM[m, c], T[m, c], cvs[m], gammas[m])
        if abs(dp) <= tol * abs(p) + 1e-300 and abs(A - 1.0) < 1e-9:
            P[c] = p
            return it, True
        same = p == p2
        for m in range(n):
            same = same and RM[m, c] == rm2[m]
        if same:
            # the iterate repeats the one two iterations back (a stiff solid's round-off
            # cycle): it alternates between two states to max_iter; take the one it ends on
            if (max_iter - it) % 2 == 1:
                p = p1
                for m in range(n):
                    RM[m, c] = rm1[m]
                    PE[m, c], DP[m, c], _ = _press_eos(codes[m], params, m, RM[m, c], T[m, c], cvs[m], gammas[m])
            P[c] = p
            return max_iter, True
        p2 = p1
        p1 = p
        for m in range(n):
            rm2[m] = rm1[m]
            rm1[m] = RM[m, c]
    P[c] = p
    return it, False


@njit(cache=True, error_model="numpy")
def equilibrate(rhos, temps, sp_old, p_guess, sp_new, vfs, css, press, codes, params, cvs, gammas,
                lo, hi, tol, max_iter, uintah_mpmice=False):
    """Step 2, eq. 13 over solids and fluids by Newton per cell: p with sum_m rho_m / rho_micro_m(p, T_m) = 1, dp = (sum theta - 1 -
    sum Q_m/y_m) / sum 1/y_m, Q_m = p - p_eos_m, y_m = (dp/drho)_m rho_micro_m^2 / rho_m.

    Arrays are seen with the collapsed axes first (ICE's Boxes.view) and taken a row along
    the last axis at a time: the first iteration, where almost every cell converges, runs
    for the whole row in loops over the cells that vectorize (_eos_row, _rho_micro_row);
    the cells that have not converged go on one at a time (_newton_cell), where an iterate
    that repeats the one two iterations back (cells full of a stiff solid, where dp never
    drops below tol p: one ulp of the solid's rho_micro moves p by ~1e-10 p) is known to
    alternate to max_iter, so the state it ends on is taken at once. The sound speed reuses
    the last (dp/drho)_T (Thomsen_Hartka_water and the MPM solids' codes: Uintah's c^2, as
    eos_sound_speed2). Every
    cell does the plain per-cell iteration's operations in its order: bitwise its results.
    uintah_mpmice: MPMICE's equilibration as Uintah's where the iterate would fall below 0 and
    where it does not converge (_next_iterate, _binary_search_cell); else pysus ICE's.
    Returns the largest iteration count (max_iter where a cell cycles)."""
    n = len(rhos)
    k0 = lo[2]
    nk = hi[2] - lo[2]
    R = np.empty((n, nk))
    T = np.empty((n, nk))
    RM = np.empty((n, nk))
    PE = np.empty((n, nk))
    DP = np.empty((n, nk))
    P = np.empty(nk)
    A = np.empty(nk)
    B = np.empty(nk)
    C = np.empty(nk)
    D = np.empty(nk)
    rm1 = np.empty(n)
    rm2 = np.empty(n)
    rm3 = np.empty(n)
    worst = 0
    for i in range(lo[0], hi[0]):
        for j in range(lo[1], hi[1]):
            for m in range(n):
                r_, t_, v_ = rhos[m][i, j, k0:k0 + nk], temps[m][i, j, k0:k0 + nk], sp_old[m][i, j, k0:k0 + nk]
                r, t, rm = R[m], T[m], RM[m]
                for c in range(nk):
                    r[c] = r_[c]
                    t[c] = t_[c]
                    rm[c] = 1.0 / v_[c]
                _eos_row(codes[m], params, m, RM[m], T[m], cvs[m], gammas[m], PE[m], DP[m])
            pg = p_guess[i, j, k0:k0 + nk]
            for c in range(nk):
                P[c] = pg[c]
            if max_iter >= 1:
                for c in range(nk):
                    A[c] = 0.0
                    B[c] = 0.0
                    C[c] = 0.0
                for m in range(n):
                    r, rm, pe, dpr = R[m], RM[m], PE[m], DP[m]
                    for c in range(nk):
                        A[c] += r[c] / rm[c]
                        y = max(dpr[c], TINY) * rm[c] * rm[c] / r[c]
                        B[c] += (P[c] - pe[c]) / y
                        C[c] += 1.0 / y
                for c in range(nk):
                    dp = (A[c] - 1.0 - B[c]) / C[c]
                    P[c] = _next_iterate(P[c], dp, uintah_mpmice)
                    D[c] = dp
                for m in range(n):
                    _rho_micro_row(codes[m], params, m, P, T[m], cvs[m], gammas[m], RM[m])
                    _eos_row(codes[m], params, m, RM[m], T[m], cvs[m], gammas[m], PE[m], DP[m])
                for c in range(nk):
                    if abs(D[c]) <= tol * abs(P[c]) + 1e-300 and abs(A[c] - 1.0) < 1e-9:
                        worst = max(worst, 1)
                    else:
                        it, done = _newton_cell(c, P, R, T, RM, PE, DP, codes, params, cvs, gammas, tol, max_iter,
                                                rm1, rm2, uintah_mpmice)
                        worst = max(worst, it)
                        if uintah_mpmice and not done:
                            _binary_search_cell(c, pg[c], P, R, T, RM, PE, DP, codes, params, cvs, gammas,
                                                max_iter, rm1, rm2, rm3)
            out = press[i, j, k0:k0 + nk]
            for c in range(nk):
                out[c] = P[c]
            for m in range(n):
                v_, f_, s_ = sp_new[m][i, j, k0:k0 + nk], vfs[m][i, j, k0:k0 + nk], css[m][i, j, k0:k0 + nk]
                r, t, rm, dpr = R[m], T[m], RM[m], DP[m]
                cv, g, code = cvs[m], gammas[m], codes[m]
                prm = params[m]
                for c in range(nk):
                    v_[c] = 1.0 / rm[c]
                    f_[c] = r[c] / rm[c]
                    if code == THOMSEN_HARTKA or code >= SOLID_UCNH:      # Uintah's c^2 (eos_sound_speed2)
                        s_[c] = np.sqrt(max(eos_sound_speed2(code, prm, rm[c], t[c], cv, g), TINY))
                        continue
                    dpdt = _dp_dtemp(code, prm, rm[c], t[c], cv, g)
                    s_[c] = np.sqrt(max(dpr[c] + t[c] * dpdt * dpdt / (rm[c] * rm[c] * cv), TINY))
    return worst
