"""Tests for components/ice/eos.py (ICE equations of state, numba dispatch)."""
import math
import sys
from pathlib import Path

import numpy as np
import pytest
from numba import njit

sys.path.insert(0, str(Path(__file__).resolve().parents[2]))

from components.ice import eos as E  # noqa: E402

AIR = dict(cv=716.5, gamma=1.4)
# Murnaghan: Uintah-style parameters for an HMX-like reactant (K = 1/bulk in 1/Pa)
MURN = E.make_eos("Murnaghan", dict(K=1.9342e-10, n=15.2, rho0=1835.0, P0=101325.0))
# JWL products (LX-14-like coefficients, SI units)
JWL = E.make_eos("JWL", dict(A=7.783e11, B=7.071e9, R1=4.2, R2=1.0, om=0.3, rho0=1891.0))
JWLC = E.make_eos("JWLC", dict(A=2.9867e11, B=4.1126e9, C=1.0e9, R1=4.95, R2=1.15,
                               om=0.35, rho0=1800.0))
# water as a stiffened gas: gamma = 4.4, Pinf = 6e8 Pa (Saurel & Abgrall 1999, JCP 150)
WATER = E.make_eos("Stiffened_gas", dict(Pinf=6.0e8))
WATER_G = 4.4
IDEAL = E.make_eos("ideal_gas", {})
TST = E.make_eos("TST", dict(a=-260.1385968, b=7.955153678e-4, u=-0.5, w=3.0, Gamma=1.63))

# (model, cv, gamma, densities, temperature) used by the generic checks
CASES = {
    "ideal_gas": (IDEAL, 716.5, 1.4, [0.01, 1.2, 50.0], 300.0),
    "Murnaghan_hi": (MURN, 1000.0, 1.4, [1835.0 * 1.0001, 1900.0, 2200.0], 300.0),
    # the low branch p = P0 (rho/rho0)^(1/(K P0)) has exponent ~5e4: p -> 0 within
    # ~1e-4 of rho0 (the intended near-incompressible "decoupling", paper 000 sec. 3.1)
    "Murnaghan_lo": (MURN, 1000.0, 1.4, [1835.0 * (1 - 1e-6), 1835.0 * (1 - 2e-5),
                                         1835.0 * (1 - 1e-4)], 300.0),
    "JWL": (JWL, 1000.0, 1.4, [10.0, 500.0, 1891.0, 2500.0], 2500.0),
    "JWLC": (JWLC, 1000.0, 1.4, [50.0, 900.0, 1800.0, 2600.0], 300.0),
    "Stiffened_gas": (WATER, 588.0, WATER_G, [990.0, 1000.0, 1100.0], 300.0),
    # Uintah's SteadyBurn_2dRT.ups product (HMX gas): gamma = Gamma = 1.63
    "TST": (TST, 514.96, 1.63, [0.5, 10.0, 300.0, 900.0], 2500.0),
}


def test_param_layouts():
    assert E.MAX_PARAMS == 8
    np.testing.assert_array_equal(MURN.params()[:4], [1.9342e-10, 15.2, 1835.0, 101325.0])
    np.testing.assert_array_equal(JWL.params()[:6], [7.783e11, 7.071e9, 4.2, 1.0, 0.3, 1891.0])
    assert WATER.params()[0] == 6.0e8 and WATER.code == E.STIFFENED_GAS
    assert MURN.params().dtype == np.float64 and MURN.params().shape == (8,)
    with pytest.raises(ValueError, match="not implemented"):
        E.make_eos("Tillotson", {})
    with pytest.raises(ValueError, match="missing"):
        E.make_eos("Murnaghan", dict(K=1.0, n=2.0))


def test_ideal_gas_round_trip():
    pr = IDEAL.params()
    for p in [1.0, 101325.0, 3.7e7]:
        for T in [50.0, 300.0, 3000.0]:
            rho = E.eos_rho_micro(E.IDEAL_GAS, pr, p, T, AIR["cv"], AIR["gamma"], 1.0)
            assert E.eos_press(E.IDEAL_GAS, pr, rho, T, AIR["cv"], AIR["gamma"]) == pytest.approx(p, rel=1e-14)
            assert E.eos_temp(E.IDEAL_GAS, pr, p, rho, AIR["cv"], AIR["gamma"]) == pytest.approx(T, rel=1e-14)


@pytest.mark.parametrize("name", list(CASES))
def test_round_trip_every_eos(name):
    m, cv, g, rhos, T = CASES[name]
    pr = m.params()
    for rho in rhos:
        p = E.eos_press(m.code, pr, rho, T, cv, g)
        back = E.eos_rho_micro(m.code, pr, p, T, cv, g, 0.7 * rho)
        assert back == pytest.approx(rho, rel=1e-10)


@pytest.mark.parametrize("name", list(CASES))
def test_dp_drho_and_dp_de_finite_differences(name):
    m, cv, g, rhos, T = CASES[name]
    pr = m.params()
    for rho in rhos:
        p, dpdrho, dpde = E.eos_press_eos(m.code, pr, rho, T, cv, g)
        # step scaled by the local exponent rho p'/p (up to ~5e4 for Murnaghan)
        h = 1e-4 * rho * min(1.0, abs(p) / (rho * dpdrho))
        fd = (E.eos_press(m.code, pr, rho + h, T, cv, g)
              - E.eos_press(m.code, pr, rho - h, T, cv, g)) / (2 * h)
        assert dpdrho == pytest.approx(fd, rel=1e-6)
        assert E.eos_dp_drho(m.code, pr, rho, T, cv, g) == dpdrho
        # dp_de = (dp/dT)_rho / cv  (e = cv T + e_cold(rho))
        hT = 1e-4 * T
        fdT = (E.eos_press(m.code, pr, rho, T + hT, cv, g)
               - E.eos_press(m.code, pr, rho, T - hT, cv, g)) / (2 * hT * cv)
        assert E.eos_dp_de(m.code, pr, rho, T, cv, g) == pytest.approx(fdT, rel=1e-6, abs=1e-12 * rho)


@pytest.mark.parametrize("name", list(CASES))
def test_cold_energy_obeys_the_first_law(name):
    """de_c/drho = (p - T (dp/dT)_rho) / rho^2: with e = cv T + e_c the Euler energy equation holds
    (what <conserveTotalEnergy> relies on); checked by central differences of eos_cold_energy."""
    m, cv, g, rhos, T = CASES[name]
    pr = m.params()
    for rho in rhos:
        p = E.eos_press(m.code, pr, rho, T, cv, g)
        dpdT = E.eos_dp_de(m.code, pr, rho, T, cv, g) * cv
        exact = (p - T * dpdT) / rho ** 2
        dpdrho = E.eos_dp_drho(m.code, pr, rho, T, cv, g)
        h = 1e-4 * rho * min(1.0, abs(p) / (rho * dpdrho)) if dpdrho > 0 else 1e-4 * rho
        fd = (E.eos_cold_energy(m.code, pr, rho + h) - E.eos_cold_energy(m.code, pr, rho - h)) / (2 * h)
        assert fd == pytest.approx(exact, rel=1e-5, abs=1e-9 * abs(p) / rho ** 2 + 1e-300)
    if m.code == E.STIFFENED_GAS:
        assert E.eos_cold_energy(m.code, pr, 1000.0) == 6.0e8 / 1000.0      # Pinf / rho
    if m.code == E.IDEAL_GAS:
        assert E.eos_cold_energy(m.code, pr, 1.2) == 0.0


def test_air_sound_speed_300K():
    pr = IDEAL.params()
    rho = E.eos_rho_micro(E.IDEAL_GAS, pr, 101325.0, 300.0, AIR["cv"], AIR["gamma"], 1.0)
    c2 = E.eos_sound_speed2(E.IDEAL_GAS, pr, rho, 300.0, AIR["cv"], AIR["gamma"])
    assert math.sqrt(c2) == pytest.approx(347.0, abs=1.0)   # sqrt(gamma R T), R = 286.6
    p, dpdrho, dpde = E.eos_press_eos(E.IDEAL_GAS, pr, rho, 300.0, AIR["cv"], AIR["gamma"])
    assert E.sound_speed2_uintah(p, rho, dpdrho, dpde) == pytest.approx(c2, rel=1e-14)


def test_water_stiffened_gas_sound_speed():
    pr, cv = WATER.params(), 588.0
    T = E.eos_temp(E.STIFFENED_GAS, pr, 101325.0, 1000.0, cv, WATER_G)
    c2 = E.eos_sound_speed2(E.STIFFENED_GAS, pr, 1000.0, T, cv, WATER_G)
    # stiffened-gas sound speed c^2 = gamma (p + Pinf) / rho = 1625 m/s for these values
    assert c2 == pytest.approx(WATER_G * (101325.0 + 6.0e8) / 1000.0, rel=1e-12)
    assert 1450.0 < math.sqrt(c2) < 1700.0


def test_murnaghan_reference_state():
    pr = MURN.params()
    p, dpdrho, dpde = E.eos_press_eos(E.MURNAGHAN, pr, 1835.0, 300.0, 1000.0, 1.4)
    assert p == 101325.0 and dpde == 0.0
    assert dpdrho == pytest.approx(1.0 / (1.9342e-10 * 1835.0), rel=1e-14)
    # both branches meet with equal slope at rho0 (Uintah's low-pressure branch)
    # (exponent 1/(K P0) = 5.1e4, so a 1e-12 step changes p by 5e-8 relative)
    lo = E.eos_press_eos(E.MURNAGHAN, pr, 1835.0 * (1 - 1e-12), 300.0, 1000.0, 1.4)
    assert lo[0] == pytest.approx(p, rel=1e-7) and lo[1] == pytest.approx(dpdrho, rel=1e-7)
    assert E.eos_rho_micro(E.MURNAGHAN, pr, 101325.0, 300.0, 1000.0, 1.4, 1.0) == pytest.approx(1835.0)
    c2 = E.eos_sound_speed2(E.MURNAGHAN, pr, 1835.0, 300.0, 1000.0, 1.4)
    assert c2 == dpdrho


def test_jwl_temperature_alpha_and_sound_speed():
    pr, cv, T = JWL.params(), 1000.0, 2500.0
    rho = 1200.0
    p, dpdrho, dpde = E.eos_press_eos(E.JWL, pr, rho, T, cv, 1.4)
    assert E.eos_temp(E.JWL, pr, p, rho, cv, 1.4) == pytest.approx(T, rel=1e-12)
    # alpha = (1/v)(dv/dT)_p, by finite differences of rho_micro(p, T)
    h = 1e-3
    rp = E.eos_rho_micro(E.JWL, pr, p, T + h, cv, 1.4, rho)
    rm = E.eos_rho_micro(E.JWL, pr, p, T - h, cv, 1.4, rho)
    alpha_fd = -(rp - rm) / (2 * h) / rho
    assert E.eos_alpha(E.JWL, pr, rho, T, cv, 1.4) == pytest.approx(alpha_fd, rel=1e-5)
    # c^2 = (dp/drho)_T + om^2 cv T for this Gruneisen-type form
    assert E.eos_sound_speed2(E.JWL, pr, rho, T, cv, 1.4) == pytest.approx(dpdrho + 0.09 * cv * T)
    assert E.eos_alpha(E.IDEAL_GAS, IDEAL.params(), 1.2, 300.0, 716.5, 1.4) == pytest.approx(1 / 300.0)
    assert E.eos_alpha(E.MURNAGHAN, MURN.params(), 1900.0, 300.0, 1.0, 1.4) == 0.0


@pytest.mark.parametrize("name", ["JWL", "JWLC", "Murnaghan_hi", "Stiffened_gas"])
def test_condensed_phase_threshold(name):
    """Paper 000 sec. 3.1: C1 at p_th, tends to 0 as v -> infinity, invertible."""
    m, cv, g, _, T = CASES[name]
    pr, p_th = m.params(), 101325.0
    rho_th = E.eos_rho_micro(m.code, pr, p_th, T, cv, g, 1.0)
    full = E.eos_press_eos(m.code, pr, rho_th, T, cv, g)
    expo = rho_th * full[1] / p_th       # exponent of the power law below p_th
    below = E.eos_press_eos_threshold(m.code, pr, rho_th * (1 - 1e-8 / expo), T, cv, g, p_th)
    assert below[0] == pytest.approx(full[0], rel=1e-7)
    assert below[1] == pytest.approx(full[1], rel=1e-7)
    above = E.eos_press_eos_threshold(m.code, pr, rho_th * 1.01, T, cv, g, p_th)
    assert above == E.eos_press_eos(m.code, pr, rho_th * 1.01, T, cv, g)
    # below p_th: p = p_th (rho/rho_th)^expo, collapsing to 0 as v -> infinity
    ratio = max(0.5, 1.0 - 2.0 / expo)
    p_mid = E.eos_press_eos_threshold(m.code, pr, rho_th * ratio, T, cv, g, p_th)[0]
    assert p_mid == pytest.approx(p_th * ratio**expo, rel=1e-9) and p_mid < p_th
    p_far = E.eos_press_eos_threshold(m.code, pr, rho_th * 1e-8, T, cv, g, p_th)[0]
    assert 0.0 <= p_far < 1e-6 * p_th
    for p in [1.0, 1e3, 5e4, 2e5]:
        r = E.eos_rho_micro_threshold(m.code, pr, p, T, cv, g, rho_th, p_th)
        assert E.eos_press_eos_threshold(m.code, pr, r, T, cv, g, p_th)[0] == pytest.approx(p, rel=1e-9)


def test_murnaghan_low_branch_is_the_threshold_curve():
    pr = MURN.params()
    for rho in [1000.0, 1700.0, 1834.0]:
        a = E.eos_press_eos(E.MURNAGHAN, pr, rho, 300.0, 1.0, 1.4)
        b = E.eos_press_eos_threshold(E.MURNAGHAN, pr, rho, 300.0, 1.0, 1.4, 101325.0)
        assert b[0] == pytest.approx(a[0], rel=1e-12) and b[1] == pytest.approx(a[1], rel=1e-12)
    # bare curve with MPM-solid arguments (p_ref, rho0, bulk) as Uintah's useModifiedEOS
    p, dp = E.threshold_press(900.0, 101325.0, 1000.0, 1.0e9)
    assert p == pytest.approx(101325.0 * 0.9 ** (1.0e9 / 101325.0))
    assert E.threshold_press(1000.0, 101325.0, 1000.0, 1.0e9)[1] == pytest.approx(1.0e6)


@njit  # not cached: test modules are not importable by name under importlib mode
def _mixture_kernel(codes, params, rho_micro, temp, cv, gamma, press, c2):
    for c in range(rho_micro.shape[1]):
        for m in range(codes.shape[0]):
            press[m, c] = E.eos_press(codes[m], params[m], rho_micro[m, c], temp[m, c], cv[m], gamma[m])
            c2[m, c] = E.eos_sound_speed2(codes[m], params[m], rho_micro[m, c], temp[m, c], cv[m], gamma[m])


def test_multimaterial_kernel_dispatch():
    models = [IDEAL, MURN, JWL, JWLC, WATER]
    codes = np.array([m.code for m in models], dtype=np.int64)
    params = np.stack([m.params() for m in models])
    cv = np.array([716.5, 1000.0, 1000.0, 1000.0, 588.0])
    gamma = np.array([1.4, 1.4, 1.4, 1.4, WATER_G])
    rho = np.array([[1.2] * 3, [1900.0] * 3, [1500.0] * 3, [1800.0] * 3, [1000.0] * 3])
    temp = np.full_like(rho, 300.0)
    press, c2 = np.empty_like(rho), np.empty_like(rho)
    _mixture_kernel(codes, params, rho, temp, cv, gamma, press, c2)
    for k, m in enumerate(models):
        assert press[k, 1] == E.eos_press(m.code, params[k], rho[k, 1], 300.0, cv[k], gamma[k])
    assert np.all(c2 > 0.0)


def test_tst_is_uintahs():
    """TST (Uintah's TST.cc): p(rho, T) from its formula, T(p, rho) its inverse, rho_micro(p, T) the
    cubic's root with the material's gamma (equal to <Gamma> here: the round trip closes)."""
    pr, cv, g = TST.params(), 514.96, 1.63
    a, b, u, w, G = -260.1385968, 7.955153678e-4, -0.5, 3.0, 1.63
    for rho, T in ((1.0, 300.0), (50.0, 2000.0), (800.0, 3500.0)):
        v = 1.0 / rho
        p = (G - 1.0) * cv * T / (v - b) - a / ((v + u * b) * (v + w * b))
        assert E.eos_press(E.TST, pr, rho, T, cv, g) == pytest.approx(p, rel=1e-14)
        assert E.eos_temp(E.TST, pr, p, rho, cv, g) == pytest.approx(T, rel=1e-12)
        assert E.eos_rho_micro(E.TST, pr, p, T, cv, g, 1.0) == pytest.approx(rho, rel=1e-9)
    # Uintah's rho_micro takes the material's gamma: with another gamma it is another root
    p = E.eos_press(E.TST, pr, 10.0, 2000.0, cv, g)
    assert E.eos_rho_micro(E.TST, pr, p, 2000.0, cv, 1.4, 1.0) != pytest.approx(10.0, rel=1e-3)
