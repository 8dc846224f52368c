"""JWLpp (components/models/jwlpp.py): the JWL++ burn of an ICE explosive into ICE products,
against sus and its own balance.

tests/models/jwlpp1d.ups: ANFO at 3e8 Pa (Murnaghan) above the 2e8 Pa threshold between two
closed ends, a copper plate at the left end, Uintah's JWLppCuRS2d constants. data/sus_jwlpp1d.npz
is sus's output on that deck (one rank, `sus jwlpp1d.ups`, read with framework.uintah_uda):
the times, totalMassBurned.dat, totalHeatReleased.dat and, after each of the 5 steps, press_CC,
F and delF (reactant), modelMass_src (product) and both temperatures over the 40 cells.

Measured, in the cells 8..39 away from the copper: step 1 burned mass per cell 5e-15 relative to
sus, pressure 4e-15; the steps' times 1.2e-8 apart, steps 2-5 burn 2.3e-8 apart, the pressure
7e-10; next to the copper (cell 4, copper volume fraction 0.2) press_CC 5.2e-11 of the maximum
after step 1, 7.5e-10 after step 2, 1.0e-5 after step 5 (1.3e-5, 1.3e-5 and 2.3e-5 with the copper
as Murnaghan n = 1 instead of Uintah's UCNH EOS, eos.py SOLID_UCNH). The start's press_CC is Uintah's (ICE's initialization leaves
the last fluid's EOS pressure, here the products' 1 atm, where its objects do not reach), which
the solid's start density in the first equilibration depends on.
Uintah's updateVolumeFraction (components/models/__init__.py) is what makes step 1 agree: without
it the heat exchange sees the product's start-of-step volume fraction (temperatures 1e-4 apart).
"""
import os

import numpy as np
import pytest

from components.models.jwlpp import jwlpp_cells

HERE = os.path.dirname(__file__)
DECK = os.path.join(HERE, "jwlpp1d.ups")
FAR = slice(8, 40)
V = 5e-4 ** 3
G, B, RHO0, E0 = 3.5083e-7, 1.3, 1160.0, 5.558e6


@pytest.fixture(scope="module")
def runs(tmp_path_factory):
    from framework.archiver import DataArchive
    from framework.controller import Controller
    c = Controller(DECK, quiet=True, filebase=str(tmp_path_factory.mktemp("jwlpp") / "jwlpp1d.uda"))
    c.run()
    return DataArchive(c.archiver.dir), np.load(os.path.join(HERE, "data", "sus_jwlpp1d.npz"))


def _cc(da, label, m, step):
    return np.squeeze(da.read(label, m, step)[0])


def test_kernel_is_jwlpp():
    """dF = dt G p^b (1 - F) with F = rho_p / (rho_r + rho_p); the burn capped by the reactant and
    by 0.2 rho0 V; nothing below the pressure or volume-fraction thresholds."""
    shape = (4, 1, 1)
    lo, hi = np.zeros(3, np.int64), np.array(shape, np.int64)
    press = np.array([3e8, 3e8, 1e8, 3e9]).reshape(shape)
    vf = np.array([0.9, 0.005, 0.9, 0.9]).reshape(shape)
    rho_r = np.array([1200.0, 1200.0, 1200.0, 1200.0]).reshape(shape)
    rho_p = np.array([100.0, 100.0, 100.0, 0.0]).reshape(shape)
    F, dF, burned = np.zeros(shape), np.zeros(shape), np.zeros(shape)
    dt = 1e-8
    jwlpp_cells(press, vf, rho_r, rho_p, lo, hi, V, 2e8, 0.01, G, B, RHO0, dt, F, dF, burned)
    f = 100.0 / 1300.0
    assert F[0, 0, 0] == pytest.approx(f, rel=1e-15)
    assert dF[0, 0, 0] == pytest.approx(dt * G * 3e8 ** B * (1 - f), rel=1e-14)
    assert burned[0, 0, 0] == pytest.approx(dF[0, 0, 0] * 1300.0 * V, rel=1e-14)
    assert burned[1, 0, 0] == 0.0 and burned[2, 0, 0] == 0.0       # volume fraction, pressure thresholds
    assert burned[3, 0, 0] == pytest.approx(dt * G * 3e9 ** B * 1200.0 * V, rel=1e-14)
    # a long step: at most 0.2 rho0 V (JWL++'s limit), and never more than the reactant
    rho_r[3] = 100.0
    jwlpp_cells(press, vf, rho_r, rho_p, lo, hi, V, 2e8, 0.01, G, B, RHO0, 1.0, F, dF, burned)
    assert burned[0, 0, 0] == pytest.approx(0.2 * RHO0 * V, rel=1e-15)
    assert burned[3, 0, 0] == pytest.approx(100.0 * V, rel=1e-15)


def test_first_step_burns_as_uintah(runs):
    """Step 1 (delt_init): burned mass, F and the state it leaves equal sus's to round-off."""
    da, sus = runs
    assert da.times[1] == sus["times"][0]
    for label, m, key, tol in [("delF", 1, "delF", 1e-9), ("modelMass_src", 2, "modelMass_src", 1e-9),
                               ("press_CC", 0, "press_CC", 1e-9), ("temp_CC", 1, "temp_reactant", 1e-9),
                               ("temp_CC", 2, "temp_product", 1e-7)]:
        ours, ref = _cc(da, label, m, 1)[FAR], sus[f"{key}_1"][FAR]
        assert np.allclose(ours, ref, rtol=tol, atol=0), label


def test_next_to_the_copper_as_uintah(runs):
    """The cell shared with the copper (cell 4) after steps 1 and 2: the copper's pressure from
    Uintah's UCNH EOS (p_ref + K/2 (x - 1/x), c^2 = K/rho), press_CC to 1e-9 of the maximum
    (measured 5.2e-11, 7.5e-10; with Murnaghan n = 1: 1.3e-5)."""
    da, sus = runs
    for step in (1, 2):
        ours, ref = _cc(da, "press_CC", 0, step), sus[f"press_CC_{step}"]
        assert abs(ours[4] - ref[4]) < 1e-9 * np.abs(ref).max(), step


@pytest.mark.parametrize("step", [2, 3, 5])
def test_later_steps_as_uintah(runs, step):
    """The steps follow sus's (their lengths set next to the copper), and the burn per cell with them."""
    da, sus = runs
    assert da.times[step] == pytest.approx(sus["times"][step - 1], rel=1e-7)
    dt_ratio = (da.times[step] - da.times[step - 1]) / (sus["times"][step - 1] - sus["times"][step - 2])
    rate = _cc(da, "delF", 1, step)[FAR] / dt_ratio       # sus's step length
    assert np.allclose(rate, sus[f"delF_{step}"][FAR], rtol=1e-7, atol=0)
    assert np.allclose(_cc(da, "press_CC", 0, step)[FAR], sus[f"press_CC_{step}"][FAR], rtol=1e-8, atol=0)
    assert np.allclose(_cc(da, "F", 1, step)[FAR], sus[f"F_{step}"][FAR], rtol=1e-7, atol=0)


def test_mass_and_energy_move_between_the_fluids(runs):
    """The reactant loses what the product gains (every step, cell by cell); totalHeatReleased is
    E0 per kg burned; the fluids' mass is conserved in the closed tube."""
    da, sus = runs
    _, burned = da.reduction("totalMassBurned")
    _, heat = da.reduction("totalHeatReleased")
    assert np.allclose(heat, burned * E0, rtol=1e-14)
    assert np.allclose(burned, sus["totalMassBurned"], rtol=1e-5, atol=0)
    for step in range(1, len(da.times)):
        assert _cc(da, "modelMass_src", 2, step).sum() == pytest.approx(burned[step - 1], rel=1e-13)
    mass = [sum(_cc(da, "rho_CC", m, i).sum() * V for m in (1, 2)) for i in range(len(da.times))]
    assert np.allclose(mass, mass[0], rtol=1e-13, atol=0)
    prod = [_cc(da, "rho_CC", 2, i).sum() * V for i in range(len(da.times))]
    assert np.allclose(np.diff(prod), burned, rtol=1e-9, atol=0)
