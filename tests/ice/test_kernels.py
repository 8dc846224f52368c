"""ICE kernels one cell at a time: equilibration pressure (eq. 13) and implicit exchange (38-39)."""
import numpy as np
import pytest

from components.ice import kernels as K
from components.ice.equilibration import equilibrate
from components.ice.eos import IDEAL_GAS, MAX_PARAMS, STIFFENED_GAS

LO, HI = np.zeros(3, np.int64), np.ones(3, np.int64)


def cell(v):
    return np.full((1, 1, 1), float(v))


def test_equilibration_two_materials():
    """Air + stiffened water: converged p makes sum theta = 1 and equals each EOS pressure."""
    codes = np.array([IDEAL_GAS, STIFFENED_GAS])
    params = np.zeros((2, MAX_PARAMS))
    params[1, 0] = 6e8
    cvs, gammas = np.array([717.5, 1000.0]), np.array([1.4, 4.4])
    rhos = (cell(0.6), cell(500.0))
    temps = (cell(300.0), cell(400.0))
    sp_old = (cell(1 / 1.2), cell(1 / 1000.0))
    out = [tuple(cell(0) for _ in range(2)) for _ in range(3)]
    press = cell(0)
    it = equilibrate(rhos, temps, sp_old, cell(1e5), out[0], out[1], out[2], press, codes, params,
                     cvs, gammas, LO, HI, 1e-12, 100)
    p = press[0, 0, 0]
    theta = [r[0, 0, 0] * v[0, 0, 0] for r, v in zip(rhos, out[0])]
    assert sum(theta) == pytest.approx(1.0, abs=1e-10) and it < 50
    rm = [1 / v[0, 0, 0] for v in out[0]]
    assert p == pytest.approx(0.4 * rm[0] * 717.5 * 300.0, rel=1e-9)           # ideal gas
    assert p == pytest.approx(3.4 * rm[1] * 1000.0 * 400.0 - 6e8, rel=1e-9)     # stiffened gas


@pytest.mark.parametrize("Kc", [1e3, 1e15])
def test_exchange_conserves_and_is_stable(Kc):
    """Three materials: momentum and energy conserved; K = 1e15 gives one common velocity."""
    n = 3
    masses = tuple(cell(m) for m in (1.0, 2.0, 0.5))
    vel = [3.0, -1.0, 10.0]
    moms = tuple(np.full((1, 1, 1, 3), m[0, 0, 0] * u) for m, u in zip(masses, vel))
    cvs = np.array([700.0, 1000.0, 500.0])
    T = [300.0, 400.0, 1000.0]
    engs = tuple(cell(m[0, 0, 0] * c * t) for m, c, t in zip(masses, cvs, T))
    vfs = tuple(cell(v) for v in (0.2, 0.5, 0.3))
    sps = tuple(cell(v) for v in (0.2, 0.25, 0.6))         # m v = theta V (V = 1), as in ICE
    Km = np.full((n, n), Kc)
    mom_out = tuple(np.zeros((1, 1, 1, 3)) for _ in range(n))
    eng_out = tuple(cell(0) for _ in range(n))
    K.exchange_cells(masses, moms, engs, vfs, sps, cvs, mom_out, eng_out, LO, HI, 1e-3, Km, Km)
    assert sum(m[0, 0, 0, 0] for m in mom_out) == pytest.approx(sum(m[0, 0, 0, 0] for m in moms), rel=1e-12)
    assert sum(e[0, 0, 0] for e in eng_out) == pytest.approx(sum(e[0, 0, 0] for e in engs), rel=1e-12)
    u = [m[0, 0, 0, 0] / ms[0, 0, 0] for m, ms in zip(mom_out, masses)]
    assert max(u) <= max(vel) and min(u) >= min(vel)
    if Kc == 1e15:
        ubar = sum(m[0, 0, 0] * v for m, v in zip(masses, vel)) / sum(m[0, 0, 0] for m in masses)
        assert np.allclose(u, ubar, rtol=1e-9)


def test_ideal_gas_equilibration_closed_form_matches_newton():
    """Three ideal gases in 64 random cells: equilibrate_ideal (p = sum rho (gamma-1) cv T, exact)
    and the Newton iteration of equilibration.equilibrate give the same p, theta, v, c within the
    Newton tolerance; the closed form's sum of theta is 1 to round-off."""
    rng = np.random.default_rng(7)
    n, shape = 3, (4, 4, 4)
    cvs, gammas = np.array([717.5, 3116.0, 1000.0]), np.array([1.4, 1.66, 1.3])
    rhos = tuple(rng.uniform(1e-6, 2.0, shape) for _ in range(n))
    temps = tuple(rng.uniform(200.0, 3000.0, shape) for _ in range(n))
    lo, hi = np.zeros(3, np.int64), np.array(shape, np.int64)
    outs = {}
    for name in ("ideal", "newton"):
        sp, vf, cs = (tuple(np.zeros(shape) for _ in range(n)) for _ in range(3))
        p = np.zeros(shape)
        if name == "ideal":
            K.equilibrate_ideal(rhos, temps, sp, vf, cs, p, cvs, gammas, lo, hi)
        else:
            # uintah_mpmice=False (ICE's equilibration, the default) given, as MPMICE gives it: the
            # specialisation of three materials that the shipped burning-container decks compile
            equilibrate(rhos, temps, tuple(np.full(shape, 1.0) for _ in range(n)), np.full(shape, 1e5),
                        sp, vf, cs, p, np.full(n, IDEAL_GAS), np.zeros((n, MAX_PARAMS)), cvs, gammas,
                        lo, hi, 1e-13, 100, False)
        outs[name] = (p, sp, vf, cs)
    exact = sum(r * (g - 1) * c * t for r, t, g, c in zip(rhos, temps, gammas, cvs))
    np.testing.assert_allclose(outs["ideal"][0], exact, rtol=1e-15)
    np.testing.assert_allclose(sum(outs["ideal"][2]), 1.0, rtol=1e-14)
    for a, b in zip(outs["ideal"], outs["newton"]):
        np.testing.assert_allclose(np.array(a), np.array(b), rtol=1e-9)


def test_two_material_solve_is_the_general_solve():
    """_solve2 (the two-material exchange, written out) against _exchange_matrix + solve_small:
    bitwise equal, for momentum and for heat (divided by cv), stiff and soft coefficients."""
    rng = np.random.default_rng(3)
    a, b = np.empty((2, 2)), np.empty(2)
    for _ in range(200):
        th, sv, cv = rng.uniform(1e-8, 1, 2), rng.uniform(0.1, 10, 2), rng.uniform(500, 4000, 2)
        Km = np.array([[0.0, 1.0], [1.0, 0.0]]) * 10.0 ** rng.uniform(-2, 15)
        rhs, dt = rng.normal(size=2), 10.0 ** rng.uniform(-8, -3)
        for heat in (False, True):
            b[:] = rhs
            K._exchange_matrix(a, th, sv, Km, dt, 2, cv if heat else None)
            K.solve_small(a, b, 2)
            x = K._solve2(rhs[0], rhs[1], th[0], th[1], sv[0], sv[1], Km[0, 1], Km[1, 0], dt, cv[0], cv[1], heat)
            assert x[0] == b[0] and x[1] == b[1]
