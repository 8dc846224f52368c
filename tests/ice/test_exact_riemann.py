"""Tests for components/ice/exact_riemann.py (Toro ch. 4 exact Riemann solver)."""
import sys
from pathlib import Path

import numpy as np
import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[2]))

from components.ice.exact_riemann import exact_riemann, star_state, wave_structure  # noqa: E402

# Initial data: Toro (2009, 3rd ed.), Table 4.1 (gamma = 1.4; left | right as rho, u, p).
TORO_DATA = {
    1: ((1.0, 0.0, 1.0), (0.125, 0.0, 0.1)),
    2: ((1.0, -2.0, 0.4), (1.0, 2.0, 0.4)),
    3: ((1.0, 0.0, 1000.0), (1.0, 0.0, 0.01)),
    4: ((1.0, 0.0, 0.01), (1.0, 0.0, 100.0)),
    5: ((5.99924, 19.5975, 460.894), (5.99242, -6.19633, 46.0950)),
}
# Exact star states: Toro (2009), Table 4.3 (p*, u*, rho*L, rho*R), as printed
# (5-6 significant digits).  NB test 5 has u* = 8.68975 (-6.19633 is u_R).
TORO_STAR = {
    1: (0.30313, 0.92745, 0.42632, 0.26557),
    2: (0.00189, 0.00000, 0.02185, 0.02185),
    3: (460.894, 19.5975, 0.57506, 5.99924),
    4: (46.0950, -6.19633, 5.99242, 0.57511),
    5: (1691.64, 8.68975, 14.2823, 31.0426),
}
# water (Saurel & Abgrall 1999 stiffened gas) | air shock tube
AIR_WATER = dict(left=(1000.0, 0.0, 1.0e9), right=(50.0, 0.0, 1.0e5),
                 gamma_left=4.4, gamma_right=1.4, pinf_left=6.0e8, pinf_right=0.0)


@pytest.mark.parametrize("test", [1, 2, 3, 4, 5])
def test_toro_table_4_3(test):
    left, right = TORO_DATA[test]
    w = wave_structure(left, right, gamma_left=1.4, gamma_right=1.4)
    p, u, rl, rr = TORO_STAR[test]
    # 5 printed digits: compare to half a unit of the last printed digit (+ input rounding)
    assert w["p_star"] == pytest.approx(p, rel=1e-5, abs=5e-6)
    assert w["u_star"] == pytest.approx(u, rel=1e-5, abs=5e-6)
    assert w["rho_star_L"] == pytest.approx(rl, rel=1e-5, abs=5e-6)
    assert w["rho_star_R"] == pytest.approx(rr, rel=1e-5, abs=5e-6)
    assert star_state(left, right, 1.4, 1.4) == (w["p_star"], w["u_star"])


def test_sod_profile_regions():
    left, right = TORO_DATA[1]
    x = np.array([0.0, 0.3, 0.6, 0.8, 1.0])
    s = exact_riemann(left, right, x, 0.25, 0.5, gamma_left=1.4)
    np.testing.assert_allclose(s["rho"][[0, -1]], [1.0, 0.125])
    assert s["p"][2] == pytest.approx(0.30313, abs=5e-6)       # star region left of contact
    assert s["rho"][2] == pytest.approx(0.42632, abs=5e-6)
    assert s["rho"][3] == pytest.approx(0.26557, abs=5e-6)     # between contact and shock
    np.testing.assert_allclose(s["e"], s["p"] / (0.4 * s["rho"]), rtol=1e-14)
    # the rarefaction fan is isentropic: p / rho^gamma constant
    xf = np.linspace(0.5 - 1.18 * 0.25, 0.5 - 0.08 * 0.25, 50)
    f = exact_riemann(left, right, xf, 0.25, 0.5)
    np.testing.assert_allclose(f["p"] / f["rho"] ** 1.4, 1.0, rtol=1e-12)


def test_vacuum_generation_raises():
    with pytest.raises(ValueError, match="vacuum"):
        star_state((1.0, -4.0, 0.4), (1.0, 4.0, 0.4), gamma_left=1.4)
    with pytest.raises(ValueError, match="vacuum"):
        exact_riemann((1.0, -4.0, 0.4), (1.0, 4.0, 0.4), np.linspace(0, 1, 5), 0.1, 0.5)


def test_stiffened_same_material_is_shifted_ideal_gas():
    pinf, g = 3.0e3, 2.0
    left, right = (2.0, 1.0, 5.0e3), (1.0, -0.5, 1.0e3)
    x = np.linspace(-1.0, 1.0, 201)
    s = exact_riemann(left, right, x, 1e-2, 0.0, gamma_left=g, gamma_right=g,
                      pinf_left=pinf, pinf_right=pinf)
    i = exact_riemann((2.0, 1.0, 5.0e3 + pinf), (1.0, -0.5, 1.0e3 + pinf), x, 1e-2, 0.0,
                      gamma_left=g, gamma_right=g)
    np.testing.assert_allclose(s["rho"], i["rho"], rtol=1e-12)
    np.testing.assert_allclose(s["u"], i["u"], rtol=1e-12, atol=1e-12)
    np.testing.assert_allclose(s["p"] + pinf, i["p"], rtol=1e-12)


def test_air_water_shock_tube_jump_conditions():
    w = wave_structure(**AIR_WATER)
    assert w["left_wave"] == "rarefaction" and w["right_wave"] == "shock"
    s_shock = w["speeds"][4]
    r0, u0, p0 = AIR_WATER["right"]
    r1, u1, p1 = w["rho_star_R"], w["u_star"], w["p_star"]
    e0, e1 = p0 / (0.4 * r0), p1 / (0.4 * r1)
    # Rankine-Hugoniot across the air shock (mass, momentum, energy)
    assert r1 * (u1 - s_shock) == pytest.approx(r0 * (u0 - s_shock), rel=1e-10)
    assert r1 * u1 * (u1 - s_shock) + p1 == pytest.approx(r0 * u0 * (u0 - s_shock) + p0, rel=1e-10)
    E0, E1 = r0 * (e0 + 0.5 * u0**2), r1 * (e1 + 0.5 * u1**2)
    assert E1 * (u1 - s_shock) + p1 * u1 == pytest.approx(E0 * (u0 - s_shock) + p0 * u0, rel=1e-10)
    # water side: isentrope of the shifted ideal gas
    rl, _, pl = AIR_WATER["left"]
    assert (p1 + 6e8) / w["rho_star_L"] ** 4.4 == pytest.approx((pl + 6e8) / rl**4.4, rel=1e-12)


def _conserved(sol, gl, gr, pinfl, pinfr, xi, us):
    left = xi <= us
    g = np.where(left, gl, gr)
    pinf = np.where(left, pinfl, pinfr)
    rho, u, p = sol["rho"], sol["u"], sol["p"]
    E = (p + g * pinf) / (g - 1.0) + 0.5 * rho * u**2
    np.testing.assert_allclose(rho * sol["e"], (p + g * pinf) / (g - 1.0), rtol=1e-12)
    return np.array([rho, rho * u, E])


def _flux(state, g, pinf):
    rho, u, p = state
    E = (p + g * pinf) / (g - 1.0) + 0.5 * rho * u**2
    return np.array([rho * u, rho * u * u + p, u * (E + p)]), np.array([rho, rho * u, E])


CASES = [dict(left=TORO_DATA[k][0], right=TORO_DATA[k][1], gamma_left=1.4, gamma_right=1.4,
              pinf_left=0.0, pinf_right=0.0) for k in TORO_DATA] + [AIR_WATER]


@pytest.mark.parametrize("case", CASES)
def test_conservation_over_closed_interval(case):
    """int_a^b U(x,t) dx = int_a^b U(x,0) dx - t (F(U_R) - F(U_L)) (integral form of the conservation laws)."""
    w = wave_structure(**case)
    speeds = np.array(w["speeds"])
    t, x0 = 0.7, 0.0
    span = speeds.max() - speeds.min() + 1.0
    a, b = x0 + t * speeds.min() - 0.3 * span * t, x0 + t * speeds.max() + 0.4 * span * t
    # integrate piecewise between wave positions with Gauss-Legendre (exact on
    # constant states, spectrally accurate in the smooth rarefaction fans)
    edges = np.concatenate([[a], x0 + t * speeds, [b]])
    gx, gw = np.polynomial.legendre.leggauss(40)
    total = np.zeros(3)
    for lo, hi in zip(edges[:-1], edges[1:]):
        if hi - lo <= 0.0:
            continue
        xq = 0.5 * (hi - lo) * gx + 0.5 * (hi + lo)
        sol = exact_riemann(case["left"], case["right"], xq, t, x0, case["gamma_left"],
                            case["gamma_right"], case["pinf_left"], case["pinf_right"])
        U = _conserved(sol, case["gamma_left"], case["gamma_right"], case["pinf_left"],
                       case["pinf_right"], (xq - x0) / t, w["u_star"])
        total += 0.5 * (hi - lo) * (U * gw).sum(axis=1)
    FL, UL = _flux(case["left"], case["gamma_left"], case["pinf_left"])
    FR, UR = _flux(case["right"], case["gamma_right"], case["pinf_right"])
    expected = UL * (x0 - a) + UR * (b - x0) - t * (FR - FL)
    scale = np.abs(UL * (x0 - a)) + np.abs(UR * (b - x0)) + t * (np.abs(FR) + np.abs(FL))
    np.testing.assert_allclose(total, expected, rtol=0, atol=1e-11 * scale.max())
