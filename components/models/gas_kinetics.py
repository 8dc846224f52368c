"""Numba kernels of the gasCombustion model: NASA-7 thermodynamics, reaction rates and the
constant-volume chemistry sub-integration of one cell, and the mixture's transport properties.

The sub-integration follows Uintah's gasCombustion::computeModelSources operation by operation
(the same sub-steps, accepted and rejected, as sus). The rates are Uintah's ReactionMech's with
fewer transcendental calls (one exponential per forward and per reverse rate, from constants
that kinetics() makes once), so that a deck gives sus's numbers to round-off. `mech` is the
Kinetics tuple of a Mechanism (gas_mechanism.py): index k over all species, j over the tracked
ones (k without the closure). The hot kernels read its fields into locals and inline chem_rhs:
a call, or a field read inside a loop, counts references to each of its arrays, which cost more
than the rates themselves.
"""
from __future__ import annotations

from collections import namedtuple

import numpy as np
from numba import njit

from .gas_mechanism import FALLOFF, ELEMENTARY, P_ATM, RU, T_REF

LN10 = np.log(10.0)

Kinetics = namedtuple("Kinetics", "mw r_gas t_mid h_coef g_coef nasa h_ref rxn_type reactants products "
                                  "n_reac n_prod dn log_a beta ea_r sign_a troe troe_t2 tb_ptr tb_species tb_eff "
                                  "tb_default closure visc_fit cond_fit diff_fit mw_ratio phi_denom")

# chemistry step status codes (the task turns them into an error naming the cell)
OK, NEG_DENSITY, HARD_T, NEG_Y, BAD_SUM, NO_CONVERGENCE, NEWTON_FAILED = 0, 1, 2, 3, 4, 5, 6


def kinetics(mech) -> Kinetics:
    """The kernels' view of a Mechanism: each reaction's Arrhenius constants as log|A|, b, Ea/Ru
    (column 0 the rate, column 1 a falloff's low-pressure limit), its species counts and mole
    change, the third-body efficiencies as a sparse list of the species that differ from the
    default, and the Wilke rule's tables of molecular weight ratios."""
    mw = mech.mw
    ratio = (mw[None, :] / mw[:, None]) ** 0.25
    phi = np.sqrt(8.0 + 8.0 * mw[:, None] / mw[None, :])
    n_reac = np.count_nonzero(mech.reactants >= 0, axis=1)
    n_prod = np.count_nonzero(mech.products >= 0, axis=1)
    a = mech.arrhenius.reshape(-1, 2, 3)
    with np.errstate(divide="ignore"):
        log_a = np.log(np.abs(a[:, :, 0]))
    tb_ptr, tb_species, tb_eff = [0], [], []
    tb_default = np.ones(len(mech.rxn_type))
    for r, kind in enumerate(mech.rxn_type):
        if kind != ELEMENTARY:
            eff, default = mech.efficiencies[r], mech.eff_default[r]
            tb_default[r] = default
            for k in np.flatnonzero(eff != default):
                tb_species.append(k)
                tb_eff.append(eff[k] - default)
        tb_ptr.append(len(tb_species))
    return Kinetics(mw, mech.r_gas, mech.t_mid, mech.h_coef, mech.g_coef, mech.nasa, mech.h_ref, mech.rxn_type,
                    mech.reactants, mech.products, n_reac, n_prod, (n_prod - n_reac).astype(float),
                    np.ascontiguousarray(log_a), np.ascontiguousarray(a[:, :, 1]),
                    np.ascontiguousarray(a[:, :, 2] / RU), np.sign(a[:, :, 0]), mech.troe, mech.troe_t2,
                    np.array(tb_ptr, np.int64), np.array(tb_species, np.int64), np.array(tb_eff, float), tb_default,
                    mech.closure, mech.visc_fit, mech.cond_fit, mech.diff_fit, ratio, phi)


@njit(cache=True, inline="always", error_model="numpy")
def _range(t, t_mid):
    return 1 if t > t_mid else 0


@njit(cache=True, inline="always", error_model="numpy")
def _cp_poly(a, i, k, t, t2, t3, t4):
    """cp_k / R_k, the NASA-7 polynomial of range i (a: Kinetics.nasa)."""
    return a[i, k, 0] + a[i, k, 1] * t + a[i, k, 2] * t2 + a[i, k, 3] * t3 + a[i, k, 4] * t4


@njit(cache=True, inline="always", error_model="numpy")
def _h_poly(h, i, k, t, t2, t3, t4, t5):
    """h_k / R_k (K) of range i from the NASA-7 enthalpy coefficients a0, a1/2, .., a4/5, a5 (h: Kinetics.h_coef)."""
    return (h[i, k, 0] * t) + (h[i, k, 1] * t2) + (h[i, k, 2] * t3) + (h[i, k, 3] * t4) + (h[i, k, 4] * t5) + h[i, k, 5]


@njit(cache=True, inline="always", error_model="numpy")
def _h_over_r(mech, k, t):
    """h_k / R_k (K)."""
    t2 = t * t
    t3 = t2 * t
    t4 = t3 * t
    return _h_poly(mech.h_coef, _range(t, mech.t_mid), k, t, t2, t3, t4, t4 * t)


@njit(cache=True, inline="always", error_model="numpy")
def energy_molar(mech, k, t):
    """u_k = h_k - Ru T, J/mol."""
    return RU * (_h_over_r(mech, k, t) - t)


# The loops below read the mechanism's fields into locals first: a field read (or a call with
# mech) inside a loop counts a reference to each array it touches, every iteration.

@njit(cache=True, inline="always", error_model="numpy")
def sensible_energy(mech, t, y):
    """e_s(T, Y) = sum_k Y_k (h_s,k(T) - R_k (T - T_REF)), J/kg: the energy ICE carries for the gas."""
    h, r_gas, h_ref = mech.h_coef, mech.r_gas, mech.h_ref
    i = _range(t, mech.t_mid)
    t2 = t * t
    t3 = t2 * t
    t4 = t3 * t
    t5 = t4 * t
    e = 0.0
    for k in range(y.shape[0]):
        h_s = r_gas[k] * _h_poly(h, i, k, t, t2, t3, t4, t5) - h_ref[k]      # h_k(T) - h_k(T_REF), J/kg
        e += y[k] * (h_s - r_gas[k] * (t - T_REF))
    return e


@njit(cache=True, inline="always", error_model="numpy")
def cv_cp_r(mech, t, y):
    """The mixture's cp, R = sum Y_k R_k (J/(kg K))."""
    a, r_gas = mech.nasa, mech.r_gas
    i = _range(t, mech.t_mid)
    t2 = t * t
    t3 = t2 * t
    t4 = t3 * t
    cp = 0.0
    r = 0.0
    for k in range(y.shape[0]):
        cp += y[k] * r_gas[k] * _cp_poly(a, i, k, t, t2, t3, t4)
        r += y[k] * r_gas[k]
    return cp, r


@njit(cache=True, error_model="numpy")
def temperature_from_energy(mech, e_s, y, t_guess, t_low, t_high):
    """T with e_s(T, Y) = e_s: Newton from the guess clamped to the polynomials' range; (T, ok)."""
    a, r_gas = mech.nasa, mech.r_gas
    t = min(max(t_guess, t_low), t_high)
    for _ in range(50):
        f = sensible_energy(mech, t, y) - e_s
        i = _range(t, mech.t_mid)
        t2 = t * t
        t3 = t2 * t
        t4 = t3 * t
        cv = 0.0
        for k in range(y.shape[0]):
            cv += y[k] * r_gas[k] * (_cp_poly(a, i, k, t, t2, t3, t4) - 1.0)
        dt = f / cv
        t -= dt
        if abs(dt) < 1e-10 * t:
            return t, True
    return t, False


@njit(cache=True, inline="always", error_model="numpy")
def _exp(x):
    """exp(x), its underflow to 0 (Troe's T3 and T1 of 1e-30 K) without the library's slow path."""
    return np.exp(x) if x > -746.0 else 0.0


LOG_C0 = np.log(1e-6 * P_ATM / RU)     # ln of the standard concentration (mol/cm^3) times T


@njit(cache=True, inline="always", error_model="numpy")
def _rates(mech, t, log_t, inv_t, t2, t3, t4, conc, g, q, sdot):
    """Net rate of each reaction (mol/(cm^3 s)) with g = g_k / (Ru T) of every species: the forward
    rate exp(ln A + b ln T - Ea / (Ru T)) (Troe's falloff between its low- and high-pressure
    limits), the third bodies' concentration, and the reverse rate kf / Kc with
    Kc = exp(sum_R g - sum_P g) (1e-6 P_ATM / (Ru T))^dn, as one exponential of the sum; each
    rate added to the species' production rates sdot (mol/(cm^3 s)) as it is made."""
    i = _range(t, mech.t_mid)
    gc = mech.g_coef          # the fields as locals: each mech.<field> in a loop costs a reference count
    rxn_type, reactants, products, n_reac, n_prod, dn = (mech.rxn_type, mech.reactants, mech.products, mech.n_reac,
                                                         mech.n_prod, mech.dn)
    log_a, beta, ea_r, sign_a, troe, troe_t2 = mech.log_a, mech.beta, mech.ea_r, mech.sign_a, mech.troe, mech.troe_t2
    tb_ptr, tb_species, tb_eff, tb_default = mech.tb_ptr, mech.tb_species, mech.tb_eff, mech.tb_default
    tlog = 1.0 - log_t
    n = conc.shape[0]
    c_total = 0.0
    for k in range(n):
        g[k] = gc[i, k, 0] * tlog - gc[i, k, 1] * t - gc[i, k, 2] * t2 - gc[i, k, 3] * t3 - gc[i, k, 4] * t4 \
            + gc[i, k, 5] * inv_t - gc[i, k, 6]
        c_total += conc[k]
    log_c0 = LOG_C0 - log_t
    for r in range(rxn_type.shape[0]):
        kf = sign_a[r, 0] * np.exp(log_a[r, 0] + beta[r, 0] * log_t - ea_r[r, 0] * inv_t)
        kind = rxn_type[r]
        m = 1.0
        if kind != ELEMENTARY:
            m = tb_default[r] * c_total
            for p in range(tb_ptr[r], tb_ptr[r + 1]):
                m += tb_eff[p] * conc[tb_species[p]]
        if kind == FALLOFF:
            k0 = sign_a[r, 1] * np.exp(log_a[r, 1] + beta[r, 1] * log_t - ea_r[r, 1] * inv_t)
            pr = max(k0 * m / kf, 1e-300)
            log10_pr = np.log10(pr)
            fc = (1.0 - troe[r, 0]) * _exp(-t / troe[r, 1]) + troe[r, 0] * _exp(-t / troe[r, 2])
            if troe_t2[r]:
                fc += _exp(-troe[r, 3] * inv_t)
            log10_fc = np.log10(fc)
            cc = -0.4 - 0.67 * log10_fc
            nn = 0.75 - 1.27 * log10_fc
            sq = (log10_pr + cc) / (nn - 0.14 * (log10_pr + cc))
            kf = kf * pr * np.exp(LN10 * log10_fc / (1.0 + sq * sq)) / (1.0 + pr)
            m = 1.0
        dg = -dn[r] * log_c0
        fwd = kf
        for s in range(n_reac[r]):
            c = reactants[r, s]
            dg -= g[c]
            fwd *= conc[c]
        rev = kf
        for s in range(n_prod[r]):
            c = products[r, s]
            dg += g[c]
            rev *= conc[c]
        qr = m * (fwd - rev * np.exp(dg))
        q[r] = qr
        for s in range(n_reac[r]):
            sdot[reactants[r, s]] -= qr
        for s in range(n_prod[r]):
            sdot[products[r, s]] += qr


@njit(cache=True, error_model="numpy")
def rates_of_progress(mech, t, conc, g, q):
    """Net rate of each reaction (mol/(cm^3 s)) at T and the concentrations conc (mol/cm^3);
    g: scratch for the species' g_k / (Ru T)."""
    t2 = t * t
    _rates(mech, t, np.log(t), 1.0 / t, t2, t2 * t, t2 * t2, conc, g, q, np.zeros(conc.shape[0]))


@njit(cache=True, inline="always", error_model="numpy")
def chem_rhs(mech, t, y, rho, cell_vol, conc, g, q, u, sdot, rhs_mass):
    """Uintah's chemStep: dY_j/dt (rhs_mass, tracked order) and returns (dT/dt, q_dot V): the
    constant-volume reactor's right-hand side at (T, Y, rho). The heat release
    sum_r q_r (sum_R u_k - sum_P u_k) is summed as -sum_k u_k sdot_k. Inlined where it is
    called: a call would count references to each of the mechanism's arrays."""
    n = y.shape[0]
    i = _range(t, mech.t_mid)
    t2 = t * t
    t3 = t2 * t
    t4 = t3 * t
    t5 = t4 * t
    log_t = np.log(t)
    inv_t = 1.0 / t
    a, h, r_gas, mw = mech.nasa, mech.h_coef, mech.r_gas, mech.mw
    cp = 0.0
    r_mix = 0.0
    c_scale = 1e-3 * rho
    for k in range(n):
        ry = y[k] * r_gas[k]
        cp += ry * _cp_poly(a, i, k, t, t2, t3, t4)
        r_mix += ry
        conc[k] = c_scale * y[k] / mw[k]
        u[k] = RU * (_h_poly(h, i, k, t, t2, t3, t4, t5) - t)
        sdot[k] = 0.0
    _rates(mech, t, log_t, inv_t, t2, t3, t4, conc, g, q, sdot)
    qdot = 0.0
    j = 0
    inv_rho = 1e3 / rho
    for k in range(n):
        qdot -= u[k] * sdot[k]
        if k == mech.closure:
            continue
        rhs_mass[j] = mw[k] * sdot[k] * inv_rho
        j += 1
    qdot *= 1e6
    return qdot / (rho * (cp - r_mix)), qdot * cell_vol


@njit(cache=True, inline="always", error_model="numpy")
def _cell_y(y_tr, i, j, k, yt, y, closure):
    """Cell (i, j, k)'s mass fractions of all species into y (yt: scratch for the tracked ones)."""
    for s in range(yt.shape[0]):
        yt[s] = y_tr[s, i, j, k]
    _fill_y(y, yt, closure)


@njit(cache=True, error_model="numpy")
def _fill_y(y, y_tracked, closure):
    """All species' mass fractions from the tracked ones, the closure species 1 - their sum."""
    s = 0.0
    j = 0
    for k in range(y.shape[0]):
        if k == closure:
            continue
        y[k] = y_tracked[j]
        s += y_tracked[j]
        j += 1
    y[closure] = 1.0 - s


@njit(cache=True, error_model="numpy")
def chemistry_cells(mech, y_old, temp, rho, y_src, eng_src, dt_chem, limiter, hrr, lo, hi, dt, cell_vol,
                    rtol, atol_y, atol_t, safety, max_grow, max_shrink, t_warn, t_hard, do_chemistry):
    """Uintah's gasCombustion::computeModelSources over the cells [lo, hi): each cell's reactor
    integrated at constant volume over dt by the adaptive Heun-Euler pair (RK2(1), weighted RMS
    error of Y and T against rtol |y| + atol), the tracked species' increments added to y_src,
    rho V (e_s(T, Y) - e_s(T0, Y0)) to eng_src. Returns (status, i, j, k, value, warned): status
    OK or the first cell's failure, warned the number of cells outside the NASA-7 range."""
    n = mech.mw.shape[0]
    nt = n - 1
    cl = mech.closure
    y, y_start, y_orig = np.empty(n), np.empty(n), np.empty(n)
    y_pred, y_heun = np.empty(n), np.empty(n)
    conc, g, u, sdot = np.empty(n), np.empty(n), np.empty(n), np.empty(n)
    q = np.empty(mech.rxn_type.shape[0])
    k1, k2 = np.empty(nt), np.empty(nt)
    msrc = np.empty(nt)
    yt = np.empty(nt)
    warned = 0
    for i in range(lo[0], hi[0]):
        for jj in range(lo[1], hi[1]):
            for kk in range(lo[2], hi[2]):
                t = temp[i, jj, kk]
                rho_c = rho[i, jj, kk]
                if rho_c <= 0.0:
                    return NEG_DENSITY, i, jj, kk, rho_c, warned
                if t < t_warn[0] or t > t_warn[1]:
                    if t < t_hard[0] or t > t_hard[1]:
                        return HARD_T, i, jj, kk, t, warned
                    warned += 1
                _cell_y(y_old, i, jj, kk, yt, y, cl)
                ysum = 0.0
                for k in range(n):
                    if y[k] < -1e-15:
                        return NEG_Y, i, jj, kk, y[k], warned
                    ysum += y[k]
                if ysum > 1.1 or ysum < 0.0:
                    return BAD_SUM, i, jj, kk, ysum, warned
                h = dt
                tt = 0.0
                h_min = dt
                i_worst_min = -1
                eng_acc = 0.0
                for s in range(nt):
                    msrc[s] = 0.0
                t_start = t
                y_start[:] = y
                if do_chemistry:
                    while tt < dt:
                        if tt + h > dt:
                            h = dt - tt
                            if h <= 1e-15:
                                break
                        t_orig = t
                        y_orig[:] = y
                        accepted = False
                        e1_dt, e1_src = chem_rhs(mech, t_orig, y_orig, rho_c, cell_vol, conc, g, q, u, sdot, k1)
                        while not accepted and h > 1e-15:
                            ysum = 0.0
                            s = 0
                            for k in range(n):
                                if k == cl:
                                    continue
                                y_pred[k] = y_orig[k] + k1[s] * h
                                ysum += y_pred[k]
                                s += 1
                            y_pred[cl] = 1.0 - ysum
                            t_pred = t_orig + h * e1_dt
                            e2_dt, e2_src = chem_rhs(mech, t_pred, y_pred, rho_c, cell_vol, conc, g, q, u, sdot, k2)
                            ysum = 0.0
                            s = 0
                            for k in range(n):
                                if k == cl:
                                    continue
                                y_heun[k] = y_orig[k] + 0.5 * h * (k1[s] + k2[s])
                                ysum += y_heun[k]
                                s += 1
                            y_heun[cl] = 1.0 - ysum
                            t_heun = t_orig + 0.5 * h * (e1_dt + e2_dt)
                            err = 0.0
                            worst = 0.0
                            i_worst = -1
                            count = 0
                            for k in range(n):
                                if k == cl:
                                    continue
                                r = (y_heun[k] - y_pred[k]) / (rtol * abs(y_heun[k]) + atol_y)
                                err += r * r
                                if abs(r) > worst:
                                    worst = abs(r)
                                    i_worst = k
                                count += 1
                            r = (t_heun - t_pred) / (rtol * abs(t_heun) + atol_t)
                            err += r * r
                            if abs(r) > worst:
                                worst = abs(r)
                                i_worst = n
                            count += 1
                            err = np.sqrt(err / count)
                            fac = safety * max(err, 1e-300) ** -0.5
                            fac = min(max_grow, max(max_shrink, fac))
                            if err <= 1.0:
                                for s in range(nt):
                                    msrc[s] += 0.5 * h * (k1[s] + k2[s])
                                y[:] = y_heun
                                eng_acc += 0.5 * h * (e1_src + e2_src)
                                t = t_heun
                                if h < h_min:
                                    h_min = h
                                    i_worst_min = i_worst
                                tt += h
                                h *= fac
                                accepted = True
                            else:
                                h *= fac
                        if not accepted:
                            return NO_CONVERGENCE, i, jj, kk, t, warned
                dt_chem[i, jj, kk] = h_min
                limiter[i, jj, kk] = i_worst_min
                for s in range(nt):
                    y_src[s, i, jj, kk] += msrc[s]
                eng_src[i, jj, kk] += rho_c * cell_vol * (sensible_energy(mech, t, y) - sensible_energy(mech, t_start, y_start))
                hrr[i, jj, kk] = eng_acc / (cell_vol * dt)
    return OK, 0, 0, 0, 0.0, warned


def _over_cells(per_cell):
    """A kernel kernel(mech, y_tr, lo, hi, fields) that calls per_cell(mech, y, i, j, k, fields,
    work) in each cell (i, j, k) of [lo, hi), y the cell's mass fractions of all species and
    work (n + 3, n) scratch; it returns the first cell where per_cell returns False as
    (i, j, k), or (-1, 0, 0)."""
    @njit(cache=True, error_model="numpy")
    def kernel(mech, y_tr, lo, hi, fields):
        n = mech.mw.shape[0]
        y, yt = np.empty(n), np.empty(n - 1)
        work = np.empty((n + 3, n))
        for i in range(lo[0], hi[0]):
            for j in range(lo[1], hi[1]):
                for k in range(lo[2], hi[2]):
                    _cell_y(y_tr, i, j, k, yt, y, mech.closure)
                    if not per_cell(mech, y, i, j, k, fields, work):
                        return i, j, k
        return -1, 0, 0
    return kernel


@njit(cache=True, inline="always", error_model="numpy")
def _thermo_cell(mech, y, i, j, k, fields, work):
    """cv and gamma of the mixture (Uintah's modifyThermoTransportProperties); False where cv < 0.
    fields: (temp, cv, gamma)."""
    temp, cv, gamma = fields
    cp, r = cv_cp_r(mech, temp[i, j, k], y)
    c = cp - r
    if c < 0.0:
        return False
    cv[i, j, k] = c
    gamma[i, j, k] = cp / c
    return True


@njit(cache=True, inline="always", error_model="numpy")
def _transport_cell(mech, y, i, j, k, fields, work):
    """The mixture's viscosity (Wilke's rule), thermal conductivity (the mean of the mole-fraction
    weighted arithmetic and harmonic means) and, where diff has species, the mixture-averaged
    diffusion coefficients D_k = (M - X_k M_k) / (P M sum_j!=k X_j / D_jk), from the species'
    fits. fields: (temp, rho, mu, lam, diff)."""
    temp, rho, mu, lam, diff = fields
    n = y.shape[0]
    x, sv, dk, dbin = work[0], work[1], work[2], work[3:]
    mw = mech.mw
    t = temp[i, j, k]
    inv_mw = 0.0
    for s in range(n):
        inv_mw += y[s] / mw[s]
    for s in range(n):
        x[s] = y[s] / (inv_mw * mw[s])
    ln_t = np.log(t)
    ln_t2 = ln_t * ln_t
    ln_t3 = ln_t * ln_t2
    ln_t4 = ln_t * ln_t3
    t14 = np.sqrt(np.sqrt(t))
    visc_fit, cond_fit, mw_ratio, phi_denom = mech.visc_fit, mech.cond_fit, mech.mw_ratio, mech.phi_denom
    for s in range(n):
        sv[s] = t14 * (visc_fit[s, 0] + visc_fit[s, 1] * ln_t + visc_fit[s, 2] * ln_t2 + visc_fit[s, 3] * ln_t3
                       + visc_fit[s, 4] * ln_t4)
    m = 0.0
    for a in range(n):
        den = 0.0
        for b in range(n):
            tmp = 1.0 + (sv[a] / sv[b]) * mw_ratio[a, b]
            den += (tmp * tmp / phi_denom[a, b]) * x[b]
        m += x[a] * (sv[a] * sv[a]) / den
    mu[i, j, k] = m
    t12 = np.sqrt(t)
    arith = 0.0
    harm = 0.0
    for s in range(n):
        la = t12 * (cond_fit[s, 0] + cond_fit[s, 1] * ln_t + cond_fit[s, 2] * ln_t2 + cond_fit[s, 3] * ln_t3
                    + cond_fit[s, 4] * ln_t4)
        arith += x[s] * la
        harm += x[s] / la
    lam[i, j, k] = 0.5 * (arith + 1.0 / harm)
    if diff.shape[0] > 0:
        _mixture_diffusion(mech.r_gas, mw, mech.diff_fit, t, rho[i, j, k], y, x, dbin, dk)
        for s in range(n):
            diff[s, i, j, k] = dk[s]
    return True


@njit(cache=True, inline="always", error_model="numpy")
def _energy_cell(mech, y, i, j, k, fields, work):
    """e_s(T, Y), the specific energy ICE carries for the gas. fields: (temp, es)."""
    temp, es = fields
    es[i, j, k] = sensible_energy(mech, temp[i, j, k], y)
    return True


@njit(cache=True, inline="always", error_model="numpy")
def _temperature_cell(mech, y, i, j, k, fields, work):
    """T from e_s and Y (Uintah's computeTempFromSensibleEnergy, its guess T_REF + e_s / 1000);
    False where Newton's iteration fails. fields: (es, temp, t_low, t_high)."""
    es, temp, t_low, t_high = fields
    e = es[i, j, k]
    t, ok = temperature_from_energy(mech, e, y, T_REF + e / 1000.0, t_low, t_high)
    if ok:
        temp[i, j, k] = t
    return ok


@njit(cache=True, inline="always", error_model="numpy")
def _sound_cell(mech, y, i, j, k, fields, work):
    """cv, gamma and the speed of sound sqrt(gamma p / rho), p = rho R_mix T, of the mixture
    (Uintah's gasCombustion::initialize with <initProfile>); False where cv < 0.
    fields: (temp, rho, cv, gamma, speed_sound)."""
    temp, rho, cv, gamma, cs = fields
    t = temp[i, j, k]
    cp, r = cv_cp_r(mech, t, y)
    c = cp - r
    if c < 0.0:
        return False
    g = cp / c
    cv[i, j, k] = c
    gamma[i, j, k] = g
    cs[i, j, k] = np.sqrt(g * (rho[i, j, k] * r * t) / rho[i, j, k])
    return True


# kernel(mech, y_tr, lo, hi, fields) over the cells [lo, hi) -> the first failing cell or (-1, 0, 0)
sound_cells = _over_cells(_sound_cell)
thermo_cells = _over_cells(_thermo_cell)
transport_cells = _over_cells(_transport_cell)
energy_cells = _over_cells(_energy_cell)
temperature_cells = _over_cells(_temperature_cell)


@njit(cache=True, error_model="numpy")
def diffusion_sources(mech, y_tr, temp, rho, y_src, eng_src, dims, lo, hi, dx, dt):
    """The species' molecular diffusion added to y_src and eng_src over the cells [lo, hi)
    (Uintah's gasCombustion, doDiffusion): on each face the mixture-averaged fluxes
    j*_k = rho D_k (M_k / M) (-grad X_k) of the face's mean state, corrected to
    j_k = j*_k - Y_k sum j* so that they carry no net mass, and the enthalpy they carry
    sum_k j_k (h_s,k(T_L) + h_s,k(T_R)) / 2; then Y_k -= dt div j_k / rho, m e -= dt div(flux)."""
    n = mech.mw.shape[0]
    sh = temp.shape
    y_all = np.zeros((n,) + sh)
    x = np.zeros((n,) + sh)
    hs = np.zeros((n,) + sh)
    inv_mw = np.zeros(sh)
    yt, yc = np.empty(n - 1), np.empty(n)
    mw, r_gas, h_ref, h_coef, diff_fit = mech.mw, mech.r_gas, mech.h_ref, mech.h_coef, mech.diff_fit
    for i in range(sh[0]):
        for j in range(sh[1]):
            for k in range(sh[2]):
                _cell_y(y_tr, i, j, k, yt, yc, mech.closure)
                m = 0.0
                for s in range(n):
                    m += yc[s] / mw[s]
                inv_mw[i, j, k] = m
                t = temp[i, j, k]
                ir = _range(t, mech.t_mid)
                t2 = t * t
                t3 = t2 * t
                t4 = t3 * t
                t5 = t4 * t
                for s in range(n):
                    y_all[s, i, j, k] = yc[s]
                    x[s, i, j, k] = yc[s] / (m * mw[s])
                    hs[s, i, j, k] = r_gas[s] * _h_poly(h_coef, ir, s, t, t2, t3, t4, t5) - h_ref[s]
    jf = np.zeros((3, n) + sh)
    phi = np.zeros((3,) + sh)
    yf, dk, xf, dbin = np.empty(n), np.empty(n), np.empty(n), np.empty((n, n))
    jstar = np.empty(n)
    for d in range(3):
        if not dims[d]:
            continue
        hi_f = np.array([hi[0], hi[1], hi[2]])
        hi_f[d] += 1
        for i in range(lo[0], hi_f[0]):
            for j in range(lo[1], hi_f[1]):
                for k in range(lo[2], hi_f[2]):
                    li, lj, lk = i - (d == 0), j - (d == 1), k - (d == 2)
                    rho_f = 0.5 * (rho[li, lj, lk] + rho[i, j, k])
                    inv_f = 0.5 * (inv_mw[li, lj, lk] + inv_mw[i, j, k])
                    t_f = 0.5 * (temp[li, lj, lk] + temp[i, j, k])
                    for s in range(n):
                        yf[s] = 0.5 * (y_all[s, li, lj, lk] + y_all[s, i, j, k])
                    _mixture_diffusion(r_gas, mw, diff_fit, t_f, rho_f, yf, xf, dbin, dk)
                    tot = 0.0
                    for s in range(n):
                        grad = -(x[s, i, j, k] - x[s, li, lj, lk]) / dx[d]
                        jstar[s] = rho_f * dk[s] * mw[s] * inv_f * grad
                        tot += jstar[s]
                    flux = 0.0
                    for s in range(n):
                        js = jstar[s] - yf[s] * tot
                        jf[d, s, i, j, k] = js
                        flux += js * 0.5 * (hs[s, li, lj, lk] + hs[s, i, j, k])
                    phi[d, i, j, k] = flux
    area = np.array([dx[1] * dx[2], dx[0] * dx[2], dx[0] * dx[1]])
    vol = dx[0] * dx[1] * dx[2]
    for i in range(lo[0], hi[0]):
        for j in range(lo[1], hi[1]):
            for k in range(lo[2], hi[2]):
                t = 0
                for s in range(n):
                    if s == mech.closure:
                        continue
                    div = 0.0
                    if dims[0]:
                        div += (jf[0, s, i + 1, j, k] - jf[0, s, i, j, k]) * area[0]
                    if dims[1]:
                        div += (jf[1, s, i, j + 1, k] - jf[1, s, i, j, k]) * area[1]
                    if dims[2]:
                        div += (jf[2, s, i, j, k + 1] - jf[2, s, i, j, k]) * area[2]
                    y_src[t, i, j, k] -= div / vol * dt / rho[i, j, k]
                    t += 1
                dphi = 0.0
                if dims[0]:
                    dphi += (phi[0, i + 1, j, k] - phi[0, i, j, k]) * area[0]
                if dims[1]:
                    dphi += (phi[1, i, j + 1, k] - phi[1, i, j, k]) * area[1]
                if dims[2]:
                    dphi += (phi[2, i, j, k + 1] - phi[2, i, j, k]) * area[2]
                eng_src[i, j, k] -= dphi * dt


@njit(cache=True, error_model="numpy")
def _mixture_diffusion(r_gas, mw, diff_fit, t, rho, y, x, dbin, dk):
    """Mixture-averaged diffusion coefficients D_k (m^2/s) of a state (T, rho, Y) into dk
    (Uintah's ReactionMech::mixtureAvgDiffCoeffs), from the mechanism's r_gas, mw and diff_fit
    (three arrays, not the Kinetics tuple: a call counts a reference to each array it takes)."""
    n = y.shape[0]
    r_mix = 0.0
    for s in range(n):
        r_mix += y[s] * r_gas[s]
    inv_mw = 0.0
    for s in range(n):
        inv_mw += y[s] / mw[s]
    for s in range(n):
        x[s] = y[s] / (inv_mw * mw[s])
    m_mix = 1.0 / inv_mw
    p = rho * r_mix * t
    ln_t = np.log(t)
    ln_t2 = ln_t * ln_t
    ln_t3 = ln_t * ln_t2
    ln_t4 = ln_t * ln_t3
    t12 = np.sqrt(t)
    for a in range(n):
        for b in range(a + 1, n):
            v = t * t12 * (diff_fit[a, b, 0] + diff_fit[a, b, 1] * ln_t + diff_fit[a, b, 2] * ln_t2
                           + diff_fit[a, b, 3] * ln_t3 + diff_fit[a, b, 4] * ln_t4)
            dbin[a, b] = v
            dbin[b, a] = v
    for a in range(n):
        s_ = 0.0
        for b in range(n):
            if b != a:
                s_ += x[b] / dbin[b, a]
        dk[a] = (m_mix - x[a] * mw[a]) / (p * m_mix * s_)


@njit(cache=True, error_model="numpy")
def interpolate_profile(px, table, xq, out):
    """out[:, q] = each row of table at xq[q], linear between the rows of px that bracket it
    (std::lower_bound's), the first or last row outside px (Uintah's <initProfile>)."""
    n = px.shape[0]
    for q in range(xq.shape[0]):
        x = xq[q]
        if x <= px[0]:
            i, frac = 0, 0.0
        elif x >= px[n - 1]:
            i, frac = n - 2, 1.0
        else:
            i = np.searchsorted(px, x) - 1
            frac = (x - px[i]) / (px[i + 1] - px[i])
        for c in range(table.shape[0]):
            out[c, q] = table[c, i] + frac * (table[c, i + 1] - table[c, i])
