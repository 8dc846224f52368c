"""The fast kernels give bitwise the values of the plain ones they replace:
ice.equilibration.equilibrate against the per-cell Newton loop equilibrate_many below (solid
Murnaghan n = 1 + ideal gas, cells from empty to solid-filled, where the stiff solid's Newton
iterate cycles at round-off, and a third, JWL material; the solids' own EOS codes SOLID_UCNH and
SOLID_HYPER, with and without the modified EOS below rho0, in place of Murnaghan), and
kernels.nc_to_cc against a direct sum over the nodes."""
import numpy as np
from numba import njit

from components.ice.eos import (IDEAL_GAS, JWL, MAX_PARAMS, MURNAGHAN, SOLID_HYPER, SOLID_UCNH, eos_press_eos,
                                eos_rho_micro, eos_sound_speed2)
from components.ice.equilibration import equilibrate
from components.ice.kernels import TINY
from components.mpmice.kernels import nc_to_cc


@njit(cache=True)
def equilibrate_many(rhos, temps, sp_old, p_guess, sp_new, vfs, css, press, codes, params, cvs, gammas,
                     lo, hi, tol, max_iter):
    """The plain per-cell Newton iteration of eq. 13 (ICE's kernel before equilibration.py, kept
    here as the reference): find p with sum_m rho_m / rho_micro_m(p, T_m) = 1.

    Linearising theta_m(p) = rho_m/rho_micro_m about the current iterate gives
    dp = (sum theta - 1 - sum Q_m/y_m) / sum 1/y_m, Q_m = p - p_eos_m,
    y_m = (dp/drho)_m rho_micro_m^2 / rho_m. Returns the largest iteration count.
    """
    n = len(rhos)
    rm = np.empty(n)
    pe = np.empty(n)
    dpr = np.empty(n)
    dpe = np.empty(n)
    worst = 0
    for i in range(lo[0], hi[0]):
        for j in range(lo[1], hi[1]):
            for k in range(lo[2], hi[2]):
                p = p_guess[i, j, k]
                for m in range(n):
                    rm[m] = 1.0 / sp_old[m][i, j, k]
                    pe[m], dpr[m], dpe[m] = eos_press_eos(codes[m], params[m], rm[m], temps[m][i, j, k],
                                                          cvs[m], gammas[m])
                it = 0
                while it < max_iter:
                    it += 1
                    A = 0.0
                    B = 0.0
                    C = 0.0
                    for m in range(n):
                        th = rhos[m][i, j, k] / rm[m]
                        A += th
                        y = max(dpr[m], TINY) * rm[m] * rm[m] / rhos[m][i, j, k]
                        B += (p - pe[m]) / y
                        C += 1.0 / y
                    dp = (A - 1.0 - B) / C
                    pn = p + dp
                    if p > 0.0 and pn < 0.1 * p:
                        pn = 0.1 * p            # keep an ideal-gas iterate positive
                    p = pn
                    for m in range(n):
                        rm[m] = eos_rho_micro(codes[m], params[m], p, temps[m][i, j, k], cvs[m], gammas[m], rm[m])
                        pe[m], dpr[m], dpe[m] = eos_press_eos(codes[m], params[m], rm[m], temps[m][i, j, k],
                                                              cvs[m], gammas[m])
                    if abs(dp) <= tol * abs(p) + 1e-300 and abs(A - 1.0) < 1e-9:
                        break
                worst = max(worst, it)
                press[i, j, k] = p
                for m in range(n):
                    sp_new[m][i, j, k] = 1.0 / rm[m]
                    vfs[m][i, j, k] = rhos[m][i, j, k] / rm[m]
                    css[m][i, j, k] = np.sqrt(max(eos_sound_speed2(codes[m], params[m], rm[m], temps[m][i, j, k],
                                                                   cvs[m], gammas[m]), TINY))
    return worst


def _case(nmat, shape, seed):
    rng = np.random.default_rng(seed)
    p_ref = 101325.0
    codes = np.array([MURNAGHAN, IDEAL_GAS, JWL][:nmat], np.int64)
    params = np.zeros((nmat, MAX_PARAMS))
    params[0, :4] = (1.0 / 117e9, 1.0, 8900.0, p_ref)
    if nmat > 2:
        params[2, :6] = (5.24e11, 7.68e9, 4.2, 1.1, 0.34, 1900.0)
    cvs = np.array([452.0, 716.0, 1500.0][:nmat])
    gammas = np.array([1.0, 1.4, 1.0][:nmat])
    theta = rng.dirichlet(np.ones(nmat), size=shape)
    theta[..., 0] = np.where(rng.random(shape) < 0.3, 1.0 - 1e-10 * rng.random(shape), theta[..., 0])
    theta /= theta.sum(-1, keepdims=True)
    temps = tuple(np.full(shape, 300.0) + 50.0 * rng.random(shape) for _ in range(nmat))
    rm0 = [8900.0 * (1.0 + 1e-5 * rng.standard_normal(shape)), 1.18 * (1 + 0.1 * rng.random(shape)),
           1900.0 * (1 + 0.01 * rng.random(shape))][:nmat]
    rhos = tuple(theta[..., m] * rm0[m] for m in range(nmat))
    sp_old = tuple(1.0 / (rm0[m] * (1.0 + 1e-6 * rng.standard_normal(shape))) for m in range(nmat))
    guess = p_ref * (1.0 + 0.05 * rng.standard_normal(shape))
    return rhos, temps, sp_old, guess, codes, params, cvs, gammas


def _run(fn, case, shape):
    rhos, temps, sp_old, guess, codes, params, cvs, gammas = case
    out = [tuple(np.zeros(shape) for _ in rhos) for _ in range(3)]
    press = np.zeros(shape)
    it = fn(rhos, temps, sp_old, guess, out[0], out[1], out[2], press, codes, params, cvs, gammas,
            np.array([0, 1, 0], np.int64), np.array(shape, np.int64), 1e-11, 100)
    return it, press, out


def _assert_equilibrations_bitwise(case, shape):
    """equilibrate_many and the per-cell equilibrate give the same iterations and bits."""
    it_a, p_a, out_a = _run(equilibrate_many, case, shape)
    it_b, p_b, out_b = _run(equilibrate, case, shape)
    assert it_a == it_b
    assert np.array_equal(p_a, p_b)
    for qa, qb in zip(out_a, out_b):
        for a, b in zip(qa, qb):
            assert np.array_equal(a, b)


def test_equilibrate_is_bitwise_equilibrate_many():
    for nmat, seed, shape in ((2, 0, (1, 12, 9)), (2, 1, (3, 4, 9)), (3, 2, (1, 12, 9)), (2, 3, (12, 9, 1))):
        case = _case(nmat, shape, seed)
        _assert_equilibrations_bitwise(case, shape)


def test_equilibrate_is_bitwise_for_the_solid_codes():
    """The row loops of SOLID_UCNH and SOLID_HYPER (equilibration._eos_row, _rho_micro_row) are the
    per-cell EOS's operations: bitwise equilibrate_many's results, cells above and below rho0."""
    shape = (1, 12, 9)
    for code, modified, viscoscram in ((SOLID_UCNH, 0.0, 0.0), (SOLID_UCNH, 1.0, 0.0), (SOLID_HYPER, 0.0, 0.0),
                                       (SOLID_HYPER, 1.0, 1.0)):
        case = list(_case(2, shape, 5))
        case[4] = np.array([code, IDEAL_GAS], np.int64)
        case[5] = case[5].copy()
        case[5][0, :5] = (117e9, 8900.0, 101325.0, modified, viscoscram)
        _assert_equilibrations_bitwise(case, shape)


# cells of the steel block of scripts/bench/mpmice.py (solid-filled, a gas sliver): rho_solid, rho_gas,
# T_solid, T_gas, sp_vol_solid, sp_vol_gas, p_guess; their Newton iterates cycle at round-off to max_iter
CYCLING = [(8899.999577437935, 1.20790077051351e-10, 300.0, 315.0313973716029, 0.0001123595551234107,
            0.25525066418544223, 153257.19376506627),
           (8899.999564593787, 1.2078994256028216e-10, 300.0, 315.0421153456528, 0.00011235955509515628,
            0.2554004033855136, 153146.77698551523),
           (8899.999861601173, 1.1793090344985002e-12, 300.0, 299.27746769405235, 0.00011235955292647563,
            0.8549066821105387, 99998.1841601948),
           (8899.99976766591, 1.6119799582511763e-11, 300.0, 311.63486699033666, 0.0001123595529967104,
            0.32023656301992665, 138424.74790619206)]


def test_equilibrate_cycling_cells():
    shape = (1, 1, len(CYCLING) + 1)
    _, _, _, _, codes, params, cvs, gammas = _case(2, shape, 0)
    c = np.array(CYCLING + [CYCLING[0]]).reshape(shape + (7,))
    col = lambda q: np.ascontiguousarray(c[..., q])      # C arrays: the kernels' specialisations of the test above
    case = ((col(0), col(1)), (col(2), col(3)), (col(4), col(5)), col(6), codes, params, cvs, gammas)
    for max_iter in (100, 101):            # the cycle ends on either of its two states
        res = []
        for fn in (equilibrate_many, equilibrate):
            rhos, temps, sp_old, guess = case[:4]
            out = [tuple(np.zeros(shape) for _ in rhos) for _ in range(3)]
            press = np.zeros(shape)
            it = fn(rhos, temps, sp_old, guess, out[0], out[1], out[2], press, codes, params, cvs, gammas,
                    np.zeros(3, np.int64), np.array(shape, np.int64), 1e-11, max_iter)
            res.append((it, press, out))
        assert res[0][0] == res[1][0] == max_iter
        assert np.array_equal(res[0][1], res[1][1])
        for qa, qb in zip(res[0][2], res[1][2]):
            for a, b in zip(qa, qb):
                assert np.array_equal(a, b)


def test_nc_to_cc_is_the_weighted_node_sum():
    rng = np.random.default_rng(3)
    nn = (7, 6, 1)
    gm, gv = rng.random(nn) * (rng.random(nn) < 0.7), rng.random(nn)
    gu = rng.standard_normal(nn + (3,))
    dims = np.array([1, 1, 0], np.int64)      # MPMICE's dims_i: the production specialisation, not a second one
    sym_lo, sym_hi = np.array([1, 0, 0], np.bool_), np.zeros(3, np.bool_)
    node_low, cc_low = np.array([0, 2, 0], np.int64), np.array([-1, 1, 0], np.int64)
    n_lo, n_hi = np.array([0, 0, 0], np.int64), np.array([6, 10, 0], np.int64)
    shape = (8, 7, 1)
    lo, hi = np.array([1, 1, 0], np.int64), np.array([6, 6, 1], np.int64)
    cm, spv, rho = np.zeros(shape), np.zeros(shape), np.zeros(shape)
    vel = np.zeros(shape + (3,))
    tiny, rho0, vol = 1e-3, 2.0, 0.5
    nc_to_cc(gm, gv, gu, node_low, cc_low, lo, hi, dims, sym_lo, sym_hi, n_lo, n_hi, tiny, rho0, vol, cm, spv, vel, rho)
    for i in range(lo[0], hi[0]):
        for j in range(lo[1], hi[1]):
            m = v = 0.0
            p = np.zeros(3)
            for a in range(2):
                x = i + cc_low[0] + a
                wa = 1.0 if (x == n_lo[0]) else 0.5
                for b in range(2):
                    y = j + cc_low[1] + b
                    w = wa * 0.5
                    mw = w * gm[x - node_low[0], y - node_low[1], 0]
                    m += mw
                    v += w * gv[x - node_low[0], y - node_low[1], 0]
                    p += mw * gu[x - node_low[0], y - node_low[1], 0]
            v += tiny / rho0           # Uintah's floor, added in every cell
            m += tiny
            assert cm[i, j, 0] == m and spv[i, j, 0] == v / m and rho[i, j, 0] == m / vol
            assert np.array_equal(vel[i, j, 0], p / m)
