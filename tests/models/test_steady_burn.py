"""Steady_Burn (components/models/steady_burn.py): the WSB burn rate and mass conservation.

tests/models/steady_burn1d.ups: burn1d.ups's 600 K slab of explosive in product gas (1D),
PBX 9501's WSB constants. Both faces burn (A = 0.025^2 m^2 each).

sus values: Uintah's sus on the same deck with <max_Timesteps> 10 and output every step
(its totalMassBurned.dat).
"""
import json
import math
import os

import numpy as np
import pytest

from components.models import kernels as K

HERE = os.path.dirname(__file__)
DECK = os.path.join(HERE, "steady_burn1d.ups")
V = 0.025 ** 3
A = 0.025 ** 2

R, Ac, Ec, Bg, Qc, Qg, Kg, Kc, Cp, W = 8.314, 1.637e15, 1.76e5, 1.6e-3, 4e5, 3.018e6, 0.07, 0.2, 1.4e3, 0.0342

# sus: (time, totalMassBurned) of the first two steps (same delT as pysus's: 1e-7 s, then the CFL step)
SUS_BURNED = [(9.9999999999999995e-08, 8.4351543933243749e-09), (3.6856858151729913e-06, 3.0254235052000259e-07)]


def wsb_by_bisection(T0, P, v):
    """The WSB steady burn (Ts, m) by plain bisection of Ts - Ts(m(Ts)) on [T0 + Qc/Cp, 3000 K]."""
    C3 = 4 * Kg * Bg * W * W / Cp / R / R * P * P

    def m(Ts):
        return math.sqrt(Ac * R * Kc / Ec / Cp / v * Ts * Ts / (Ts - T0 - Qc / Cp / 2) * math.exp(-Ec / R / Ts))

    def f(Ts):
        return Ts - (T0 + Qc / Cp + Qg / Cp * C3 / (math.sqrt(m(Ts) ** 2 + C3) + m(Ts)) ** 2)

    lo, hi = T0 + Qc / Cp, 3000.0
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if f(mid) < 0 else (lo, mid)
    return mid, m(mid)


@pytest.mark.parametrize("T0,P", [(300.0, 101325.0), (600.0, 101325.0), (300.0, 1e7), (450.0, 3e8)])
def test_surface_temperature_solver_against_bisection(T0, P):
    v = 1 / 1800.0
    CC = [Ac * R * Kc / Ec / Cp, Qc / Cp / 2, 4 * Kg * Bg * W * W / Cp / R / R, Qc / Cp, Qg / Cp]
    C3 = CC[2] * P * P
    C = (CC[0] / v, T0 + CC[1], C3, T0 + CC[3], CC[4] * C3)
    Ts = K.wsb_surface_temperature(850.0, *C, Ec, R, 1e-6)
    Ts_ref, m_ref = wsb_by_bisection(T0, P, v)
    assert abs(Ts - Ts_ref) < 1e-5
    assert abs(K.wsb_mass_flux(Ts, C[0], C[1], Ec, R) - m_ref) < 1e-6 * m_ref


@pytest.fixture(scope="module")
def archive(tmp_path_factory):
    from framework.archiver import DataArchive
    from framework.controller import Controller
    c = Controller(DECK, quiet=True, filebase=str(tmp_path_factory.mktemp("sburn") / "steady_burn1d.uda"))
    c.run()
    return DataArchive(c.archiver.dir)


def test_solid_mass_lost_is_gas_mass_gained(archive):
    solid0 = float(archive.particles(0, 0)["p.mass"].sum())
    gas0 = float(archive.read("rho_CC", 1, 0)[0].sum() * V)
    for i in range(1, len(archive.times)):
        solid = float(archive.particles(0, i)["p.mass"].sum())
        gas = float(archive.read("rho_CC", 1, i)[0].sum() * V)
        assert abs((solid0 - solid) - (gas - gas0)) < 1e-12 * (solid0 + gas0)
    assert solid0 - solid > 5e-6


def test_first_step_burns_at_the_wsb_rate_and_as_sus(archive):
    """Step 1: solid at 600 K, gas at 1 atm, v = 1/1800: both faces burn dt A m(Ts); sus burned
    the same to 16 digits."""
    t, burned = archive.reduction("totalMassBurned")
    _, m = wsb_by_bisection(600.0, 101325.0, 1 / 1800.0)
    assert abs(burned[0] - 2 * t[0] * A * m) < 1e-6 * burned[0]
    assert abs(burned[0] - SUS_BURNED[0][1]) < 1e-13 * burned[0]
    # step 2 (the same delT as sus's to 1e-8): the state has moved, the rate with it (2.8e-4 measured)
    assert abs(t[1] - SUS_BURNED[1][0]) < 1e-8 * t[1]
    assert abs(burned[1] - SUS_BURNED[1][1]) < 1e-3 * burned[1]


def test_heat_released_and_surface_temperature(archive):
    _, burned = archive.reduction("totalMassBurned")
    _, heat = archive.reduction("totalHeatReleased")
    np.testing.assert_allclose(heat, np.asarray(burned) * (Qc + Qg), rtol=1e-14)
    ts = archive.read("SteadyBurn.SurfTemp", 0, 1)[0].ravel()
    cells = np.nonzero(archive.read("SteadyBurn.BurningCell", 0, 1)[0].ravel())[0]
    assert list(cells) == [18, 21]                  # the slab's two surface cells
    assert np.all((ts[cells] > 880.0) & (ts[cells] < 900.0))      # bisection at 600 K, 1 atm: 885.7 K


def test_bad_value_refused(tmp_path):
    from framework.controller import Controller
    from framework.problemspec import InputError
    text = open(DECK).read().replace("<SpecificHeatBoth>  1.4e3", "<SpecificHeatBoth>  -1.4e3")
    with pytest.raises(InputError) as e:
        Controller(str(tmp_path / "d.ups"), deck_text=text, quiet=True, filebase=str(tmp_path / "d.uda")).run()
    assert "SpecificHeatBoth" in str(e.value)
